// SegmentInertiaTerm: mass block against quadrature of the kinetic energy with
// the corrected interpolation (docs/models.md §2.2, §4.1), force against
// Lagrange's equation, analytic Jacobians against finite differences, and
// properties of M and of the inertial force.
#include <gtest/gtest.h>

#include <random>

#include <Eigen/Eigenvalues>

#include "models/core/assembly.h"
#include "models/yarn/terms/segment_inertia.h"
#include "tests/support/fd_check.h"

namespace wl {
namespace {

using Vec8 = Eigen::Matrix<double, 8, 1>;
using Mat8 = Eigen::Matrix<double, 8, 8>;

constexpr double kRho = 0.002;  // kg/m

SegmentInertiaTerm make_term(double rho = kRho) {
  SegmentInertiaTerm t;
  t.add({0, 1, 2, 3, 4, 5, 6, 7}, rho);
  return t;
}

// A random segment state; `scale` sets the size of the velocities. u1 > u0.
struct State {
  Vec8 q, v;
};
State random_state(std::mt19937& rng, double vscale) {
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  State s;
  for (int i = 0; i < 6; ++i) s.q(i) = U(rng);
  s.q(6) = U(rng);
  s.q(7) = s.q(6) + 0.3 + 1.5 * (U(rng) + 1.0);
  for (int i = 0; i < 8; ++i) s.v(i) = vscale * U(rng);
  return s;
}

Mat8 mass_of(const SegmentInertiaTerm& t, const Vec8& q, const Vec8& v) {
  Vec8 f;
  Mat8 m = Mat8::Zero();
  t.evaluate(0, q.data(), v.data(), ElementOutput{f.data(), nullptr, nullptr, m.data()});
  return m;
}
Vec8 force_of(const SegmentInertiaTerm& t, const Vec8& q, const Vec8& v) {
  Vec8 f = Vec8::Zero();
  t.evaluate(0, q.data(), v.data(), ElementOutput{f.data(), nullptr, nullptr, nullptr});
  return f;
}

// Velocity of the material point u (held fixed) under the corrected
// interpolation x(u) = ((u1 − u) x0 + (u − u0) x1) / Δu, differentiated in time.
Vec3 material_velocity(const Vec8& q, const Vec8& v, double u) {
  const Vec3 x0 = q.segment<3>(0), x1 = q.segment<3>(3), xd0 = v.segment<3>(0), xd1 = v.segment<3>(3);
  const double u0 = q(6), u1 = q(7), ud0 = v(6), ud1 = v(7), D = u1 - u0, Dd = ud1 - ud0;
  const Vec3 num = (u1 - u) * x0 + (u - u0) * x1;
  const Vec3 num_dot = ud1 * x0 + (u1 - u) * xd0 - ud0 * x1 + (u - u0) * xd1;
  return num_dot / D - num * Dd / (D * D);
}

// ρ ∫_{u0}^{u1} ẋ_a(u)·ẋ_b(u) du by 3-point Gauss–Legendre (exact: the integrand is quadratic in u).
double quadrature_bilinear(const Vec8& q, const Vec8& va, const Vec8& vb, double rho) {
  const double gx[3] = {-std::sqrt(0.6), 0.0, std::sqrt(0.6)};
  const double gw[3] = {5.0 / 9.0, 8.0 / 9.0, 5.0 / 9.0};
  const double u0 = q(6), u1 = q(7), half = 0.5 * (u1 - u0), mid = 0.5 * (u0 + u1);
  double sum = 0.0;
  for (int i = 0; i < 3; ++i) {
    const double u = mid + half * gx[i];
    sum += gw[i] * material_velocity(q, va, u).dot(material_velocity(q, vb, u));
  }
  return rho * half * sum;
}

TEST(SegmentInertiaTerm, MassMatchesQuadratureOfKineticEnergy) {
  std::mt19937 rng(11);
  auto t = make_term();
  for (int trial = 0; trial < 10; ++trial) {
    const State s = random_state(rng, 1.0);
    const Mat8 m = mass_of(t, s.q, s.v);
    // Every entry: M_ij = ρ∫ẋ(e_i)·ẋ(e_j) du.
    Mat8 mq;
    for (int i = 0; i < 8; ++i)
      for (int j = 0; j < 8; ++j) mq(i, j) = quadrature_bilinear(s.q, Vec8::Unit(i), Vec8::Unit(j), kRho);
    EXPECT_LT((m - mq).norm(), 1e-12 * mq.norm()) << "M:\n" << m << "\nquadrature:\n" << mq;
    // T(q, q̇) = ½ q̇ᵀ M q̇ and the closed-form T against ½ρ∫‖ẋ‖² du.
    const double tq = 0.5 * quadrature_bilinear(s.q, s.v, s.v, kRho);
    EXPECT_NEAR(0.5 * s.v.dot(m * s.v), tq, 1e-12 * std::abs(tq));
    EXPECT_NEAR(SegmentInertiaTerm::kinetic_energy(s.q.data(), s.v.data(), kRho), tq, 1e-12 * std::abs(tq));
    Mat8 mb;
    SegmentInertiaTerm::mass_block(s.q.data(), kRho, mb.data());
    EXPECT_EQ(mb, m);
  }
}

// Lagrange: M q̈ = ∂T/∂q − Ṁq̇ (docs/models.md §3.1.2). ∂T/∂q by central differences
// of T = ½ q̇ᵀ M(q) q̇; Ṁq̇ by central differences of M along q̇.
TEST(SegmentInertiaTerm, ForceMatchesLagrangeEquation) {
  std::mt19937 rng(12);
  auto t = make_term();
  const double h = 1e-6;
  for (int trial = 0; trial < 10; ++trial) {
    const State s = random_state(rng, trial < 5 ? 1.0 : 20.0);
    auto T = [&](const Vec8& q) { return 0.5 * s.v.dot(mass_of(t, q, s.v) * s.v); };
    Vec8 dTdq;
    for (int j = 0; j < 8; ++j) {
      Vec8 qp = s.q, qm = s.q;
      qp(j) += h;
      qm(j) -= h;
      dTdq(j) = (T(qp) - T(qm)) / (2 * h);
    }
    const double eps = h / std::max(1.0, s.v.norm());
    const Mat8 mdot = (mass_of(t, s.q + eps * s.v, s.v) - mass_of(t, s.q - eps * s.v, s.v)) / (2 * eps);
    const Vec8 expected = dTdq - mdot * s.v;
    const Vec8 f = force_of(t, s.q, s.v);
    EXPECT_LT((f - expected).norm(), 1e-6 * expected.norm())
        << "force " << f.transpose() << "\nLagrange " << expected.transpose();
  }
}

TEST(SegmentInertiaTerm, JacobiansMatchFiniteDifferences) {
  std::mt19937 rng(13);
  auto t = make_term();
  std::vector<test::LocalState> states;
  // Near rest: a straight segment of unit stretch with small velocities.
  states.push_back({{0, 0, 0, 0.01, 0, 0, 0.02, 0.03}, {1e-3, -2e-3, 0, 0, 1e-3, 2e-3, 5e-4, -1e-3}});
  // Far from rest: random stretched/compressed states with large velocities.
  for (int k = 0; k < 4; ++k) {
    const State s = random_state(rng, k < 2 ? 1.0 : 10.0);
    states.push_back(
        {std::vector<double>(s.q.data(), s.q.data() + 8), std::vector<double>(s.v.data(), s.v.data() + 8)});
  }
  auto r = test::check_element(t, 0, states);
  EXPECT_TRUE(r.ok) << r.detail;
}

TEST(SegmentInertiaTerm, MassIsSymmetricPositiveSemidefiniteWithSlidingNullSpace) {
  std::mt19937 rng(14);
  auto t = make_term();
  for (int trial = 0; trial < 10; ++trial) {
    const State s = random_state(rng, 1.0);
    const Mat8 m = mass_of(t, s.q, s.v);
    EXPECT_EQ((m - m.transpose()).norm(), 0.0);
    Eigen::SelfAdjointEigenSolver<Mat8> es(m);
    const auto& ev = es.eigenvalues();  // ascending
    EXPECT_GT(ev(0), -1e-14 * ev(7));
    // Rank 6 (docs/models.md §3.1.1): two zero eigenvalues, the rest clearly positive.
    EXPECT_LT(std::abs(ev(1)), 1e-12 * ev(7));
    EXPECT_GT(ev(2), 1e-6 * ev(7));
    // Null vectors (w, 0, 1, 0) and (0, w, 0, 1): nodes sliding through still material.
    const Vec3 w = (s.q.segment<3>(3) - s.q.segment<3>(0)) / (s.q(7) - s.q(6));
    Vec8 n0 = Vec8::Zero(), n1 = Vec8::Zero();
    n0 << w, Vec3::Zero(), 1, 0;
    n1 << Vec3::Zero(), w, 0, 1;
    EXPECT_LT((m * n0).norm(), 1e-14 * m.norm());
    EXPECT_LT((m * n1).norm(), 1e-14 * m.norm());
  }
}

// With u̇ = 0 the Lagrangian part of M is constant, so the x-rows of the
// inertial force vanish. The u-rows do not: T = ρΔu σx/6 gives
// f_u0 = −½ρ‖ẋ0‖² and f_u1 = +½ρ‖ẋ1‖² (material carried across the segment
// ends; docs/models.md §3.1.2 closed form with u̇ = 0, derived by hand).
TEST(SegmentInertiaTerm, ZeroSlidingVelocityGivesNoForceOnPositions) {
  std::mt19937 rng(15);
  auto t = make_term();
  for (int trial = 0; trial < 5; ++trial) {
    State s = random_state(rng, 3.0);
    s.v(6) = s.v(7) = 0.0;
    const Vec8 f = force_of(t, s.q, s.v);
    const double scale = kRho * s.v.squaredNorm();
    EXPECT_LT(f.head<6>().norm(), 1e-14 * scale);
    EXPECT_NEAR(f(6), -0.5 * kRho * s.v.head<3>().squaredNorm(), 1e-14 * scale);
    EXPECT_NEAR(f(7), 0.5 * kRho * s.v.segment<3>(3).squaredNorm(), 1e-14 * scale);
  }
}

// Nodes sliding along a segment whose material stays still: T ≡ 0 along the
// motion and the generalized momentum is zero, so the inertial force vanishes.
TEST(SegmentInertiaTerm, StillMaterialWithSlidingNodesGivesNoForce) {
  std::mt19937 rng(16);
  auto t = make_term();
  for (int trial = 0; trial < 5; ++trial) {
    State s = random_state(rng, 1.0);
    const Vec3 w = (s.q.segment<3>(3) - s.q.segment<3>(0)) / (s.q(7) - s.q(6));
    const double a0 = s.v(6), a1 = s.v(7);
    s.v << a0 * w, a1 * w, a0, a1;
    for (double u = s.q(6); u <= s.q(7); u += 0.25 * (s.q(7) - s.q(6)))
      ASSERT_LT(material_velocity(s.q, s.v, u).norm(), 1e-13);  // the state really is "material at rest"
    const Vec8 f = force_of(t, s.q, s.v);
    EXPECT_LT(f.norm(), 1e-14 * kRho * (1.0 + s.v.squaredNorm()));
  }
}

// A whole yarn (5 nodes, non-straight, frozen end coordinates) translating
// rigidly with u̇ = 0 has no inertial force: the u-row contributions of
// neighbouring segments cancel at every interior node.
TEST(SegmentInertiaTerm, RigidlyTranslatingYarnHasNoInertialForce) {
  SegmentInertiaTerm t;
  // DoFs: x of node i at 3i..3i+2, u of nodes 1..3 at 15..17; u of nodes 0, 4 are constants 0, 1.
  auto u_index = [](int i) { return i == 0 ? encode_constant(0) : i == 4 ? encode_constant(1) : 14 + i; };
  for (int i = 0; i < 4; ++i)
    t.add({3 * i, 3 * i + 1, 3 * i + 2, 3 * i + 3, 3 * i + 4, 3 * i + 5, u_index(i), u_index(i + 1)},
          kRho);  // one yarn, one density (a density jump would leave ½Δρ‖V‖² at that node)
  Vec q(18), v(18), constants(2);
  const double L = 1e-3;
  for (int i = 0; i < 5; ++i) q.segment<3>(3 * i) = Vec3(i * L, 0.2 * L * (i % 2), 0.1 * L * i * i);
  q.segment<3>(15) = Vec3(1.1 * L, 2.05 * L, 3.2 * L);
  constants << 0.0, 4.3 * L;
  const Vec3 V(0.3, -1.2, 2.0);
  v.setZero();
  for (int i = 0; i < 5; ++i) v.segment<3>(3 * i) = V;
  Assembly assembly(18, {&t});
  Vec f = Vec::Zero(18);
  assembly.add_stage(0, q, v, constants, {}, f, nullptr, nullptr, nullptr);
  EXPECT_LT(f.norm(), 1e-14 * kRho * V.squaredNorm()) << f.transpose();
}

TEST(SegmentInertiaTerm, RejectsNonPositiveDensity) {
  SegmentInertiaTerm t;
  EXPECT_THROW(t.add({0, 1, 2, 3, 4, 5, 6, 7}, 0.0), std::invalid_argument);
  EXPECT_THROW(t.add({0, 1, 2, 3, 4, 5, 6, 7}, std::nan("")), std::invalid_argument);
}

}  // namespace
}  // namespace wl
