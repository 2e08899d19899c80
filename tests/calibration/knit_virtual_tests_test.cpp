// Virtual material tests on a knit patch (docs/calibration.md §8): the test map that
// carries a node's depth through the cloth, the continuum on the contact grid against
// its analytic membrane response, and physics checks of the knit's curves.
#include <gtest/gtest.h>

#include <cmath>

#include "calibration/knit_test_patch.h"
#include "calibration/virtual_tests.h"
#include "models/fem/fem_material.h"
#include "models/scene/scene.h"
#include "tests/support/fd_check.h"

namespace wl {
namespace {

Scene stockinette() { return load_scene(WEAVELAB_SOURCE_DIR "/experiments/scenes/knit_stockinette.toml"); }

TEST(KnitVirtualTests, TestMapWithDepthMatchesCentralDifferences) {
  // A point 0.2 mm through the cloth, every test, unrotated and rotated.
  const Vec3 rest(1.3e-3, -0.7e-3, 2e-4);
  const double span = 0.012;
  for (const std::string& name : test_names())
    for (bool rotated : {false, true}) {
      const TestKind kind = test_kind(name);
      const double lambda = kind == TestKind::shear                                      ? 0.3
                            : clamps_rotation(kind) && kind != TestKind::stretch_bending ? 40.0
                                                                                         : 0.05;
      auto position = [&](const Eigen::VectorXd& l) {
        Vec3 x, dx;
        test_map(kind, rest, span, l[0], rotated, &x, &dx);
        return Eigen::VectorXd(x);
      };
      auto derivative = [&](int) {
        Vec3 x, dx;
        test_map(kind, rest, span, lambda, rotated, &x, &dx);
        return Eigen::VectorXd(dx);
      };
      // x = (λ, 0): the checker's step is relative to the extent of x, here λ.
      const test::FdReport r = test::check_jacobian_columns(position, Eigen::Vector2d(lambda, 0.0), derivative, {0});
      EXPECT_TRUE(r.ok) << name << (rotated ? " rotated: " : ": ") << r.detail;
    }
}

TEST(KnitVirtualTests, BendingCarriesTheDepthAlongTheNormal) {
  // The point at depth Z lies at distance |Z| from its mid-surface point, along the normal:
  // perpendicular to the bent surface's tangent along the bend.
  const double Z = 2e-4, span = 0.012, kappa = 60.0;
  for (TestKind kind : {TestKind::bending_warp, TestKind::bending_weft, TestKind::bending_diagonal}) {
    const Vec3 mid(2.1e-3, 1.4e-3, 0.0), deep(2.1e-3, 1.4e-3, Z);
    Vec3 x0, x1, xz, dx;
    test_map(kind, mid, span, kappa, false, &x0, &dx);
    test_map(kind, deep, span, kappa, false, &xz, &dx);
    const Vec3 b = kind == TestKind::bending_warp   ? Vec3(1, 0, 0)
                   : kind == TestKind::bending_weft ? Vec3(0, 1, 0)
                                                    : Vec3(std::sqrt(0.5), std::sqrt(0.5), 0);
    Vec3 xm;  // the tangent along the bend by central differences (relative error (hκ)²/6 = 6e-10)
    test_map(kind, mid + 1e-6 * b, span, kappa, false, &x1, &dx);
    test_map(kind, mid - 1e-6 * b, span, kappa, false, &xm, &dx);
    EXPECT_NEAR((xz - x0).norm(), Z, 1e-15) << test_name(kind);
    EXPECT_NEAR((xz - x0).dot((x1 - xm).normalized()), 0.0, 1e-8 * Z) << test_name(kind);
  }
}

TEST(KnitVirtualTests, ContinuumOnTheContactGridAnswersItsMembraneStiffness) {
  // The continuum patch on the contact grid (two spacings, W/2 and C) under an affine ring
  // follows the map inside, so R = k·ε with the grid's own span and area: this fixes the
  // response's normalization on the knit patch.
  // Course-wise (warp), wale-wise (weft) and both at once, at stiffnesses of a knit's size.
  const Scene patch = material_test_scene(stockinette(), 6);
  FemMaterial m = default_fem_material(patch);
  m.warp_stretch_N_per_m = 0.7;
  m.weft_stretch_N_per_m = 3.0;
  const std::vector<double> strains{0.01, 0.05};
  const Vec3 k(m.warp_stretch_N_per_m, m.weft_stretch_N_per_m, m.warp_stretch_N_per_m + m.weft_stretch_N_per_m);
  const TestKind kinds[] = {TestKind::uniaxial_warp, TestKind::uniaxial_weft, TestKind::biaxial};
  for (int t = 0; t < 3; ++t) {
    const ResponseCurve c = run_fem_test(patch, m, {kinds[t], strains});
    ASSERT_EQ(c.points.size(), strains.size()) << c.message;
    for (size_t i = 0; i < strains.size(); ++i)
      EXPECT_NEAR(c.points[i].response / strains[i], k[t], 1e-9 * k[t]) << test_name(kinds[t]);
  }
}

TEST(KnitVirtualTests, StretchFromTheRelaxedRestIsMonotoneAndSofterAlongTheCourse) {
  // A 6 × 6 stockinette, sliding frozen, stretched course-wise (warp-like, x) and wale-wise
  // (weft-like, y) to 6 %. At rest the ring holds what the relaxed tile, truncated at the patch's
  // edges, leaves unbalanced: |R(0)| must stay below the response to half a percent of strain,
  // ½(R(1 %) − R(0)) (measured 0.08 and 0.38 of R(1 %) − R(0)). From there each curve must
  // rise with every rung. Along the
  // course a stockinette stretches by opening its loops (bending the heads and sinkers); along
  // the wale it pulls its legs, which the stitches hold nearly straight: course-wise must be
  // less than half as stiff (measured about a fifth).
  const Scene patch = material_test_scene(stockinette(), 6);
  const std::vector<double> ladder{0.01, 0.03, 0.06};
  std::vector<double> rise[2];
  for (int k = 0; k < 2; ++k) {
    const TestKind kind = k == 0 ? TestKind::uniaxial_warp : TestKind::uniaxial_weft;
    ResponsePoint rest;
    const ResponseCurve c = run_yarn_test(patch, {kind, ladder}, {}, &rest);
    ASSERT_TRUE(c.complete) << c.message;
    ASSERT_EQ(c.points.size(), ladder.size());
    double previous = 0.0;
    for (const ResponsePoint& p : c.points) {
      const double r = p.response - rest.response;
      EXPECT_GT(r, previous) << test_name(kind) << " at " << p.load;
      previous = r;
      rise[k].push_back(r);
    }
    EXPECT_LT(std::abs(rest.response), 0.5 * rise[k][0]) << test_name(kind) << ": R(0) = " << rest.response;
  }
  for (size_t i = 0; i < ladder.size(); ++i)
    EXPECT_LT(rise[0][i], 0.5 * rise[1][i]) << "course-wise against wale-wise at strain " << ladder[i];
}

TEST(KnitVirtualTests, RefusesAPatchThePatternsTileDoesNotCover) {
  Scene garter = load_scene(WEAVELAB_SOURCE_DIR "/experiments/scenes/knit_garter.toml");
  EXPECT_THROW(material_test_scene(garter, 7), std::invalid_argument);  // its tile is 2 courses
  EXPECT_THROW(material_test_scene(stockinette(), 5), std::invalid_argument);
  EXPECT_NO_THROW(material_test_scene(garter, 8));
}

}  // namespace
}  // namespace wl
