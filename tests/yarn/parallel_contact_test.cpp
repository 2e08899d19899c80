// ParallelContactTerm: FD checks in both regimes, no force when Δu ≥ d, ends
// pushed apart when active; parallel_contact_distance rule (docs/models.md §4.14).
#include <gtest/gtest.h>

#include "models/yarn/terms/parallel_contact.h"
#include "tests/support/fd_check.h"

namespace wl {
namespace {

constexpr double kKcL = 1.0 * 1e-3;  // k_c L, N
constexpr double kD = 2e-3;          // contact distance, m

ParallelContactTerm make_term() {
  ParallelContactTerm t;
  t.add({0, 1}, kKcL, kD);
  return t;
}

Eigen::Vector2d force_at(const ParallelContactTerm& t, double u0, double u1) {
  Eigen::Vector2d q(u0, u1), v = Eigen::Vector2d::Zero(), f = Eigen::Vector2d::Zero();
  t.evaluate(0, q.data(), v.data(), ElementOutput{f.data(), nullptr, nullptr, nullptr});
  return f;
}

TEST(ParallelContactTerm, ActiveRegimeMatchesFiniteDifferences) {
  auto t = make_term();
  // Δu well below d (FD step 1e-7 stays away from the kink at Δu = d).
  std::vector<test::LocalState> states = {{{0.0, 1e-3}, {0, 0}}, {{0.5, 0.5005}, {1, -1}}, {{1.0, 0.999}, {0, 0}}};
  auto r = test::check_element(t, 0, states);
  EXPECT_TRUE(r.ok) << r.detail;
  Eigen::Vector2d q(0.0, 1e-3), v(0, 0), f;
  Eigen::Matrix2d k;
  t.evaluate(0, q.data(), v.data(), ElementOutput{f.data(), k.data(), nullptr, nullptr});
  EXPECT_GT(k.norm(), 0.0);  // the active check really compared a non-zero Jacobian
}

TEST(ParallelContactTerm, InactiveRegimeHasNoForceAndNoJacobian) {
  auto t = make_term();
  for (const Eigen::Vector2d& q : {Eigen::Vector2d(0.0, 3e-3), Eigen::Vector2d(0.5, 0.6)}) {
    Eigen::Vector2d v(1, -1), f = Eigen::Vector2d::Zero();
    Eigen::Matrix2d k = Eigen::Matrix2d::Zero();  // outputs arrive zero-filled
    t.evaluate(0, q.data(), v.data(), ElementOutput{f.data(), k.data(), nullptr, nullptr});
    EXPECT_EQ(f.norm(), 0.0) << q.transpose();
    EXPECT_EQ(k.norm(), 0.0) << q.transpose();
  }
}

TEST(ParallelContactTerm, NoForceWhenSeparatedByAtLeastD) {
  auto t = make_term();
  EXPECT_EQ(force_at(t, 0.0, kD).norm(), 0.0);
  EXPECT_EQ(force_at(t, 0.1, 0.1 + 1.5 * kD).norm(), 0.0);
  const double q[2] = {0.0, 5 * kD};
  EXPECT_EQ(t.energy(0, q), 0.0);
}

TEST(ParallelContactTerm, PushesEndsApartWhenActive) {
  auto t = make_term();
  const double du = 0.25 * kD;
  const Eigen::Vector2d f = force_at(t, 0.3, 0.3 + du);
  EXPECT_LT(f(0), 0.0);  // u0 pushed back
  EXPECT_GT(f(1), 0.0);  // u1 pushed forward
  EXPECT_NEAR(f(1), kKcL * (kD - du), 1e-15);
  EXPECT_EQ(f(0) + f(1), 0.0);  // internal force: no net push along the yarn
}

TEST(ParallelContactTerm, DistanceIsFourRWhenSignsDifferElseTwoR) {
  const double R = 5e-4;
  EXPECT_DOUBLE_EQ(parallel_contact_distance(1, -1, R), 4 * R);
  EXPECT_DOUBLE_EQ(parallel_contact_distance(-1, 1, R), 4 * R);
  EXPECT_DOUBLE_EQ(parallel_contact_distance(1, 1, R), 2 * R);
  EXPECT_DOUBLE_EQ(parallel_contact_distance(-1, -1, R), 2 * R);
  EXPECT_THROW(parallel_contact_distance(0, 1, R), std::invalid_argument);
  EXPECT_THROW(parallel_contact_distance(1, 1, -R), std::invalid_argument);
}

TEST(ParallelContactTerm, RejectsBadParameters) {
  ParallelContactTerm t;
  EXPECT_THROW(t.add({0, 1}, -1.0, kD), std::invalid_argument);
  EXPECT_THROW(t.add({0, 1}, kKcL, 0.0), std::invalid_argument);
}

}  // namespace
}  // namespace wl
