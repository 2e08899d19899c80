// The Ceres fit: recovery of known continuum parameters from the continuum's
// own curves, and the covariance on a problem with a closed-form answer.
#include <gtest/gtest.h>

#include <cmath>

#include <Eigen/Dense>

#include "calibration/fit.h"
#include "models/scene/scene.h"

namespace wl {
namespace {

TEST(CalibrationFit, RecoversContinuumParametersFromItsOwnCurves) {
  const Scene patch = material_test_scene(load_scene(WEAVELAB_SOURCE_DIR "/experiments/scenes/hanging_wind.toml"), 7);
  FemMaterial truth = default_fem_material(patch);
  truth.warp_stretch_N_per_m *= 0.8;
  truth.weft_stretch_N_per_m *= 1.3;
  truth.shear_N_per_m *= 2.0;
  truth.shear_lock_angle_rad *= 0.9;
  truth.shear_lock_exponent = 2.0;
  truth.warp_bending_N_m *= 0.7;
  truth.weft_bending_N_m *= 1.5;
  const ContinuumTest continuum = [&](const FemMaterial& m, const TestSpec& t, const std::vector<std::string>& keys) {
    return run_fem_test(patch, m, t, keys);
  };
  std::vector<FitCurve> curves;
  for (const std::string& name : default_test_names()) {
    const TestKind kind = test_kind(name);
    // every other rung of the default ladder keeps the test quick
    std::vector<double> ladder;
    const std::vector<double> full = default_ladder(kind, 7, patch.spacing_m);
    for (size_t i = 1; i < full.size(); i += 2) ladder.push_back(full[i]);
    FitCurve c{{kind, ladder}, {}};
    for (const ResponsePoint& p : run_fem_test(patch, truth, c.test).points) c.target.push_back(p.response);
    curves.push_back(c);
  }
  // Start off by a factor 3 in every parameter (the lock angle by 1/3: it must stay below π/2).
  FemMaterial start = truth;
  for (const std::string& key : fittable_parameters())  // the diagonal stiffness and the stretch's extras stay off (0)
    material_value(start, key) *= key == "shear_lock_angle_rad" ? 1.0 / 3.0 : 3.0;
  FitOptions opt;
  opt.starts = 1;
  opt.max_iterations = 400;  // the lock angle and exponent start far off along a curved valley
  opt.progress = getenv("FITDEBUG") != nullptr;
  const FitResult r = fit_continuum(curves, start, continuum, opt);
  ASSERT_TRUE(r.converged) << r.message;
  FemMaterial fitted = r.material;
  // all but the diagonal stiffness, the spline shear's knot values and the stretch's coupling and
  // three quartics, which are off
  EXPECT_EQ(r.parameters.size(), fittable_parameters().size() - 1 - FemSettings::kMaxShearKnots - 4);
  for (const FittedParameter& p : r.parameters)
    EXPECT_NEAR(material_value(fitted, p.key) / material_value(truth, p.key), 1.0, 1e-6) << p.key;
  for (double rms : r.relative_rms) EXPECT_LT(rms, 1e-8);
}

TEST(CalibrationFit, CovarianceMatchesLinearLeastSquares) {
  // A "continuum" whose response is linear in two parameters, R(λ) = a·λ + b·λ², fitted to
  // targets with a fixed deterministic scatter: the optimum, standard errors and correlation
  // are those of weighted linear least squares, σ²(XᵀWX)⁻¹ with σ² = RSS_w/(m − n).
  const std::vector<double> lambda{0.5, 1.0, 1.5, 2.0, 2.5, 3.0};
  const std::vector<double> scatter{0.03, -0.05, 0.02, 0.04, -0.01, -0.03};
  const double a0 = 2.0, b0 = 0.7;
  FitCurve curve{{TestKind::uniaxial_warp, lambda}, {}};
  for (size_t i = 0; i < lambda.size(); ++i)
    curve.target.push_back(a0 * lambda[i] + b0 * lambda[i] * lambda[i] + scatter[i]);
  const ContinuumTest linear = [&](const FemMaterial& m, const TestSpec& t, const std::vector<std::string>& keys) {
    ResponseCurve c{t.kind, {}, true, "", {}};
    for (double l : t.ladder) {
      c.points.push_back({l, m.warp_stretch_N_per_m * l + m.weft_stretch_N_per_m * l * l, 0});
      std::vector<double> s;
      for (const auto& k : keys) s.push_back(k == "fem.warp_stretch_N_per_m" ? l : l * l);
      c.sensitivities.push_back(s);
    }
    return c;
  };
  FemMaterial guess;
  guess.warp_stretch_N_per_m = 1.0;
  guess.weft_stretch_N_per_m = 1.0;
  FitOptions opt;
  opt.free = {"warp_stretch_N_per_m", "weft_stretch_N_per_m"};
  opt.starts = 3;
  const FitResult r = fit_continuum({curve}, guess, linear, opt);
  ASSERT_TRUE(r.converged) << r.message;

  const int m = static_cast<int>(lambda.size());
  Eigen::MatrixXd X(m, 2);
  Eigen::VectorXd y(m);
  for (int i = 0; i < m; ++i) {
    X(i, 0) = lambda[i];
    X(i, 1) = lambda[i] * lambda[i];
    y[i] = curve.target[i];
  }
  const Eigen::Matrix2d XtX = X.transpose() * X;  // the uniform weight cancels in p̂ and in σ²(XᵀWX)⁻¹
  const Eigen::Vector2d p = XtX.ldlt().solve(X.transpose() * y);
  const double s2 = (y - X * p).squaredNorm() / (m - 2);
  const Eigen::Matrix2d cov = s2 * XtX.inverse();
  ASSERT_EQ(r.parameters.size(), 2u);
  for (int k = 0; k < 2; ++k) {
    EXPECT_NEAR(r.parameters[k].value, p[k], 1e-8 * std::abs(p[k]));
    EXPECT_NEAR(r.parameters[k].std_error, std::sqrt(cov(k, k)), 1e-6 * std::sqrt(cov(k, k)));
    EXPECT_LT(r.parameters[k].start_spread, 1e-6);
  }
  EXPECT_NEAR(r.correlation[0][1], cov(0, 1) / std::sqrt(cov(0, 0) * cov(1, 1)), 1e-6);
}

}  // namespace
}  // namespace wl
