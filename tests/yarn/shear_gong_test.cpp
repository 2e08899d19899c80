// Gong shear with lock (docs/models.md §3.4.3): derivatives against finite
// differences (F_n frozen) at angles on both sides of φ̄ and around the lock
// angle; k_sh > 0 on (0, π) thanks to the mirrored angle (docs/models.md §4.12); the locked
// stiffness rises steeply below φ_l; F_n and SπR² enter as (1 + F_n) SπR².
#include <gtest/gtest.h>

#include <numbers>

#include "models/yarn/terms/shear_gong.h"
#include "tests/yarn/crossing_states.h"

namespace wl {
namespace {

constexpr double kPi = std::numbers::pi;
const std::array<int, 9> kStencil{0, 1, 2, 3, 4, 5, 6, 7, 8};

// Freezes F_n (per node) in the term, as the model's evaluation does.
void freeze(GongShearTerm& t, const std::vector<double>& Fn) {
  t.prepare(EvalContext{0.0, nullptr, nullptr, nullptr, Fn});
}

std::vector<test::LocalState> states_at(const std::vector<double>& angles, double scale) {
  std::vector<test::LocalState> s;
  for (double phi : angles) {
    s.push_back(test::crossing_state(phi, 1.1 * scale, 0.9 * scale));
    s.push_back(test::nudged(test::crossing_state(phi, 0.95 * scale, 1.05 * scale, -0.5), 0.01 * scale));
  }
  return s;
}

TEST(GongShearTerm, LockedDerivativesMatchFiniteDifferences) {
  std::vector<double> Fn{0.0, 0.7};
  GongShearTerm t(1.0, 0.25, 3.0, 0.6);
  t.add(kStencil, 1, 2.0, true);
  freeze(t, Fn);
  const double pl = t.lock_angle();
  auto r =
      test::check_element(t, 0, states_at({0.15, pl - 0.05, pl, pl + 0.05, 0.9, 1.4, 1.75, 2.2, kPi - pl, 2.95}, 1.0));
  EXPECT_TRUE(r.ok) << r.detail;
}

TEST(GongShearTerm, LockedDerivativesAtYarnScale) {
  // docs/models.md §8.4 numbers: L = 1 mm, R = 0.5 mm (φ_l = π/3), S = 1000.
  std::vector<double> Fn{0.3};
  const double L = 1e-3, R = 5e-4;
  GongShearTerm t(L, R, 3.0, 0.6);
  t.add(kStencil, 0, 1000.0 * kPi * R * R, true);
  freeze(t, Fn);
  test::FdOptions opt;
  opt.rel_step = 1e-7;  // the locked stiffness varies steeply at yarn scale: a smaller truncation error
  opt.rtol = 1e-5;
  opt.floor = 1e-16;
  auto r = test::check_element(t, 0, states_at({0.3, 1.0, kPi / 3, 1.2, 1.9, 2.6}, L), opt);
  EXPECT_TRUE(r.ok) << r.detail;
}

TEST(GongShearTerm, FreeDerivativesMatchFiniteDifferences) {
  std::vector<double> Fn{1.5};
  GongShearTerm t(1.0, 0.25, 3.0, 0.6);
  t.add(kStencil, 0, 0.8, false);
  freeze(t, Fn);
  auto r = test::check_element(t, 0, states_at({0.3, 1.2, 2.0, 2.8}, 1.0));
  EXPECT_TRUE(r.ok) << r.detail;
}

TEST(GongShearTerm, StiffnessDerivativesMatchFiniteDifferences) {
  std::vector<double> Fn{0.4};
  GongShearTerm t(1.0, 0.1, 3.0, 0.6);
  t.add(kStencil, 0, 1.0, true);
  freeze(t, Fn);
  const double h = 1e-6;
  for (double phi : {0.1, 0.2, 0.5, 1.0, 1.4, 1.8, 2.5, 3.0}) {
    const auto s = t.stiffness(0, phi), sp = t.stiffness(0, phi + h), sm = t.stiffness(0, phi - h);
    const double dk = (sp.k - sm.k) / (2 * h), d2k = (sp.dk - sm.dk) / (2 * h);
    EXPECT_NEAR(s.dk, dk, 1e-6 * (1 + std::abs(dk))) << "phi " << phi;
    EXPECT_NEAR(s.d2k, d2k, 1e-5 * (1 + std::abs(d2k))) << "phi " << phi;
  }
}

TEST(GongShearTerm, StiffnessPositiveOnWholeRange) {
  for (double RL : {0.1, 0.25, 0.5}) {
    std::vector<double> Fn{0.0};
    GongShearTerm t(1.0, RL, 3.0, 0.6);
    t.add(kStencil, 0, 1.0, true);
    freeze(t, Fn);
    for (int i = 1; i < 1000; ++i) {
      const double phi = kPi * i / 1000;
      EXPECT_GT(t.stiffness(0, phi).k, 0.0) << "R/L " << RL << " phi " << phi;
    }
  }
}

TEST(GongShearTerm, StiffnessMirroredAboutRightAngle) {
  std::vector<double> Fn{0.2};
  GongShearTerm t(1.0, 0.25, 3.0, 0.6);
  t.add(kStencil, 0, 1.0, true);
  freeze(t, Fn);
  for (double d : {0.1, 0.6, 1.2}) {
    const auto lo = t.stiffness(0, kPi / 2 - d), hi = t.stiffness(0, kPi / 2 + d);
    EXPECT_NEAR(lo.k, hi.k, 1e-12 * lo.k);
    EXPECT_NEAR(lo.dk, -hi.dk, 1e-9 * (1 + std::abs(lo.dk)));
  }
}

TEST(GongShearTerm, LockedStiffnessRisesSteeplyBelowLockAngle) {
  for (double RL : {0.1, 0.25}) {
    std::vector<double> Fn{0.0};
    GongShearTerm t(1.0, RL, 3.0, 0.6);
    t.add(kStencil, 0, 1.0, true);
    freeze(t, Fn);
    const double pl = t.lock_angle(), free = 1.0;  // (1 + F_n) SπR²
    EXPECT_NEAR(pl, 2 * std::asin(RL), 1e-15);
    EXPECT_NEAR(t.stiffness(0, kPi / 2).k, free, 0.01 * free);
    EXPECT_LT(t.stiffness(0, pl + 0.8).k, 1.5 * free);  // σ = 0.6 gives a broad transition (docs/models.md §4.11)
    EXPECT_GT(t.stiffness(0, pl - 0.1).k, 20.0 * free);
    // Monotone: the more the yarns are sheared shut, the stiffer.
    double prev = t.stiffness(0, 0.01).k;
    for (double phi = 0.02; phi < pl + 0.5; phi += 0.01) {
      const double k = t.stiffness(0, phi).k;
      EXPECT_LT(k, prev) << "R/L " << RL << " phi " << phi;
      prev = k;
    }
  }
}

TEST(GongShearTerm, FreeStiffnessUsesFrozenNormalForce) {
  std::vector<double> Fn{0.0, 0.0};
  GongShearTerm t(1.0, 0.25, 3.0, 0.6);
  t.add(kStencil, 1, 2.0, false);
  freeze(t, Fn);
  const auto s = test::crossing_state(1.1, 1.0, 1.0);
  const double V0 = t.energy(0, s.q.data());
  EXPECT_NEAR(V0, 0.5 * 2.0 * 1.0 * std::pow(1.1 - kPi / 2, 2), 1e-12);
  Fn[1] = 3.0;  // the model's table changes: the term holds its own frozen copy
  EXPECT_EQ(t.energy(0, s.q.data()), V0);
  freeze(t, Fn);  // the next evaluation freezes the new F_n
  EXPECT_NEAR(t.energy(0, s.q.data()), 4.0 * V0, 1e-12);
  EXPECT_EQ(t.stiffness(0, 0.2).k, t.stiffness(0, 2.9).k);
}

TEST(GongShearTerm, RestAtRightAngle) {
  std::vector<double> Fn{0.5};
  GongShearTerm t(1.0, 0.25, 3.0, 0.6);
  t.add(kStencil, 0, 1.0, true);
  freeze(t, Fn);
  const auto s = test::crossing_state(kPi / 2, 1.0, 1.2);
  Eigen::Matrix<double, 9, 1> f = Eigen::Matrix<double, 9, 1>::Zero();
  t.evaluate(0, s.q.data(), s.v.data(), ElementOutput{f.data()});
  EXPECT_LT(f.norm(), 1e-12);
  EXPECT_LT(t.energy(0, s.q.data()), 1e-24);
}

TEST(GongShearTerm, RejectsBadParameters) {
  std::vector<double> Fn{0.0};
  EXPECT_THROW(GongShearTerm(0.0, 0.1, 3, 0.6), std::invalid_argument);
  EXPECT_THROW(GongShearTerm(1.0, 1.5, 3, 0.6), std::invalid_argument);
  EXPECT_THROW(GongShearTerm(1.0, 0.75, 3, 0.6), std::invalid_argument);  // lock angle 2 arcsin(0.75) > π/2
  EXPECT_THROW(GongShearTerm(1.0, 0.1, 3, 0.0), std::invalid_argument);
  GongShearTerm t(1.0, 0.1, 3, 0.6);
  t.add(kStencil, 5, 1.0, true);  // node 5 of a one-node table
  EXPECT_THROW(freeze(t, Fn), std::out_of_range);
  EXPECT_THROW(t.add(kStencil, 0, -1.0, true), std::invalid_argument);
}

}  // namespace
}  // namespace wl
