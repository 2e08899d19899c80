// The flat-cost rule of the trajectory fit (calibration/fit_stopping.h) and the
// default growing window (calibration/fit_continuation.h), as pure functions.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "calibration/fit_continuation.h"
#include "calibration/fit_stopping.h"
#include "calibration/trajectory_fit.h"

namespace wl {
namespace {

// A cost that falls by √10 per iteration down to 2.54e-13 at iteration 20 and
// then sits there, each iteration shaving 1e-6 of itself off: the stalled fit's
// history, which Ceres's own tolerances let run to the iteration cap.
std::vector<double> stalling_history(int iterations) {
  std::vector<double> h;
  for (int i = 0; i <= iterations; ++i)
    h.push_back(i <= 20 ? 2.54e-13 * std::pow(10.0, (20 - i) / 2.0) : h.back() * (1 - 1e-6));
  return h;
}

TEST(FlatCostRule, StopsAFlatCostOneWindowAfterItFlattens) {
  const FlatCostRule rule;  // the fit's default: window 5, fraction 1e-4, noise unmeasured
  const std::vector<double> h = stalling_history(45);
  int stop = -1;
  for (int i = 0; i < static_cast<int>(h.size()) && stop < 0; ++i)
    if (flat_cost_reason(std::vector<double>(h.begin(), h.begin() + i + 1), rule)) stop = i;
  // Flat from iteration 20: over 21…25 it falls by 5e-6 of itself, below the fraction 1e-4;
  // over 20…24 the window still holds the last √10 fall.
  EXPECT_EQ(stop, 25);
  const auto why = flat_cost_reason(std::vector<double>(h.begin(), h.begin() + 26), rule);
  ASSERT_TRUE(why);
  EXPECT_NE(why->find("stopped improving"), std::string::npos) << *why;
  EXPECT_NE(why->find("fraction"), std::string::npos) << *why;
}

TEST(FlatCostRule, KeepsGoingWhileTheCostFallsByMoreThanTheFraction) {
  const FlatCostRule rule;
  std::vector<double> h{1.0};
  for (int i = 0; i < 200; ++i) {
    h.push_back(h.back() * (1 - 1e-4));  // 5e-4 of the cost over a window of 5: above the fraction 1e-4
    EXPECT_FALSE(flat_cost_reason(h, rule)) << "iteration " << i + 1;
  }
  EXPECT_FALSE(flat_cost_reason({1.0, 1.0, 1.0}, rule));  // fewer iterations than the window
  EXPECT_FALSE(flat_cost_reason({NAN, NAN, NAN, NAN, NAN, NAN}, rule));
}

// A decrease above the fraction but within the cost's noise floor stops the fit,
// and the reason says which bound it met.
TEST(FlatCostRule, ADecreaseWithinTheNoiseFloorStops) {
  FlatCostRule rule;
  std::vector<double> h{1e-6};
  for (int i = 0; i < 5; ++i) h.push_back(h.back() * (1 - 1e-3));  // about 5e-9 over the window
  EXPECT_FALSE(flat_cost_reason(h, rule));
  rule.residual_noise = 1e-5;  // N = √(2·1e-6)·1e-5 + ½·1e-10 ≈ 1.4e-8 > 5e-9
  const auto why = flat_cost_reason(h, rule);
  ASSERT_TRUE(why);
  EXPECT_NE(why->find("noise floor"), std::string::npos) << *why;
  rule.residual_noise = 1e-7;  // N ≈ 1.4e-10 < 5e-9
  EXPECT_FALSE(flat_cost_reason(h, rule));
}

// N(C) bounds the change of ½‖r + δr‖² from ½‖r‖² for any δr of norm σ, and the
// bound is reached when δr is parallel to r.
TEST(FlatCostRule, CostNoiseBoundsTheCostChangeOfAResidualPerturbation) {
  std::mt19937 rng(3);
  std::normal_distribution<double> n01;
  for (int trial = 0; trial < 20; ++trial) {
    Eigen::VectorXd r(30), d(30);
    for (int i = 0; i < 30; ++i) r[i] = n01(rng), d[i] = 1e-3 * n01(rng);
    const double c = 0.5 * r.squaredNorm(), sigma = d.norm();
    EXPECT_LE(std::abs(0.5 * (r + d).squaredNorm() - c), cost_noise(c, sigma) * (1 + 1e-12));
    const Eigen::VectorXd along = sigma * r.normalized();
    EXPECT_NEAR(0.5 * (r + along).squaredNorm() - c, cost_noise(c, sigma), 1e-12 * c);
  }
}

// The trapezoidal prediction is exact for residuals quadratic in θ, so the
// measured noise is the noise added, and nothing without it.
TEST(FlatCostRule, ResidualNoiseIsWhatTheSensitivitiesDoNotExplain) {
  std::mt19937 rng(5);
  std::normal_distribution<double> n01;
  const int m = 12, n = 3;
  Eigen::VectorXd a(m);
  Eigen::MatrixXd b(m, n), c(m, n);  // r_i(θ) = a_i + b_i·θ + ½ Σ_k c_ik θ_k²
  for (int i = 0; i < m; ++i) {
    a[i] = n01(rng);
    for (int k = 0; k < n; ++k) b(i, k) = n01(rng), c(i, k) = n01(rng);
  }
  const auto r = [&](const Eigen::VectorXd& t) { return Eigen::VectorXd(a + b * t + 0.5 * c * t.cwiseProduct(t)); };
  const auto j = [&](const Eigen::VectorXd& t) { return Eigen::MatrixXd(b + c * t.asDiagonal()); };
  const Eigen::VectorXd t0 = Eigen::VectorXd::Constant(n, 0.3), step = Eigen::VectorXd::Constant(n, 1e-3);
  const Eigen::VectorXd t1 = t0 + step;
  EXPECT_LT(residual_noise(r(t0), j(t0), r(t1), j(t1), step), 1e-14);
  Eigen::VectorXd noise = Eigen::VectorXd::Zero(m);
  noise[4] = 3e-9;
  EXPECT_NEAR(residual_noise(r(t0), j(t0), r(t1) + noise, j(t1), step), 3e-9, 1e-14);
  // A first-order prediction alone would leave the curvature, ½ Σ c_ik step_k², unexplained.
  EXPECT_GT((r(t1) - r(t0) - j(t0) * step).norm(), 1e-7);
}

TEST(DefaultGrowingWindow, PlainUpToTenFramesThenDoublingFromFive) {
  EXPECT_TRUE(default_growing_window(1).empty());
  EXPECT_TRUE(default_growing_window(10).empty());
  EXPECT_EQ(default_growing_window(11), (std::vector<int>{5, 11}));
  EXPECT_EQ(default_growing_window(16), (std::vector<int>{5, 10, 16}));
  EXPECT_EQ(default_growing_window(20), (std::vector<int>{5, 10, 20}));
  EXPECT_EQ(default_growing_window(25), (std::vector<int>{5, 10, 25}));  // the published schedule
  EXPECT_EQ(default_growing_window(30), (std::vector<int>{5, 10, 20, 30}));
  EXPECT_EQ(default_growing_window(100), (std::vector<int>{5, 10, 20, 40, 100}));
  for (int frames = 11; frames <= 400; ++frames) {
    const std::vector<int> w = default_growing_window(frames);
    EXPECT_NO_THROW(check_window(w, frames)) << frames;
    for (size_t k = 1; k + 1 < w.size(); ++k) EXPECT_EQ(w[k], 2 * w[k - 1]) << frames;  // doubling
    ASSERT_GE(w.size(), 2u);
    EXPECT_LT(w.back(), 3 * w[w.size() - 2]) << frames;  // the last grows less than threefold
  }
}

}  // namespace
}  // namespace wl
