// The spline shear law in calibration (docs/calibration.md §5.2): a synthetic recovery of the knot
// values from a continuum with known ones (their dR/dp are checked in
// VirtualTests.ContinuumSensitivitiesMatchCentralDifferences).
#include <gtest/gtest.h>

#include <cmath>

#include "calibration/fit.h"
#include "calibration/virtual_tests.h"
#include "models/fem/fem_material.h"
#include "models/scene/scene.h"
#include "tests/support/fit_recovery.h"

namespace wl {
namespace {

// The hanging-cloth fabric's first guess with a softening spline (the knots 0.1 … 0.4 rad).
FemMaterial softening(const Scene& patch) {
  FemMaterial m = default_fem_material(patch);
  m.shear_knots_rad = {0.1, 0.2, 0.3, 0.4};
  const double k[4] = {0.9, 0.7, 0.35, 0.2};
  for (int i = 0; i < 4; ++i) m.shear_knot_N_per_m[i] = k[i] * m.shear_N_per_m;
  return m;
}

TEST(ShearSplineCalibration, FitRecoversKnownKnotValues) {
  // The continuum's own picture-frame curve, fitted by the same law from the linear law (every knot
  // at k_sh, k_sh 30 % off): the seven parameters come back.
  const Scene patch = test::hanging_wind_patch(7);
  const FemMaterial truth = softening(patch);
  const std::vector<FitCurve> curves = test::synthetic_curves(
      patch, truth,
      {{TestKind::shear, {0.03, 0.06, 0.1, 0.14, 0.18, 0.22, 0.26, 0.3, 0.34, 0.38, 0.45, 0.55, 0.65, 0.8}}});
  FemMaterial start = truth;
  start.shear_N_per_m *= 1.3;
  for (int i = 0; i < 4; ++i) start.shear_knot_N_per_m[i] = start.shear_N_per_m;
  start.shear_lock_angle_rad *= 0.9;
  start.shear_lock_exponent *= 1.2;
  test::expect_fit_recovers(patch, curves, truth, start, 7, 1e-5);
}

}  // namespace
}  // namespace wl
