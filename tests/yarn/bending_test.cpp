// BendingTerm (docs/models.md §3.3): analytic force and Jacobian against finite
// differences (bent, nearly straight and straight), against Cirio et al. 2016's printed
// eqs. (28)–(29), zero force when straight, closed-form force, translation invariance.
#include <gtest/gtest.h>

#include <cmath>

#include "models/yarn/terms/bending.h"
#include "tests/support/fd_check.h"

namespace wl {
namespace {

using L11 = Eigen::Matrix<double, 11, 1>;
using M11 = Eigen::Matrix<double, 11, 11>;

BendingTerm one_stencil(double kb) {
  BendingTerm t;
  t.add({0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10}, kb);
  return t;
}

void eval(const BendingTerm& t, const std::vector<double>& q, L11& f, M11& K) {
  f.setZero();
  K.setZero();
  std::vector<double> v(11, 0.0);
  t.evaluate(0, q.data(), v.data(), ElementOutput{f.data(), K.data()});
}

// q = (x0, x1, x2, u1, u2) with x1 = x0 + l1 (cos φ, sin φ, 0) and x2 = x0 − l2 (1, 0, 0):
// the bending angle is φ.
std::vector<double> planar(double phi, double l1, double l2, double u1, double u2) {
  return {0.2, -0.1, 0.05, 0.2 + l1 * std::cos(phi), -0.1 + l1 * std::sin(phi), 0.05, 0.2 - l2, -0.1, 0.05, u1, u2};
}

TEST(BendingTerm, ForcesAndJacobiansMatchFiniteDifferences) {
  const BendingTerm t = one_stencil(1.7);
  const std::vector<double> z(11, 0.0);
  const std::vector<test::LocalState> states = {
      // near rest: slightly bent, Δu at rest
      {planar(0.05, 1.0, 1.0, 1.0, -1.0), z},
      // far from rest: strongly bent out of plane, unequal segments
      {{0.1, 0.2, -0.3, 0.9, 1.1, 0.4, -0.5, 0.6, 0.2, 2.2, -0.1}, z},
      // nearly folded (θ ≈ 2.6)
      {planar(2.6, 0.8, 1.3, 0.7, -1.4), z},
      // u not at rest: bent, with U far from l1 + l2
      {{0.0, 0.0, 0.0, 1.0, 0.3, -0.2, -0.9, 0.2, 0.3, 5.3, 4.9}, z},
  };
  const auto r = test::check_element(t, 0, states);
  EXPECT_TRUE(r.ok) << r.detail;
}

TEST(BendingTerm, FiniteDifferencesNearlyStraightAndStraight) {
  const BendingTerm t = one_stencil(0.9);
  const std::vector<double> z(11, 0.0);
  const std::vector<test::LocalState> states = {
      {planar(1e-3, 1.0, 0.7, 0.4, -1.3), z},   // series branch
      {planar(0.049, 1.0, 0.7, 0.4, -1.3), z},  // just below the series threshold
      {planar(0.051, 1.0, 0.7, 0.4, -1.3), z},  // just above it
      {planar(1e-6, 1.2, 0.9, 0.4, -1.3), z},   // FD steps cross through θ = 0 scale
  };
  const auto r = test::check_element(t, 0, states);
  EXPECT_TRUE(r.ok) << r.detail;
  // Exactly straight: the force is 0, while central differences of the energy
  // carry an O(h²) truncation error (cubic terms of V, ~1e-14 here), so the
  // absolute floor is raised; the O(1) Jacobian is still checked to 1e-5.
  const std::vector<test::LocalState> straight = {
      {planar(0.0, 1.2, 0.9, 0.4, -1.3), z},
      {{0, 0, 0, 0.6, 0.6, 0.6, -0.3, -0.3, -0.3, 1.1, -0.8}, z},  // along a diagonal
  };
  test::FdOptions opt;
  opt.floor = 1e-8;
  opt.rel_step = 5e-8;
  const auto rs = test::check_element(t, 0, straight, opt);
  EXPECT_TRUE(rs.ok) << rs.detail;
  EXPECT_GT(rs.dfdq_error, 0.0);  // the Jacobian comparison really ran
  EXPECT_LT(rs.dfdq_error, 1e-6);
}

TEST(BendingTerm, FiniteDifferencesAtMillimetreScale) {
  const double kb = 1.4e-4 * M_PI * 0.25e-6;  // B·πR², B = 1.4e-4, R = 0.5 mm
  const BendingTerm t = one_stencil(kb);
  const std::vector<double> z(11, 0.0);
  std::vector<double> q1 = planar(0.3, 1e-3, 1.1e-3, 3e-3, 1e-3);
  std::vector<double> q2 = planar(1e-4, 1e-3, 0.9e-3, 3e-3, 1e-3);
  test::FdOptions opt;
  opt.floor = 1e-20;
  const auto r = test::check_element(t, 0, {{q1, z}, {q2, z}}, opt);
  EXPECT_TRUE(r.ok) << r.detail;
}

TEST(BendingTerm, StraightYarnHasExactlyZeroForceAndFiniteJacobian) {
  const BendingTerm t = one_stencil(2.0);
  L11 f;
  M11 K;
  // Collinear nodes with exactly representable coordinates: θ = 0 exactly.
  const std::vector<double> q = {1, 2, 3, 2, 4, 5, -1, -2, -1, 1.5, -1.5};
  eval(t, q, f, K);
  EXPECT_EQ(t.energy(0, q.data()), 0.0);
  EXPECT_TRUE(f.allFinite());
  EXPECT_EQ(f.norm(), 0.0);
  ASSERT_TRUE(K.allFinite());
  // Straight limit, by hand: V ≈ (k_b/U)θ², and a transverse displacement δ of x1
  // gives θ ≈ δ/l1, so ∂F_x1/∂x1 = −(2k_b/U)/l1² P_1 (P_1: projector ⊥ yarn).
  const Vec3 e = Vec3(1, 2, 2) / 3.0;  // x1−x0 = (1,2,2), l1 = 3
  const Mat3 P = Mat3::Identity() - e * e.transpose();
  const double U = 3.0, l1 = 3.0;
  const Mat3 expected = -(2.0 * 2.0 / U) / (l1 * l1) * P;
  EXPECT_LT((K.block<3, 3>(3, 3) - expected).norm(), 1e-14);
  EXPECT_LT((K - K.transpose()).norm(), 1e-14);
}

TEST(BendingTerm, ForceMatchesClosedForm) {
  // Planar stencil bent by θ: |F_x1| = 2 k_b θ /(l1 U) (Cirio et al. 2016 eq. (21), |P_1 d_2| = sin θ),
  // perpendicular to x1−x0, and F_u1 = k_b θ²/U².
  const double kb = 1.3, th = 0.7, l1 = 0.8, l2 = 1.1, U = 2.0;
  const BendingTerm t = one_stencil(kb);
  L11 f;
  M11 K;
  eval(t, planar(th, l1, l2, 0.5, 0.5 - U), f, K);
  const Vec3 e1(std::cos(th), std::sin(th), 0.0);
  const Vec3 n1(std::sin(th), -std::cos(th), 0.0);  // ⊥ e1, toward straightening
  EXPECT_LT((f.segment<3>(3) - 2.0 * kb * th / (l1 * U) * n1).norm(), 1e-13);
  EXPECT_NEAR(f.segment<3>(3).dot(e1), 0.0, 1e-13);
  EXPECT_LT((f.segment<3>(6) - 2.0 * kb * th / (l2 * U) * Vec3(0, -1, 0)).norm(), 1e-13);
  EXPECT_NEAR(f[9], kb * th * th / (U * U), 1e-13);
  EXPECT_NEAR(f[10], -kb * th * th / (U * U), 1e-13);
  EXPECT_NEAR(t.energy(0, planar(th, l1, l2, 0.5, 0.5 - U).data()), kb * th * th / U, 1e-13);
}

TEST(BendingTerm, JacobianEqualsSeedEquations28And29) {
  // Cirio et al. 2016 eqs. (28), (29) written out literally, at a generic bent state.
  const double kb = 0.8;
  const BendingTerm t = one_stencil(kb);
  const std::vector<double> q = {0.1, 0.2, -0.3, 0.9, 1.1, 0.4, -0.5, 0.6, 0.2, 2.2, -0.1};
  L11 f;
  M11 K;
  eval(t, q, f, K);
  const Vec3 x0(q[0], q[1], q[2]), x1(q[3], q[4], q[5]), x2(q[6], q[7], q[8]);
  const double U = q[9] - q[10];
  const double l1 = (x1 - x0).norm(), l2 = (x2 - x0).norm();
  const Vec3 d1 = (x1 - x0) / l1, d2 = (x2 - x0) / l2;
  const Mat3 I = Mat3::Identity();
  const Mat3 P1 = I - d1 * d1.transpose(), P2 = I - d2 * d2.transpose();
  const double th = std::acos(-d1.dot(d2)), s = std::sin(th), c12 = d1.dot(d2);
  const Mat3 K11 = 2 * kb / (l1 * l1 * s * U) *
                   (th * (P1 * d2 * d1.transpose() + d1 * d2.transpose() * P1 + c12 * P1) -
                    1.0 / s * (1.0 + th / s * c12) * P1 * d2 * d2.transpose() * P1);
  const Mat3 K12 =
      -2 * kb / (l2 * l1 * s * U) * ((1.0 / s) * (1.0 + th / s * c12) * P1 * d2 * d1.transpose() + th * P1) * P2;
  EXPECT_LT((K.block<3, 3>(3, 3) - K11).norm(), 1e-12 * K11.norm());
  EXPECT_LT((K.block<3, 3>(3, 6) - K12).norm(), 1e-12 * K12.norm());
  // and the force, Cirio et al. 2016 eq. (21)
  const Vec3 F1 = -2 * kb * th / (l1 * U * s) * P1 * d2;
  EXPECT_LT((f.segment<3>(3) - F1).norm(), 1e-13);
}

TEST(BendingTerm, TranslationInvarianceAndSymmetry) {
  const BendingTerm t = one_stencil(1.1);
  L11 f;
  M11 K;
  const std::vector<double> q = {0.1, 0.2, -0.3, 0.9, 1.1, 0.4, -0.5, 0.6, 0.2, 2.2, -0.1};
  eval(t, q, f, K);
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(f[k] + f[3 + k] + f[6 + k], 0.0, 1e-14) << "component " << k;
  EXPECT_NEAR(f[9] + f[10], 0.0, 1e-14);
  EXPECT_LT((K - K.transpose()).norm(), 1e-12 * K.norm());
  // Rigid translation: every column sum over x rows of the x–x Jacobian vanishes.
  for (int k = 0; k < 3; ++k) {
    Eigen::Matrix<double, 11, 1> shift = Eigen::Matrix<double, 11, 1>::Zero();
    shift[k] = shift[3 + k] = shift[6 + k] = 1.0;
    EXPECT_LT((K * shift).norm(), 1e-12 * K.norm());
  }
}

TEST(BendingTerm, RejectsBadStiffness) {
  BendingTerm t;
  EXPECT_THROW(t.add({0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10}, -1.0), std::invalid_argument);
}

}  // namespace
}  // namespace wl
