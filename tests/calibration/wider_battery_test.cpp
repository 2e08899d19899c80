// The wider battery of virtual tests (docs/calibration.md §2.1): bending along
// both diagonals, the combined loads and the rigidly rotated patch, each against
// an analytic limit, on the continuum and on the yarn level.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "calibration/fit.h"
#include "calibration/virtual_tests.h"
#include "models/fem/fem_material.h"
#include "models/scene/scene.h"
#include "tests/support/fit_recovery.h"

namespace wl {
namespace {

Scene hanging_wind() { return load_scene(WEAVELAB_SOURCE_DIR "/experiments/scenes/hanging_wind.toml"); }

// R of a test at one load.
double response(const Scene& patch, const FemMaterial& m, TestKind kind, double load) {
  const ResponseCurve c = run_fem_test(patch, m, {kind, {load}});
  EXPECT_TRUE(c.complete) << c.message;
  return c.complete ? c.points[0].response : NAN;
}

TEST(WiderBattery, NamesParseWithAndWithoutRotation) {
  for (const std::string& name : test_names()) {
    EXPECT_EQ(test_name(test_spec(name)), name);
    const TestSpec r = test_spec("rotated-" + name);
    EXPECT_TRUE(r.rotated);
    EXPECT_EQ(test_name(r), "rotated-" + name);
  }
  EXPECT_EQ(default_test_names().size(), 6u);
  EXPECT_THROW(test_spec("rotated-twist"), std::invalid_argument);
  EXPECT_NEAR((test_rotation() * test_rotation().transpose() - Mat3::Identity()).norm(), 0.0, 1e-15);
  EXPECT_NEAR(std::acos(0.5 * (test_rotation().trace() - 1)), 2.0, 1e-12);
}

TEST(WiderBattery, PatchMapDerivativesMatchCentralDifferences) {
  for (const std::string& name : test_names())
    for (bool rotated : {false, true}) {
      const TestKind kind = test_kind(name);
      const PatchMap map{kind, 7, 0.004, 0.0, rotated};
      const double lambda = default_ladder(kind, 7, 0.004)[5], h = 1e-6 * lambda;
      for (auto [i, j] : {std::pair{0, 0}, std::pair{6, 2}, std::pair{3, 5}}) {
        const Vec3 fd = (map.position(i, j, lambda + h) - map.position(i, j, lambda - h)) / (2 * h);
        EXPECT_NEAR((map.derivative(i, j, lambda) - fd).norm(), 0.0, 1e-7 * fd.norm() + 1e-12) << name;
      }
    }
}

TEST(WiderBattery, FemDiagonalBendingIsTheSumOverItsHinges) {
  // On the grid mesh (diagonals (i,j)–(i+1,j+1)) the cylinder z = ½κ(b·X)² bending along
  // b = (1,1)/√2 bends every edge along u and v by κL and every diagonal by κL/√2; along
  // b = (1,−1)/√2 only the diagonals, by κL/√2 (the linear interpolant of the quadratic
  // on each triangle, docs/calibration.md §2.1). With the hinge coefficients k_e‖ē‖²/(Ā₁+Ā₂)
  // (k on u and v edges, 2k_d on diagonals) and (N−1)(N−2) interior edges along u and as
  // many along v, (N−1)² diagonals: W = ½κ²L²[(N−1)(N−2)(k_warp + k_weft) + (N−1)²k_d], so
  //   R_diagonal = κ[(N−2)/(N−1)·(k_warp + k_weft) + k_d],  R_antidiagonal = κ·k_d,
  // up to the membrane work of the chords (relative (κL)², 1e-5 here).
  const int n = 9;
  const Scene patch = material_test_scene(hanging_wind(), n);
  FemMaterial m = default_fem_material(patch);
  m.warp_bending_N_m *= 1.4;  // warp and weft differ
  for (double kd : {0.0, 0.2 * m.weft_bending_N_m}) {
    m.diagonal_bending_N_m = kd;
    const double k_d = kd > 0 ? kd : 0.5 * (m.warp_bending_N_m + m.weft_bending_N_m);
    const double kappa = 1.0;
    const ResponseCurve d = run_fem_test(patch, m, {TestKind::bending_diagonal, {kappa}});
    const ResponseCurve a = run_fem_test(patch, m, {TestKind::bending_antidiagonal, {kappa}});
    ASSERT_TRUE(d.complete && a.complete) << d.message << a.message;
    const double rd = kappa * ((n - 2.0) / (n - 1.0) * (m.warp_bending_N_m + m.weft_bending_N_m) + k_d);
    EXPECT_NEAR(d.points[0].response, rd, 1e-4 * rd) << "k_d " << kd;
    EXPECT_NEAR(a.points[0].response, kappa * k_d, 1e-4 * kappa * k_d) << "k_d " << kd;
  }
}

TEST(WiderBattery, FemGridLinesBendAlongTheDiagonalsLikeAPlateWithoutTwist) {
  // With [fem] grid_line_bending the lines along u and v bend like yarns: a cylinder of curvature κ
  // about v turns each warp line by κL at its N−2 interior vertices, so R = k_warp κ(N−2)/(N−1) as
  // with the hinges; one along either diagonal turns each line by its normal curvature κ/2 only,
  // V = k w (κL/2)²/(2L) per vertex over lines of total width (N−1)L, so
  //   R_diagonal = R_antidiagonal = ¼κ(k_warp + k_weft)(N−2)/(N−1),
  // a plate without twist stiffness (up to the chords' membrane work, 1e-4 here).
  const int n = 9;
  Scene patch = material_test_scene(hanging_wind(), n);
  patch.fem.grid_line_bending = true;
  FemMaterial m = default_fem_material(patch);
  m.warp_bending_N_m *= 1.4;
  const double kappa = 1.0, f = (n - 2.0) / (n - 1.0);
  const double kw = m.warp_bending_N_m, kf = m.weft_bending_N_m;
  EXPECT_NEAR(response(patch, m, TestKind::bending_warp, kappa), kw * kappa * f, 1e-4 * kw * kappa);
  EXPECT_NEAR(response(patch, m, TestKind::bending_weft, kappa), kf * kappa * f, 1e-4 * kf * kappa);
  for (TestKind kind : {TestKind::bending_diagonal, TestKind::bending_antidiagonal})
    EXPECT_NEAR(response(patch, m, kind, kappa), 0.25 * kappa * (kw + kf) * f, 1e-4 * kappa * (kw + kf))
        << test_name(kind);
}

TEST(WiderBattery, FemCombinedLoadsAreTheSumOfTheirPartsAtSmallLoad) {
  // The continuum has no coupling between stretch and shear or stretch and bending, so at
  // small load W(λ) = W_stretch(λ) + W_other(cλ) and R(λ) = R_uniaxial-warp(λ) + c·R_other(cλ),
  // c = 10 rad per unit strain (shear) or 50/((N−1)L) per unit strain (curvature), up to
  // relative O(λ) terms of the geometry (1e-5 here).
  const int n = 7;
  const Scene patch = material_test_scene(hanging_wind(), n);
  const FemMaterial m = default_fem_material(patch);
  const double lambda = 1e-5;
  const double c_bend = 50.0 / ((n - 1) * patch.spacing_m);
  const double ss = response(patch, m, TestKind::stretch_shear, lambda);
  const double ss_parts =
      response(patch, m, TestKind::uniaxial_warp, lambda) + 10.0 * response(patch, m, TestKind::shear, 10.0 * lambda);
  EXPECT_NEAR(ss, ss_parts, 1e-4 * std::abs(ss_parts));
  const double sb = response(patch, m, TestKind::stretch_bending, lambda);
  const double sb_parts = response(patch, m, TestKind::uniaxial_warp, lambda) +
                          c_bend * response(patch, m, TestKind::bending_warp, c_bend * lambda);
  EXPECT_NEAR(sb, sb_parts, 1e-4 * std::abs(sb_parts));
  // Both parts weigh: the stretch part alone misses by a hundred times the tolerance.
  EXPECT_GT(std::abs(ss - response(patch, m, TestKind::uniaxial_warp, lambda)), 1e-2 * std::abs(ss));
  EXPECT_GT(std::abs(sb - response(patch, m, TestKind::uniaxial_warp, lambda)), 1e-2 * std::abs(sb));
}

TEST(WiderBattery, RotatedPatchAnswersAsTheUnrotatedOnBothModels) {
  // Both models are objective: the same load on the patch turned by 2 rad about (1,2,3)/√14
  // gives the same response, to the equilibrium tolerance (10⁻¹⁰ of the reactions).
  const Scene patch = material_test_scene(hanging_wind(), 7);
  FemMaterial m = default_fem_material(patch);
  m.diagonal_bending_N_m = 0.3 * m.warp_bending_N_m;
  for (TestKind kind : {TestKind::shear, TestKind::bending_diagonal, TestKind::stretch_bending}) {
    const std::vector<double> full = default_ladder(kind, 7, patch.spacing_m);
    const std::vector<double> ladder{full[2], full.back()};
    for (const bool yarn : {false, true}) {
      const ResponseCurve plain = yarn ? run_yarn_test(patch, {kind, ladder}) : run_fem_test(patch, m, {kind, ladder});
      const ResponseCurve turned =
          yarn ? run_yarn_test(patch, {kind, ladder, true}) : run_fem_test(patch, m, {kind, ladder, true});
      ASSERT_TRUE(plain.complete && turned.complete) << plain.message << turned.message;
      for (size_t i = 0; i < ladder.size(); ++i) {
        EXPECT_GT(std::abs(plain.points[i].response), 0.0);
        EXPECT_NEAR(turned.points[i].response, plain.points[i].response, 1e-8 * std::abs(plain.points[i].response))
            << test_name(kind) << (yarn ? " yarn" : " fem") << " at " << ladder[i];
      }
    }
  }
}

TEST(WiderBattery, YarnLevelRunsEveryNewTestToTheTopOfItsLadder) {
  // The yarn level's response grows with the load on every new test (a stiffening or
  // softening fabric, but never one that gives way within these ladders).
  const Scene patch = material_test_scene(hanging_wind(), 7);
  for (TestKind kind : {TestKind::bending_diagonal, TestKind::bending_antidiagonal, TestKind::stretch_shear,
                        TestKind::stretch_bending}) {
    const std::vector<double> full = default_ladder(kind, 7, patch.spacing_m);
    const ResponseCurve c = run_yarn_test(patch, {kind, {full[1], full[4], full.back()}});
    ASSERT_TRUE(c.complete) << c.message;
    EXPECT_GT(c.points[0].response, 0.0) << test_name(kind);
    for (size_t i = 1; i < c.points.size(); ++i)
      EXPECT_GT(c.points[i].response, c.points[i - 1].response) << test_name(kind);
  }
}

TEST(WiderBattery, YarnLevelBendsAlongTheDiagonalsLikeAPlateWithoutTwist) {
  // The yarns bend by their normal curvature κ/2 along a diagonal and nothing resists the twist, so
  // at small curvature R_diagonal = R_antidiagonal = ¼(R_warp + R_weft) (docs/calibration.md §5.1);
  // the hinge continuum is 5.8× and 2.0× stiffer there (README, "Wider battery").
  const int n = 9;
  const Scene patch = material_test_scene(hanging_wind(), n);
  const double kappa = default_ladder(TestKind::bending_warp, n, patch.spacing_m)[0];
  auto yarn = [&](TestKind kind) {
    const ResponseCurve c = run_yarn_test(patch, {kind, {kappa}});
    EXPECT_TRUE(c.complete) << c.message;
    return c.complete ? c.points[0].response : NAN;
  };
  const double plate = 0.25 * (yarn(TestKind::bending_warp) + yarn(TestKind::bending_weft));
  for (TestKind kind : {TestKind::bending_diagonal, TestKind::bending_antidiagonal}) {
    const double r = yarn(kind);
    std::printf("[ battery ] %s: %.6g, plate without twist %.6g, ratio %.4f\n", test_name(kind).c_str(), r, plate,
                r / plate);
    EXPECT_NEAR(r / plate, 1.0, 0.01) << test_name(kind);  // measured 0.9989
  }
}

TEST(WiderBattery, FitRecoversTheDiagonalBendingStiffness) {
  // Synthetic recovery: the continuum's own bending curves (warp, weft and both diagonals)
  // from a truth with its own diagonal stiffness, fitted from a start off by ×3 in each.
  const Scene patch = material_test_scene(hanging_wind(), 7);
  FemMaterial truth = default_fem_material(patch);
  truth.warp_bending_N_m *= 0.7;
  truth.weft_bending_N_m *= 1.5;
  truth.diagonal_bending_N_m = 0.25 * truth.weft_bending_N_m;
  std::vector<TestSpec> tests;
  for (TestKind kind :
       {TestKind::bending_warp, TestKind::bending_weft, TestKind::bending_diagonal, TestKind::bending_antidiagonal}) {
    const std::vector<double> full = default_ladder(kind, 7, patch.spacing_m);
    tests.push_back({kind, {full[1], full[4], full.back()}});
  }
  const std::vector<FitCurve> curves = test::synthetic_curves(patch, truth, tests);
  FemMaterial start = truth;
  start.warp_bending_N_m *= 3.0;
  start.weft_bending_N_m /= 3.0;
  start.diagonal_bending_N_m *= 3.0;
  test::expect_fit_recovers(patch, curves, truth, start, 3, 1e-6);
}

TEST(WiderBattery, FitRecoversTheGridLineBendingStiffnesses) {
  // Synthetic recovery of both stiffnesses of the grid-line law from its own warp, weft and
  // diagonal curves (its dR/dp are checked in VirtualTests.ContinuumSensitivitiesMatchCentralDifferences).
  Scene patch = material_test_scene(hanging_wind(), 7);
  patch.fem.grid_line_bending = true;
  FemMaterial truth = default_fem_material(patch);
  truth.warp_bending_N_m *= 0.7;
  truth.weft_bending_N_m *= 1.5;
  const std::vector<std::string> keys{"warp_bending_N_m", "weft_bending_N_m"};
  const ContinuumTest continuum = [&](const FemMaterial& m, const TestSpec& t, const std::vector<std::string>& ks) {
    return run_fem_test(patch, m, t, ks);
  };
  std::vector<FitCurve> curves;
  for (TestKind kind : {TestKind::bending_warp, TestKind::bending_weft, TestKind::bending_diagonal}) {
    const std::vector<double> full = default_ladder(kind, 7, patch.spacing_m);
    FitCurve fc{{kind, {full[1], full.back()}}, {}};
    for (const ResponsePoint& pt : run_fem_test(patch, truth, fc.test).points) fc.target.push_back(pt.response);
    curves.push_back(fc);
  }
  FemMaterial start = truth;
  start.warp_bending_N_m *= 3.0;
  start.weft_bending_N_m /= 3.0;
  FitOptions opt;
  opt.starts = 1;
  const FitResult r = fit_continuum(curves, start, continuum, opt);
  ASSERT_TRUE(r.converged) << r.message;
  FemMaterial fitted = r.material;
  for (const std::string& key : keys)
    EXPECT_NEAR(material_value(fitted, key) / material_value(truth, key), 1.0, 1e-6) << key;
}

}  // namespace
}  // namespace wl
