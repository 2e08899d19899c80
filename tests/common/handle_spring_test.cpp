// HandleSpringTerm: FD check, the force pulls the point toward its target,
// and a moving target follows its prescribed motion (docs/models.md §3.10).
#include <gtest/gtest.h>

#include <cmath>

#include "models/common/handle_spring.h"
#include "models/model_factory.h"
#include "tests/support/fd_check.h"

namespace wl {
namespace {

TEST(HandleSpringTerm, ForcesAndJacobianMatchFiniteDifferences) {
  HandleSpringTerm t;
  t.add({0, 1, 2}, Vec3(0.1, -0.2, 5.0), 1e4);
  t.add({3, 4, 5}, Vec3(0, 0, 0), 2.5);
  std::vector<test::LocalState> states = {{{0.1, -0.2, 5.0}, {0, 0, 0}},        // at the anchor
                                          {{0.1001, -0.2, 4.9995}, {1, 0, 0}},  // near
                                          {{-3.0, 2.0, 1.0}, {0, 2, 0}}};       // far
  for (int e = 0; e < 2; ++e) {
    auto r = test::check_element(t, e, states);
    EXPECT_TRUE(r.ok) << r.detail;
  }
}

TEST(HandleSpringTerm, PullsTowardAnchor) {
  HandleSpringTerm t;
  const Vec3 anchor(1.0, 2.0, 3.0);
  t.add({0, 1, 2}, anchor, 100.0);
  const Vec3 x(1.5, 2.0, 2.0), v = Vec3::Zero();
  Vec3 f = Vec3::Zero();
  t.evaluate(0, x.data(), v.data(), ElementOutput{f.data(), nullptr, nullptr, nullptr});
  EXPECT_LT((f - 100.0 * (anchor - x)).norm(), 1e-12);
  EXPECT_NEAR(t.energy(0, x.data()), 0.5 * 100.0 * 1.25, 1e-12);
}

// Target moving at w = (−0.5, 0, 0.2) m/s from 10 ms to 30 ms.
HandleSpringTerm moving_handle() {
  HandleSpringTerm t;
  t.add({0, 1, 2}, Vec3(0.1, -0.2, 5.0), 1e4, HandleMotion{Vec3(-0.5, 0.0, 0.2), 0.01, 0.03});
  return t;
}

TEST(HandleSpringTerm, MovingTargetFollowsItsMotion) {
  const HandleSpringTerm t = moving_handle();
  const Vec3 a0(0.1, -0.2, 5.0), w(-0.5, 0.0, 0.2);
  EXPECT_EQ(t.target(0, 0.0), a0);
  EXPECT_EQ(t.target(0, 0.01), a0);
  EXPECT_LT((t.target(0, 0.02) - (a0 + 0.01 * w)).norm(), 1e-15);
  EXPECT_LT((t.target(0, 0.03) - (a0 + 0.02 * w)).norm(), 1e-15);
  EXPECT_LT((t.target(0, 0.5) - (a0 + 0.02 * w)).norm(), 1e-15);  // held after the stop
  HandleSpringTerm forever;
  forever.add({0, 1, 2}, a0, 1.0, HandleMotion{w});
  EXPECT_LT((forever.target(0, 2.0) - (a0 + 2.0 * w)).norm(), 1e-15);
}

// The force, energy and Jacobian at the time of the last evaluation (prepare),
// checked against differences at a time inside the motion.
TEST(HandleSpringTerm, MovingTargetForcesMatchFiniteDifferences) {
  HandleSpringTerm t = moving_handle();
  Vec x(3), v = Vec::Zero(3);
  x << 0.1, -0.2, 5.0;
  t.prepare(EvalContext{0.025, &x, &v});
  const Vec3 a = t.target(0, 0.025);
  Vec3 f = Vec3::Zero();
  t.evaluate(0, x.data(), v.data(), ElementOutput{f.data()});
  EXPECT_LT((f - 1e4 * (a - Vec3(x))).norm(), 1e-9);
  EXPECT_GT(f.norm(), 10.0);  // the target has left the node: 7.5 mm · 10⁴ N/m
  auto r = test::check_element(t, 0, {{{0.1, -0.2, 5.0}, {0, 0, 0}}, {{0.09, -0.2, 5.004}, {1, 0, 0}}});
  EXPECT_TRUE(r.ok) << r.detail;
  // A clone keeps the time.
  const auto c = t.clone();
  EXPECT_EQ(c->energy(0, x.data()), t.energy(0, x.data()));
  EXPECT_GT(t.energy(0, x.data()), 0.0);
}

// Both models build the scene's moving handle and read t from the evaluation:
// with every other term off, the force on the held node at its rest position
// is k·w·(t − t_start) inside the motion and k·w·(t_stop − t_start) after it.
TEST(HandleSpringTerm, BothModelsMoveTheTargetWithTheEvaluationTime) {
  Scene s = parse_scene(
      "[cloth]\nwarps = 5\nwefts = 5\n[[handles]]\nnode = [2, 4]\nstiffness_N_per_m = 100\n"
      "velocity_m_per_s = [0.3, -0.1, 0.2]\nstart_s = 0.01\nstop_s = 0.02\n"
      "[terms]\nstretch = false\nbending = false\nshear = false\nparallel_contact = false\nfriction = false\n"
      "gravity = false\nwind = false\ninertia = false\n",
      "moving_handle.toml");
  const Vec3 w(0.3, -0.1, 0.2);
  for (const std::string name : {"yarn", "fem"}) {
    auto model = make_model(s, name);
    const Vec q = model->initial_q(), v = model->initial_v();
    Evaluation ev;
    allocate_evaluation(*model, ev);
    // The held node's x DoF: the largest force once the target moved (w's largest component is x).
    model->evaluate(0.015, q, v, kForce, ev);
    Eigen::Index node = 0;
    ev.force.cwiseAbs().maxCoeff(&node);
    EXPECT_LT((ev.force.segment<3>(node) - 100.0 * 0.005 * w).norm(), 1e-12) << name;
    EXPECT_NEAR(ev.force.norm(), 100.0 * 0.005 * w.norm(), 1e-12) << name;
    for (const auto& [t, moved] : {std::pair{0.005, 0.0}, std::pair{0.01, 0.0}, std::pair{0.5, 0.01}}) {
      model->evaluate(t, q, v, kForce, ev);
      EXPECT_LT((ev.force.segment<3>(node) - 100.0 * moved * w).norm(), 1e-12) << name << " t = " << t;
    }
  }
}

TEST(HandleSpringTerm, RejectsBadParameters) {
  HandleSpringTerm t;
  EXPECT_THROW(t.add({0, 1, 2}, Vec3::Zero(), -1.0), std::invalid_argument);
  EXPECT_THROW(t.add({0, 1, 2}, Vec3(0, std::nan(""), 0), 1.0), std::invalid_argument);
  EXPECT_THROW(t.add({0, 1, 2}, Vec3::Zero(), 1.0, HandleMotion{Vec3(0, 0, INFINITY)}), std::invalid_argument);
  EXPECT_THROW(t.add({0, 1, 2}, Vec3::Zero(), 1.0, HandleMotion{Vec3(1, 0, 0), 0.02, 0.01}), std::invalid_argument);
  EXPECT_THROW(t.add({0, 1, 2}, Vec3::Zero(), 1.0, HandleMotion{Vec3(1, 0, 0), NAN}), std::invalid_argument);
  EXPECT_EQ(t.num_elements(), 0);
}

}  // namespace
}  // namespace wl
