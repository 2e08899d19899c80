// Cirio shear (docs/models.md §3.4.2): derivatives against finite differences,
// forces against Cirio et al. 2016 eqs. (43)–(45) written out independently, rest at π/2.
#include <gtest/gtest.h>

#include <numbers>

#include "models/yarn/terms/shear_cirio.h"
#include "tests/yarn/crossing_states.h"

namespace wl {
namespace {

constexpr double kPi = std::numbers::pi;

CirioShearTerm make_term(double kx_L) {
  CirioShearTerm t;
  t.add({0, 1, 2, 3, 4, 5, 6, 7, 8}, kx_L);
  return t;
}

Eigen::Matrix<double, 9, 1> force(const Term& t, const test::LocalState& s) {
  Eigen::Matrix<double, 9, 1> f = Eigen::Matrix<double, 9, 1>::Zero();
  t.evaluate(0, s.q.data(), s.v.data(), ElementOutput{f.data()});
  return f;
}

TEST(CirioShearTerm, DerivativesMatchFiniteDifferences) {
  const CirioShearTerm t = make_term(2.5);
  std::vector<test::LocalState> states;
  for (double phi : {0.15, 0.6, 1.2, kPi / 2, 2.0, 2.9})
    states.push_back(test::nudged(test::crossing_state(phi, 1.1, 0.8), 0.02));
  states.push_back(test::crossing_state(1.0, 0.9, 1.3));
  auto r = test::check_element(t, 0, states);
  EXPECT_TRUE(r.ok) << r.detail;
}

TEST(CirioShearTerm, ForcesMatchSeedFormula) {
  // Cirio et al. 2016 eqs. (43)–(45): F_x1 = k_x L (φ−π/2)/(l1 sin φ) P1 d3, F_x3 (1↔3), F_x0 = −(F_x1 + F_x3).
  const double kL = 1.7;
  const CirioShearTerm t = make_term(kL);
  for (double phi : {0.4, 1.1, 2.3}) {
    const auto s = test::nudged(test::crossing_state(phi, 1.2, 0.7), 0.05);
    Eigen::Map<const Vec3> x0(s.q.data()), x1(s.q.data() + 3), x3(s.q.data() + 6);
    const double l1 = (x1 - x0).norm(), l3 = (x3 - x0).norm();
    const Vec3 d1 = (x1 - x0) / l1, d3 = (x3 - x0) / l3;
    const double ph = std::acos(d1.dot(d3));
    const Mat3 P1 = Mat3::Identity() - d1 * d1.transpose(), P3 = Mat3::Identity() - d3 * d3.transpose();
    const Vec3 F1 = kL * (ph - kPi / 2) / (l1 * std::sin(ph)) * P1 * d3;
    const Vec3 F3 = kL * (ph - kPi / 2) / (l3 * std::sin(ph)) * P3 * d1;
    const auto f = force(t, s);
    EXPECT_LT((f.segment<3>(3) - F1).norm(), 1e-12 * (1 + F1.norm()));
    EXPECT_LT((f.segment<3>(6) - F3).norm(), 1e-12 * (1 + F3.norm()));
    EXPECT_LT((f.head<3>() + F1 + F3).norm(), 1e-12 * (1 + F1.norm()));
  }
}

TEST(CirioShearTerm, RestAtRightAngleAndRestoring) {
  const CirioShearTerm t = make_term(1.0);
  const auto rest = test::crossing_state(kPi / 2, 1.0, 1.0);
  EXPECT_LT(t.energy(0, rest.q.data()), 1e-20);
  EXPECT_LT(force(t, rest).norm(), 1e-12);
  // Closed angle: the force on x3 opens it (moves x3 away from x1), open angle: closes it.
  for (double phi : {1.0, 2.2}) {
    const auto s = test::crossing_state(phi, 1.0, 1.0);
    auto moved = s;
    const auto f = force(t, s);
    for (int i = 0; i < 9; ++i) moved.q[i] += 1e-4 * f[i];
    const double before = test::crossing_angle_of(s), after = test::crossing_angle_of(moved);
    EXPECT_LT(std::abs(after - kPi / 2), std::abs(before - kPi / 2)) << "phi " << phi;
  }
}

TEST(CirioShearTerm, DegenerateCrossingGivesZeroForce) {
  const CirioShearTerm t = make_term(1.0);
  test::LocalState s{{0, 0, 0, 1, 0, 0, 2, 0, 0}, std::vector<double>(9, 0.0)};  // φ = 0
  Eigen::Matrix<double, 9, 9> K = Eigen::Matrix<double, 9, 9>::Zero();
  Eigen::Matrix<double, 9, 1> f = Eigen::Matrix<double, 9, 1>::Zero();
  t.evaluate(0, s.q.data(), s.v.data(), ElementOutput{f.data(), K.data()});
  EXPECT_TRUE(f.allFinite() && K.allFinite());
  EXPECT_EQ(f.norm(), 0.0);
  EXPECT_NEAR(t.energy(0, s.q.data()), 0.5 * kPi * kPi / 4, 1e-12);
}

TEST(CirioShearTerm, RejectsNegativeStiffness) {
  CirioShearTerm t;
  EXPECT_THROW(t.add({0, 1, 2, 3, 4, 5, 6, 7, 8}, -1.0), std::invalid_argument);
}

}  // namespace
}  // namespace wl
