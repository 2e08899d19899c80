// Calibration's kept continuum patches: a patch re-parameterized per curve
// evaluation gives bitwise the curves of a patch built for each material, and
// a fit on kept patches with its starts run concurrently gives bitwise the fit
// of the rebuild path with its starts run in order.
#include <gtest/gtest.h>

#include "calibration/fem_test_patch.h"
#include "calibration/fit.h"
#include "models/fem/fem_model.h"
#include "models/scene/scene.h"

namespace wl {
namespace {

Scene patch_scene() {
  return material_test_scene(load_scene(WEAVELAB_SOURCE_DIR "/experiments/scenes/hanging_wind.toml"), 7);
}

// Another material than the scene's: every fitted parameter moved.
FemMaterial moved_material(const Scene& scene) {
  FemMaterial m = default_fem_material(scene);
  m.warp_stretch_N_per_m *= 1.7;
  m.shear_N_per_m *= 3.0;
  m.shear_lock_exponent = 2.0;
  m.warp_bending_N_m *= 0.5;
  m.areal_density_kg_per_m2 *= 1.2;
  return m;
}

Vec values(const SparseMatrix& m) { return Eigen::Map<const Vec>(m.valuePtr(), m.nonZeros()); }

void expect_same_curve(const ResponseCurve& a, const ResponseCurve& b, const std::string& what) {
  ASSERT_EQ(a.complete, b.complete) << what;
  ASSERT_EQ(a.points.size(), b.points.size()) << what;
  for (size_t i = 0; i < a.points.size(); ++i) {
    EXPECT_EQ(a.points[i].response, b.points[i].response) << what << " point " << i;
    EXPECT_EQ(a.points[i].newton_iterations, b.points[i].newton_iterations) << what << " point " << i;
    EXPECT_EQ(a.sensitivities[i], b.sensitivities[i]) << what << " point " << i;
  }
}

TEST(FemTestPatch, ReparameterizedModelEvaluatesAsANewOne) {
  const Scene scene = patch_scene();
  const FemMaterial guess = default_fem_material(scene), other = moved_material(scene);
  FemModel kept(scene, make_fem_mesh(scene), guess);
  kept.set_material(other);
  FemModel fresh(scene, make_fem_mesh(scene), other);
  Vec q = fresh.initial_q();
  for (Eigen::Index i = 0; i < q.size(); ++i) q[i] += 1e-5 * std::sin(0.7 * i);  // stretched, sheared, bent
  const Vec v = Vec::Constant(q.size(), 0.01);
  Evaluation a, b;
  kept.evaluate(0.0, q, v, kForce | kDfdq | kDfdv | kMass, a);
  fresh.evaluate(0.0, q, v, kForce | kDfdq | kDfdv | kMass, b);
  ASSERT_GT(b.force.norm(), 0.0);
  EXPECT_EQ(a.force, b.force);
  ASSERT_GT(values(b.dfdq).norm(), 0.0);
  EXPECT_EQ(values(a.dfdq), values(b.dfdq));
  EXPECT_EQ(values(a.mass), values(b.mass));
  Vec pa, pb;
  ASSERT_TRUE(kept.force_parameter_derivative("fem.shear_N_per_m", 0.0, q, v, pa));
  ASSERT_TRUE(fresh.force_parameter_derivative("fem.shear_N_per_m", 0.0, q, v, pb));
  EXPECT_EQ(pa, pb);
}

TEST(FemTestPatch, CurvesAreBitwiseThoseOfANewPatch) {
  const Scene scene = patch_scene();
  const FemMaterial guess = default_fem_material(scene), other = moved_material(scene);
  const std::vector<std::string> keys = {"fem.warp_stretch_N_per_m", "fem.shear_N_per_m", "fem.warp_bending_N_m"};
  for (const TestSpec& test : {TestSpec{TestKind::uniaxial_warp, {0.004, 0.012}}, TestSpec{TestKind::shear, {0.2, 0.6}},
                               TestSpec{TestKind::bending_warp, {20.0, 60.0}}}) {
    FemTestPatch patch(scene, guess, test);
    // guess, another material, the guess again: each as a patch built for it
    for (const FemMaterial* m : {&guess, &other, &guess}) {
      const ResponseCurve kept = patch.run(*m, keys), fresh = run_fem_test(scene, *m, test, keys);
      ASSERT_TRUE(fresh.complete) << fresh.message;
      expect_same_curve(kept, fresh, test_name(test));
    }
  }
}

TEST(FemTestPatch, ConcurrentStartsOnKeptPatchesFitAsTheRebuildPathInOrder) {
  const Scene scene = patch_scene();
  FemMaterial truth = default_fem_material(scene);
  truth.warp_stretch_N_per_m *= 0.8;
  truth.shear_N_per_m *= 2.0;
  std::vector<FitCurve> curves;
  for (const TestSpec& test :
       {TestSpec{TestKind::uniaxial_warp, {0.004, 0.012}}, TestSpec{TestKind::shear, {0.2, 0.6}}}) {
    FitCurve c{test, {}};
    for (const ResponsePoint& p : run_fem_test(scene, truth, test).points) c.target.push_back(p.response);
    curves.push_back(c);
  }
  const FemMaterial guess = default_fem_material(scene);
  FitOptions opt;
  opt.free = {"warp_stretch_N_per_m", "shear_N_per_m"};
  opt.starts = 2;
  opt.max_iterations = 8;
  opt.threads = 1;
  const ContinuumTest rebuild = [&](const FemMaterial& m, const TestSpec& t, const std::vector<std::string>& keys) {
    return run_fem_test(scene, m, t, keys);
  };
  const FitResult in_order = fit_continuum(curves, guess, rebuild, opt);
  FemTestPatches patches(scene);
  const ContinuumTest kept = [&](const FemMaterial& m, const TestSpec& t, const std::vector<std::string>& keys) {
    return patches.run(m, t, keys);
  };
  opt.threads = 2;
  const FitResult concurrent = fit_continuum(curves, guess, kept, opt);
  ASSERT_GT(in_order.evaluations, 10);
  EXPECT_EQ(concurrent.evaluations, in_order.evaluations);
  EXPECT_EQ(concurrent.cost, in_order.cost);
  ASSERT_EQ(concurrent.starts.size(), 2u);
  for (size_t s = 0; s < 2; ++s) {
    EXPECT_EQ(concurrent.starts[s].value, in_order.starts[s].value) << "start " << s;
    EXPECT_EQ(concurrent.starts[s].cost, in_order.starts[s].cost) << "start " << s;
  }
  for (size_t k = 0; k < in_order.parameters.size(); ++k)
    EXPECT_EQ(concurrent.parameters[k].value, in_order.parameters[k].value) << in_order.parameters[k].key;
  EXPECT_EQ(concurrent.fitted, in_order.fitted);
}

}  // namespace
}  // namespace wl
