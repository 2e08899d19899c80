// StretchTerm (docs/models.md §3.2): analytic force and Jacobian against finite
// differences, zero force at rest, the closed-form tension, translation invariance.
#include <gtest/gtest.h>

#include <cmath>

#include <Eigen/Eigenvalues>

#include "models/core/step_stiffness.h"
#include "models/yarn/terms/stretch.h"
#include "tests/support/fd_check.h"

namespace wl {
namespace {

StretchTerm one_segment(double ks) {
  StretchTerm t;
  t.add({0, 1, 2, 3, 4, 5, 6, 7}, ks);
  return t;
}

Eigen::Matrix<double, 8, 1> force(const StretchTerm& t, const std::vector<double>& q) {
  Eigen::Matrix<double, 8, 1> f = Eigen::Matrix<double, 8, 1>::Zero();
  std::vector<double> v(8, 0.0);
  t.evaluate(0, q.data(), v.data(), ElementOutput{f.data()});
  return f;
}

TEST(StretchTerm, ForcesAndJacobiansMatchFiniteDifferences) {
  const StretchTerm t = one_segment(2.5);
  const std::vector<double> zero(8, 0.0);
  const std::vector<test::LocalState> states = {
      // near rest: ‖x1−x0‖ ≈ Δu
      {{0.0, 0.0, 0.0, 1.001, 0.002, -0.001, 0.3, 1.3}, zero},
      // far from rest: stretched by ~60 % and tilted
      {{0.1, -0.2, 0.3, 1.2, 0.9, 0.8, -0.4, 0.8}, zero},
      // compressed (‖w‖ < 1)
      {{0.5, 0.5, 0.5, 0.8, 0.6, 0.4, 1.0, 2.5}, zero},
      // u not at rest: material coordinates far from their rest spacing
      {{-1.0, 2.0, 0.5, -0.3, 2.4, 0.1, 3.7, 4.05}, zero},
  };
  const auto r = test::check_element(t, 0, states);
  EXPECT_TRUE(r.ok) << r.detail;
}

TEST(StretchTerm, FiniteDifferencesAtMillimetreScale) {
  // Realistic magnitudes: L = 1 mm, k_s = Y·πR² with Y = 5e5 Pa, R = 0.5 mm.
  const double ks = 5e5 * M_PI * 0.25e-6;
  const StretchTerm t = one_segment(ks);
  const std::vector<double> zero(8, 0.0);
  const std::vector<test::LocalState> states = {
      {{0.0, 0.0, 0.0, 1.03e-3, 0.1e-3, -0.2e-3, 2e-3, 3e-3}, zero},
      {{0.0, 0.0, 0.0, 0.9e-3, 0.3e-3, 0.1e-3, 2e-3, 3.1e-3}, zero},
  };
  test::FdOptions opt;
  opt.floor = 1e-14;
  const auto r = test::check_element(t, 0, states, opt);
  EXPECT_TRUE(r.ok) << r.detail;
}

// The step stiffness (docs/models.md §3.2): V = ½ k_s (‖x‖ − Δu)²/Δu is convex
// where the segment is stretched, so the projection leaves −K as it is; a
// compressed segment's −K is indefinite (its geometric stiffness), and the
// projection keeps its positive eigenpairs only. The force is untouched.
TEST(StretchTerm, StepStiffnessDropsACompressedSegmentsNegativeStiffnessOnly) {
  StretchTerm t = one_segment(2.5);
  t.set_projected_step_stiffness(true);
  EXPECT_TRUE(t.projects_step_stiffness());
  using Mat8 = Eigen::Matrix<double, 8, 8>;
  for (const bool compressed : {false, true}) {
    const std::vector<double> q = compressed ? std::vector<double>{0.5, 0.5, 0.5, 0.8, 0.6, 0.4, 1.0, 2.5}
                                             : std::vector<double>{0.1, -0.2, 0.3, 1.2, 0.9, 0.8, -0.4, 0.8};
    Eigen::Matrix<double, 8, 1> f = Eigen::Matrix<double, 8, 1>::Zero();
    const std::vector<double> v(8, 0.0);
    Mat8 k = Mat8::Zero();
    t.evaluate(0, q.data(), v.data(), ElementOutput{f.data(), k.data()});
    EXPECT_EQ(f, force(t, q));
    Mat8 kp = k;
    project_step_stiffness(8, kp.data());
    const Eigen::SelfAdjointEigenSolver<Mat8> exact(-k);
    const double scale = exact.eigenvalues().cwiseAbs().maxCoeff();
    EXPECT_GE(Eigen::SelfAdjointEigenSolver<Mat8>(-kp).eigenvalues().minCoeff(), -1e-12 * scale);
    if (!compressed) {
      EXPECT_GE(exact.eigenvalues().minCoeff(), -1e-12 * scale);
      EXPECT_LT((kp - k).norm(), 1e-12 * scale);
      continue;
    }
    EXPECT_LT(exact.eigenvalues().minCoeff(), -0.1 * scale);
    for (int i = 0; i < 8; ++i) {
      const auto u = exact.eigenvectors().col(i);
      EXPECT_LT((-kp * u - std::max(exact.eigenvalues()[i], 0.0) * u).norm(), 1e-10 * scale);
    }
  }
}

TEST(StretchTerm, ZeroForceAndEnergyAtRest) {
  const StretchTerm t = one_segment(7.0);
  // ‖x1−x0‖ = √(0.36+0.64) = 1 = Δu
  const std::vector<double> q = {1.0, 2.0, 3.0, 1.6, 2.8, 3.0, 0.25, 1.25};
  EXPECT_NEAR(t.energy(0, q.data()), 0.0, 1e-15);
  EXPECT_LT(force(t, q).norm(), 1e-14);
}

TEST(StretchTerm, TensionMatchesClosedForm) {
  // Straight segment along x, length 1.5, Δu = 1: ‖w‖ = 1.5, so the spring
  // pulls x1 back with k_s(‖w‖−1) = 0.5 k_s and F_u1 = ½ k_s (2.25 − 1).
  const double ks = 4.0;
  const StretchTerm t = one_segment(ks);
  const std::vector<double> q = {0, 0, 0, 1.5, 0, 0, 2.0, 3.0};
  const auto f = force(t, q);
  EXPECT_NEAR(f[3], -0.5 * ks, 1e-13);
  EXPECT_NEAR(f[0], 0.5 * ks, 1e-13);
  EXPECT_NEAR(f[7], 0.5 * ks * 1.25, 1e-13);
  EXPECT_NEAR(f[6], -0.5 * ks * 1.25, 1e-13);
  EXPECT_NEAR(t.energy(0, q.data()), 0.5 * ks * 1.0 * 0.25, 1e-13);
}

TEST(StretchTerm, TranslationInvariance) {
  const StretchTerm t = one_segment(3.0);
  const std::vector<double> q = {0.1, -0.2, 0.3, 1.2, 0.9, 0.8, -0.4, 0.8};
  const auto f = force(t, q);
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(f[k] + f[3 + k], 0.0, 1e-14) << "component " << k;
  // Shifting the material coordinates (sliding both ends equally) changes nothing.
  EXPECT_NEAR(f[6] + f[7], 0.0, 1e-14);
  auto q2 = q;
  q2[6] += 0.7;
  q2[7] += 0.7;
  EXPECT_LT((force(t, q2) - f).norm(), 1e-13);
}

TEST(StretchTerm, LocalForceMatchesEvaluate) {
  const StretchTerm t = one_segment(3.0);
  const std::vector<double> q = {0.1, -0.2, 0.3, 1.2, 0.9, 0.8, -0.4, 0.8};
  const auto f = StretchTerm::local_force(Vec3(0.1, -0.2, 0.3), Vec3(1.2, 0.9, 0.8), -0.4, 0.8, 3.0);
  EXPECT_LT((f - force(t, q)).norm(), 1e-15);
}

TEST(StretchTerm, RejectsBadStiffness) {
  StretchTerm t;
  EXPECT_THROW(t.add({0, 1, 2, 3, 4, 5, 6, 7}, -1.0), std::invalid_argument);
  EXPECT_THROW(t.add({0, 1, 2, 3, 4, 5, 6, 7}, std::nan("")), std::invalid_argument);
}

}  // namespace
}  // namespace wl
