// GravityTerm: analytic force and Jacobian against finite differences, and the
// total force on a yarn at rest equals its total mass times g.
#include <gtest/gtest.h>

#include "models/core/assembly.h"
#include "models/yarn/terms/gravity.h"
#include "tests/support/fd_check.h"

namespace wl {
namespace {

TEST(GravityTerm, ForcesAndJacobianMatchFiniteDifferences) {
  GravityTerm t(Vec3(0.3, -0.5, -9.81));
  t.add({0, 1, 2, 3, 4, 5, 6, 7}, 0.002);
  std::vector<test::LocalState> states = {
      {{0, 0, 0, 1e-3, 0, 0, 0, 1e-3}, {0, 0, 0, 0, 0, 0, 0, 0}},                        // at rest
      {{0.4, -1.0, 2.0, 0.1, 0.7, -0.3, 0.2, 1.9}, {1, -2, 0.5, 0.3, 0, 1, 0.2, -0.4}},  // far from rest
      {{-2.0, 0.3, 5.0, 1.0, 1.0, 1.0, -1.0, -0.5}, {0, 0, 0, 0, 0, 0, 0, 0}}};
  auto r = test::check_element(t, 0, states);
  EXPECT_TRUE(r.ok) << r.detail;
}

// A yarn of 4 segments with different densities, frozen end coordinates; the
// x-forces summed over all nodes equal (Σ ρ_s Δu_s)·g.
TEST(GravityTerm, TotalForceOnYarnAtRestIsTotalMassTimesG) {
  const Vec3 g(0.0, 0.0, -9.81);
  GravityTerm t(g);
  auto u_index = [](int i) { return i == 0 ? encode_constant(0) : i == 4 ? encode_constant(1) : 14 + i; };
  const double rho[4] = {0.002, 0.003, 0.002, 0.005};
  for (int i = 0; i < 4; ++i)
    t.add({3 * i, 3 * i + 1, 3 * i + 2, 3 * i + 3, 3 * i + 4, 3 * i + 5, u_index(i), u_index(i + 1)}, rho[i]);
  const double L = 1e-3;
  const double u[5] = {0.0, 1.1 * L, 1.9 * L, 3.2 * L, 4.0 * L};
  Vec q(18), v = Vec::Zero(18), constants(2);
  for (int i = 0; i < 5; ++i) q.segment<3>(3 * i) = Vec3(i * L, 0.3 * L * (i % 2), -0.2 * L * i * i);
  q.segment<3>(15) = Vec3(u[1], u[2], u[3]);
  constants << u[0], u[4];
  Assembly assembly(18, {&t});
  Vec f = Vec::Zero(18);
  assembly.add_stage(0, q, v, constants, {}, f, nullptr, nullptr, nullptr);
  Vec3 total = Vec3::Zero();
  for (int i = 0; i < 5; ++i) total += f.segment<3>(3 * i);
  double mass = 0.0;
  for (int i = 0; i < 4; ++i) mass += rho[i] * (u[i + 1] - u[i]);
  EXPECT_LT((total - mass * g).norm(), 1e-12 * mass * g.norm()) << total.transpose();
  // Gravity pulls down: the potential energy decreases when the yarn is lowered.
  Vec q_low = q;
  for (int i = 0; i < 5; ++i) q_low(3 * i + 2) -= 0.01;
  EXPECT_LT(assembly.energy(q_low, constants), assembly.energy(q, constants));
}

TEST(GravityTerm, RejectsBadInput) {
  EXPECT_THROW(GravityTerm(Vec3(0, 0, std::nan(""))), std::invalid_argument);
  GravityTerm t(Vec3(0, 0, -9.81));
  EXPECT_THROW(t.add({0, 1, 2, 3, 4, 5, 6, 7}, -1.0), std::invalid_argument);
}

}  // namespace
}  // namespace wl
