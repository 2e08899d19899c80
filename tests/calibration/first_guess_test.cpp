// The continuum fit's first guess from the yarn-level curves (calibration/first_guess.h,
// calibration/stretch_law_guess.h, docs/calibration.md §8), on curves written by hand
// from the stretch law R_warp = k_u ε + (q_u + q_a)ε³, R_weft = k_v ε + (q_v + q_a)ε³,
// R_biaxial = (k_u + k_v + 2k_c)ε + (q_u + q_v + 16q_a)ε³ (docs/models.md §6.3.1).
#include <gtest/gtest.h>

#include <cmath>

#include "calibration/first_guess.h"
#include "calibration/stretch_law_guess.h"
#include "tests/support/test_scenes.h"

namespace wl {
namespace {

// k_u = 100, k_v = 80, k_c = 10 N/m; q_u = 1000, q_v = 2000, q_a = 500 N/m.
constexpr double kU = 100, kV = 80, kC = 10, qU = 1000, qV = 2000, qA = 500;

FitCurve curve(TestKind kind, double linear, double cubic, std::vector<double> ladder = {0.01, 0.02, 0.05}) {
  FitCurve c{{kind, ladder, false}, {}};
  for (double e : ladder) c.target.push_back(linear * e + cubic * e * e * e);
  return c;
}

std::vector<FitCurve> stretch_curves() {
  return {curve(TestKind::uniaxial_warp, kU, qU + qA), curve(TestKind::uniaxial_weft, kV, qV + qA),
          curve(TestKind::biaxial, kU + kV + 2 * kC, qU + qV + 16 * qA)};
}

TEST(FirstGuess, CubicPartOfAnExactCurveIsItsCubicCoefficient) {
  EXPECT_NEAR(cubic_part(curve(TestKind::uniaxial_warp, 100.0, 5000.0)), 5000.0, 1e-8 * 5000.0);
  EXPECT_NEAR(cubic_part(curve(TestKind::uniaxial_warp, 100.0, 0.0)), 0.0, 1e-8);
}

TEST(FirstGuess, CubicPartIsZeroWhenTheLadderHasOneStrain) {
  // R = kε + cε³ at one strain cannot tell k from c: the normal equations are singular.
  EXPECT_EQ(cubic_part(curve(TestKind::uniaxial_warp, 100.0, 5000.0, {0.02, 0.02})), 0.0);
}

TEST(FirstGuess, CouplingIsHalfTheBiaxialExcessOverTheUniaxialSecants) {
  FemMaterial m;
  m.warp_stretch_N_per_m = kU;
  m.weft_stretch_N_per_m = kV;
  // Linear curves (no cubic part): the secants at the first load are k exactly.
  const std::vector<FitCurve> linear{curve(TestKind::uniaxial_warp, kU, 0), curve(TestKind::uniaxial_weft, kV, 0),
                                     curve(TestKind::biaxial, kU + kV + 2 * kC, 0)};
  stretch_law_first_guess(linear, true, false, m);
  EXPECT_NEAR(m.stretch_coupling_N_per_m, kC, 1e-9 * kC);
  EXPECT_EQ(m.warp_stretch_quartic_N_per_m, 0.0);  // stiffening not asked for
}

TEST(FirstGuess, CouplingIsKeptAboveTwoPercentOfTheGeometricMean) {
  FemMaterial m;
  m.warp_stretch_N_per_m = kU;
  m.weft_stretch_N_per_m = kV;
  const std::vector<FitCurve> uncoupled{curve(TestKind::uniaxial_warp, kU, 0), curve(TestKind::uniaxial_weft, kV, 0),
                                        curve(TestKind::biaxial, kU + kV, 0)};
  stretch_law_first_guess(uncoupled, true, false, m);
  EXPECT_NEAR(m.stretch_coupling_N_per_m, 0.02 * std::sqrt(kU * kV), 1e-12 * kU);
}

TEST(FirstGuess, StiffeningRecoversTheArealQuarticFromTheBiaxialExcess) {
  FemMaterial m;
  m.warp_stretch_N_per_m = kU;
  m.weft_stretch_N_per_m = kV;
  stretch_law_first_guess(stretch_curves(), false, true, m);
  // (c_b − c_u − c_v)/14 = (q_u + q_v + 16q_a − q_u − q_a − q_v − q_a)/14 = q_a.
  EXPECT_NEAR(m.areal_stretch_quartic_N_per_m, qA, 1e-6 * qA);
  // Each direction starts at its curve's cubic part, q + q_a (above 1 % of k / ε_max² = 400 and 320).
  EXPECT_NEAR(m.warp_stretch_quartic_N_per_m, qU + qA, 1e-6 * qU);
  EXPECT_NEAR(m.weft_stretch_quartic_N_per_m, qV + qA, 1e-6 * qV);
  EXPECT_EQ(m.stretch_coupling_N_per_m, 0.0);  // coupling not asked for
}

TEST(FirstGuess, WovenStartsAtTheScenesValuesWithTheAskedExtras) {
  const Scene scene = parse_scene(test::hanging_cloth_toml(9, 0.01), "first_guess.toml");
  const FemMaterial scene_values = fem_material(scene);
  FirstGuessOptions o;
  o.diagonal_bending = true;
  o.shear_knots_rad = {0.1, 0.3};
  const FemMaterial m = continuum_first_guess(scene, scene, {}, o);
  EXPECT_EQ(m.warp_stretch_N_per_m, scene_values.warp_stretch_N_per_m);
  EXPECT_EQ(m.shear_N_per_m, scene_values.shear_N_per_m);
  EXPECT_EQ(m.diagonal_bending_N_m, 0.5 * (scene_values.warp_bending_N_m + scene_values.weft_bending_N_m));
  ASSERT_EQ(m.shear_knots_rad, o.shear_knots_rad);
  EXPECT_EQ(m.shear_knot_N_per_m[0], scene_values.shear_N_per_m);  // the spline starts linear
  EXPECT_EQ(m.shear_knot_N_per_m[1], scene_values.shear_N_per_m);
}

TEST(FirstGuess, KnitStiffnessesStartAtTheirTestsSecants) {
  const Scene knit = parse_scene(test::hanging_knit_toml(6, 6), "knit.toml");
  const FemMaterial defaults = default_fem_material(knit);
  // The biaxial secant is shared between warp and weft; a uniaxial weft curve overrides the weft.
  const std::vector<FitCurve> curves{curve(TestKind::biaxial, 60.0, 0.0), curve(TestKind::uniaxial_weft, 20.0, 0.0),
                                     curve(TestKind::bending_warp, 3e-6, 0.0)};
  const FemMaterial m = knit_first_guess(knit, curves);
  EXPECT_NEAR(m.warp_stretch_N_per_m, 30.0, 1e-12 * 30.0);
  EXPECT_NEAR(m.weft_stretch_N_per_m, 20.0, 1e-12 * 20.0);
  EXPECT_NEAR(m.warp_bending_N_m, 3e-6, 1e-12 * 3e-6);
  EXPECT_EQ(m.shear_N_per_m, defaults.shear_N_per_m);  // no shear test: default_fem_material's
  EXPECT_EQ(m.weft_bending_N_m, defaults.weft_bending_N_m);
}

}  // namespace
}  // namespace wl
