// The coupled, stiffening stretch law in the virtual tests (docs/models.md §6.3.1,
// docs/calibration.md §8): the homogeneous patch's responses against their hand-derived
// values, and the fit recovering known coupling and stiffening from the law's own curves
// (their dR/dp are checked in VirtualTests.ContinuumSensitivitiesMatchCentralDifferences).
#include <gtest/gtest.h>

#include "calibration/virtual_tests.h"
#include "models/fem/fem_material.h"
#include "tests/support/fit_recovery.h"

namespace wl {
namespace {

// k_u = 300, k_v = 120, k_c = 40 (below √(k_u k_v) = 190), q_u = 2·10⁴, q_v = 5·10⁴, q_a = 10⁴ N/m.
FemMaterial coupled(const Scene& patch) {
  FemMaterial m = default_fem_material(patch);
  m.warp_stretch_N_per_m = 300.0;
  m.weft_stretch_N_per_m = 120.0;
  m.stretch_coupling_N_per_m = 40.0;
  m.warp_stretch_quartic_N_per_m = 2e4;
  m.weft_stretch_quartic_N_per_m = 5e4;
  m.areal_stretch_quartic_N_per_m = 1e4;
  return m;
}

TEST(StretchLawCalibration, BiaxialExceedsTheUniaxialSumByTwiceTheCoupling) {
  // A homogeneous patch under the affine ring answers R = dψ/dλ (docs/calibration.md §2):
  // uniaxial warp k_u ε + (q_u + q_a)ε³, weft k_v ε + (q_v + q_a)ε³, biaxial (k_u + k_v + 2k_c)ε +
  // (q_u + q_v + 16q_a)ε³ (ψ's ¼q_a(2ε)⁴), so biaxial − warp − weft = 2k_c ε + 14q_a ε³ = 80ε + 1.4·10⁵ε³.
  const Scene patch = test::hanging_wind_patch(7);
  const FemMaterial m = coupled(patch);
  const std::vector<double> ladder{0.01, 0.04};
  const ResponseCurve u = run_fem_test(patch, m, {TestKind::uniaxial_warp, ladder}),
                      v = run_fem_test(patch, m, {TestKind::uniaxial_weft, ladder}),
                      b = run_fem_test(patch, m, {TestKind::biaxial, ladder});
  ASSERT_TRUE(u.complete && v.complete && b.complete) << u.message << v.message << b.message;
  for (size_t i = 0; i < ladder.size(); ++i) {
    const double e = ladder[i], e3 = e * e * e;
    EXPECT_NEAR(u.points[i].response, 300.0 * e + 3e4 * e3, 1e-9 * 300.0);
    EXPECT_NEAR(v.points[i].response, 120.0 * e + 6e4 * e3, 1e-9 * 300.0);
    EXPECT_NEAR(b.points[i].response, 500.0 * e + 2.3e5 * e3, 1e-9 * 300.0);
    EXPECT_NEAR(b.points[i].response - u.points[i].response - v.points[i].response, 80.0 * e + 1.4e5 * e3,
                1e-9 * 300.0);
  }
}

TEST(StretchLawCalibration, FitRecoversKnownCouplingAndStiffening) {
  // The law's own three stretch curves, fitted from the linear stiffnesses 20 % off and the
  // extras at a fifth or five times their values: the six parameters come back.
  const Scene patch = test::hanging_wind_patch(7);
  const FemMaterial truth = coupled(patch);
  const std::vector<double> ladder{0.02, 0.04, 0.06, 0.08, 0.1};
  const std::vector<FitCurve> curves = test::synthetic_curves(
      patch, truth,
      {{TestKind::uniaxial_warp, ladder}, {TestKind::uniaxial_weft, ladder}, {TestKind::biaxial, ladder}});
  FemMaterial start = truth;
  start.warp_stretch_N_per_m *= 1.2;
  start.weft_stretch_N_per_m *= 0.8;
  start.stretch_coupling_N_per_m *= 0.2;
  start.warp_stretch_quartic_N_per_m *= 5;
  start.weft_stretch_quartic_N_per_m *= 0.2;
  start.areal_stretch_quartic_N_per_m *= 5;
  test::expect_fit_recovers(patch, curves, truth, start, 6, 1e-5);
}

}  // namespace
}  // namespace wl
