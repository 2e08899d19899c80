// Virtual material tests: analytic limits of both models and the implicit-
// function-theorem sensitivities of the continuum against central differences.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "calibration/fit.h"
#include "calibration/virtual_tests.h"
#include "models/fem/fem_material.h"
#include "models/scene/scene.h"

namespace wl {
namespace {

Scene hanging_wind() { return load_scene(WEAVELAB_SOURCE_DIR "/experiments/scenes/hanging_wind.toml"); }

TEST(VirtualTests, YarnUniaxialWarpOfStraightYarnsIsTheirStretchStiffness) {
  // Straight, uncrimped yarns with sliding frozen: only the warps stretch, each by ε over (N−1)L,
  // so W = Σ_j ½k_s,j (N−1)L ε² and R = dW/dε / ((N−1)L)² = Σ_j k_s,j ε / ((N−1)L).
  const Scene scene = hanging_wind();
  const int n = 7;
  const Scene patch = material_test_scene(scene, n);
  const double L = scene.spacing_m, area = std::numbers::pi * scene.radius_m * scene.radius_m;
  double sum_ks = 0;
  for (int j = 0; j < n; ++j) sum_ks += scene.warp_type(j).stretch_modulus_Pa * area;
  const TestSpec test{TestKind::uniaxial_warp, {0.005, 0.01, 0.02}};
  const ResponseCurve c = run_yarn_test(patch, test);
  ASSERT_TRUE(c.complete) << c.message;
  for (const ResponsePoint& p : c.points)
    EXPECT_NEAR(p.response, sum_ks * p.load / ((n - 1) * L), 1e-9 * sum_ks / L) << "strain " << p.load;
}

TEST(VirtualTests, FemUniaxialAndBiaxialResponsesAreTheMembraneStiffness) {
  const Scene patch = material_test_scene(hanging_wind(), 7);
  FemMaterial m = default_fem_material(patch);
  m.warp_stretch_N_per_m = 300.0;
  m.weft_stretch_N_per_m = 120.0;
  for (auto [kind, k] : {std::pair{TestKind::uniaxial_warp, 300.0}, std::pair{TestKind::uniaxial_weft, 120.0},
                         std::pair{TestKind::biaxial, 420.0}}) {
    const ResponseCurve c = run_fem_test(patch, m, {kind, {0.004, 0.012}});
    ASSERT_TRUE(c.complete) << c.message;
    for (const ResponsePoint& p : c.points) EXPECT_NEAR(p.response, k * p.load, 1e-9 * k) << test_name(kind);
  }
}

TEST(VirtualTests, FemBendingAtSmallCurvatureIsTheBendingStiffness) {
  // On the grid mesh a cylinder of curvature κ bends only the hinges across edges along the
  // cylinder's axis, each by κL at ½k per unit coefficient (docs/models.md §6.5); the
  // N−2 interior columns of them give W = ½kκ²L²(N−2)(N−1), so R = dW/dκ/((N−1)L)² =
  // kκ(N−2)/(N−1), up to the membrane work of the chord-vs-arc strain (κL)²/24 (1e-5 here).
  const int n = 9;
  const Scene patch = material_test_scene(hanging_wind(), n);
  FemMaterial m = default_fem_material(patch);
  for (TestKind kind : {TestKind::bending_warp, TestKind::bending_weft}) {
    const double k = kind == TestKind::bending_warp ? m.warp_bending_N_m : m.weft_bending_N_m;
    const ResponseCurve c = run_fem_test(patch, m, {kind, {1.0}});
    ASSERT_TRUE(c.complete) << c.message;
    EXPECT_NEAR(c.points[0].response, k * (n - 2.0) / (n - 1.0), 1e-4 * k) << test_name(kind);
  }
}

TEST(VirtualTests, ContinuumSensitivitiesMatchCentralDifferences) {
  // Shear at 0.2 and 0.4 rad: below and past the lock angle (0.52 rad here... and its stiffening).
  // Every test of the wider battery too, with the diagonal stiffness on (0.3 of the mean, so that
  // the 45° hinges differ from the law without it); then the bending tests with grid-line bending;
  // then the shear test with the spline shear law, softening over its four knots (docs/models.md §6.4.1);
  // then the stretch tests with the stretch's coupling and quartic stiffening (§6.3.1).
  for (const int law : {0, 1, 2, 3}) {
    const bool grid_lines = law == 1, spline = law == 2, stretch = law == 3;
    Scene patch = material_test_scene(hanging_wind(), 7);
    patch.fem.grid_line_bending = grid_lines;
    FemMaterial m = default_fem_material(patch);
    if (law == 0) m.diagonal_bending_N_m = 0.15 * (m.warp_bending_N_m + m.weft_bending_N_m);
    if (spline) {
      m.shear_knots_rad = {0.1, 0.2, 0.3, 0.35};
      m.shear_knot_N_per_m = {0.9 * m.shear_N_per_m, 0.7 * m.shear_N_per_m, 0.35 * m.shear_N_per_m,
                              0.2 * m.shear_N_per_m};
    }
    if (stretch) {
      m.stretch_coupling_N_per_m = 0.3 * std::sqrt(m.warp_stretch_N_per_m * m.weft_stretch_N_per_m);
      m.warp_stretch_quartic_N_per_m = 500 * m.warp_stretch_N_per_m;  // tangent k + 3qε²: 1.6 k at 2 %
      m.weft_stretch_quartic_N_per_m = 300 * m.weft_stretch_N_per_m;
      m.areal_stretch_quartic_N_per_m = 100 * m.weft_stretch_N_per_m;
    }
    for (const std::string& name : test_names()) {
      const TestKind kind = test_kind(name);
      if (grid_lines && !clamps_rotation(kind)) continue;
      if (spline && kind != TestKind::shear) continue;
      if (stretch && kind != TestKind::uniaxial_warp && kind != TestKind::uniaxial_weft && kind != TestKind::biaxial)
        continue;
      // (the spline law at 0.4 and 0.55 rad, beyond its last knot, where every knot value acts)
      const std::vector<double> ladder = default_ladder(kind, 7, patch.spacing_m);
      const TestSpec test{kind, {ladder[spline ? 7 : 3], ladder[spline ? 10 : 7]}};
      const std::vector<std::string> keys = informed_parameters(kind, m);
      if (stretch) {
        ASSERT_EQ(keys.size(), kind == TestKind::biaxial ? 6u : 3u);
      }
      std::vector<std::string> prefixed;
      for (const auto& k : keys) prefixed.push_back("fem." + k);
      const ResponseCurve c = run_fem_test(patch, m, test, prefixed);
      ASSERT_TRUE(c.complete) << c.message;
      for (size_t k = 0; k < keys.size(); ++k) {
        FemMaterial hi = m, lo = m;
        const double p = material_value(hi, keys[k]), h = 1e-4 * p;
        material_value(hi, keys[k]) = p + h;
        material_value(lo, keys[k]) = p - h;
        const ResponseCurve ch = run_fem_test(patch, hi, test), cl = run_fem_test(patch, lo, test);
        for (size_t i = 0; i < c.points.size(); ++i) {
          const double fd = (ch.points[i].response - cl.points[i].response) / (2 * h);
          const double exact = c.sensitivities[i][k];
          EXPECT_NE(exact, 0.0) << name << " " << keys[k];
          EXPECT_NEAR(exact, fd, 1e-5 * std::abs(fd) + 1e-9 * std::abs(c.points[i].response) / p)
              << name << " " << keys[k] << " at " << c.points[i].load << (grid_lines ? " (grid lines)" : "")
              << (spline ? " (spline shear)" : "") << (stretch ? " (coupled stretch)" : "");
        }
      }
    }
  }
}

TEST(VirtualTests, APatchOfASceneWithObstaclesTestsTheFabricAlone) {
  // The cantilever's strip lies on a ledge; its fabric's patch is flat at z = 0, where the ledge's
  // top is, and must not carry the ledge into the tests.
  const Scene scene = load_scene(WEAVELAB_SOURCE_DIR "/experiments/scenes/cantilever_ledge.toml");
  ASSERT_FALSE(scene.obstacles.empty());
  const Scene patch = material_test_scene(scene, 7);
  EXPECT_TRUE(patch.obstacles.empty());
  const ResponseCurve c = run_yarn_test(patch, {TestKind::bending_warp, {10.0}});
  EXPECT_TRUE(c.complete) << c.message;
}

TEST(VirtualTests, PatchSmallerThanThePatternIsRejected) {
  Scene s = hanging_wind();
  s.pattern.kind = Pattern::Kind::satin;  // 5-harness: needs 5 + 4
  EXPECT_THROW(material_test_scene(s, 8), std::invalid_argument);
  EXPECT_NO_THROW(material_test_scene(s, 9));
}

TEST(VirtualTests, YarnTestsRunAtOnceGiveTheCurvesOfOneAfterAnother) {
  // Three tests of a patch on two threads: each curve bitwise that of run_yarn_test alone.
  const Scene patch = material_test_scene(hanging_wind(), 7);
  const std::vector<TestSpec> tests{
      {TestKind::uniaxial_warp, {0.005, 0.01}}, {TestKind::shear, {0.05, 0.1}}, {TestKind::bending_weft, {2.0, 4.0}}};
  std::vector<int> reported;
  const std::vector<ResponseCurve> at_once =
      run_yarn_tests(patch, tests, 2, [&](int k, const ResponseCurve&) { reported.push_back(k); });
  ASSERT_EQ(at_once.size(), tests.size());
  std::sort(reported.begin(), reported.end());
  EXPECT_EQ(reported, (std::vector<int>{0, 1, 2}));
  for (size_t k = 0; k < tests.size(); ++k) {
    const ResponseCurve alone = run_yarn_test(patch, tests[k]);
    ASSERT_TRUE(alone.complete) << alone.message;
    ASSERT_EQ(at_once[k].points.size(), alone.points.size());
    for (size_t i = 0; i < alone.points.size(); ++i) {
      EXPECT_NE(alone.points[i].response, 0.0);
      EXPECT_EQ(at_once[k].points[i].response, alone.points[i].response) << test_name(tests[k]) << " rung " << i;
    }
  }
}

// A stop request ends a test at the Newton iteration it is asked before: here
// the first of the second rung, so the first rung's point stands as without it.
TEST(VirtualTests, AStopRequestEndsATestAtItsNewtonIteration) {
  const Scene patch = material_test_scene(hanging_wind(), 7);
  const TestSpec shear{TestKind::shear, {0.05, 0.1}};
  const ResponseCurve whole = run_yarn_test(patch, shear);
  ASSERT_TRUE(whole.complete) << whole.message;
  ASSERT_EQ(whole.points.size(), 2u);
  const int first_rung = whole.points[0].newton_iterations;
  ASSERT_GT(first_rung, 0);
  int asked = 0;
  EquilibriumOptions stop_in_second_rung;
  stop_in_second_rung.stop_requested = [&] { return ++asked > first_rung; };
  const ResponseCurve stopped = run_yarn_tests(patch, {shear}, 1, {}, nullptr, stop_in_second_rung).front();
  EXPECT_TRUE(stopped.stopped);
  EXPECT_FALSE(stopped.complete);
  EXPECT_EQ(asked, first_rung + 1);
  ASSERT_EQ(stopped.points.size(), 1u) << stopped.message;
  EXPECT_EQ(stopped.points[0].response, whole.points[0].response);
  EXPECT_NE(stopped.message.find("stopped after 0 Newton iterations"), std::string::npos) << stopped.message;
}

}  // namespace
}  // namespace wl
