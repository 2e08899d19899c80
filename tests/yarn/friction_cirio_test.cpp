// Cirio stick/slip friction (docs/models.md §3.7.3): Jacobians in both modes, the
// return mapping in accept_step (anchor moves only when slipping, to exactly
// k_f|u − ū| = μF_n), return to stick on reversal, and a pulled crossing under
// backward Euler that sticks below μF_n and slides at (F − μF_n)/d_f above it.
#include <gtest/gtest.h>

#include <cmath>

#include "models/yarn/terms/friction_cirio.h"
#include "tests/support/fd_check.h"

namespace wl {
namespace {

double force_of(const Term& t, int e, double u, double udot) {
  double f = 0.0;
  t.evaluate(e, &u, &udot, ElementOutput{&f});
  return f;
}

// As the model does: inputs frozen at the accepted state, the step accepted,
// the inputs frozen again for the next step.
void accept(Term& t, const std::vector<double>& Fn, const Vec& q, const Vec& v, double h = 1e-3) {
  EvalContext ctx{0.0, &q, &v, nullptr, Fn};
  t.prepare(ctx);
  t.accept_step(ctx, h);
  t.prepare(ctx);
}

TEST(CirioFrictionTerm, DerivativesMatchFiniteDifferencesInBothModes) {
  std::vector<double> Fn{1.0};
  CirioFrictionTerm t(0.5, 1000, 20, 10);
  t.add(0, 0, 0.0);  // stays stuck: k_f|δ| = 0.1 < 0.5
  t.add(1, 0, 0.0);  // slips: k_f|δ| = 2 > 0.5
  t.add(2, 0, 0.0);  // slips the other way
  Vec q(3), v(3);
  q << 1e-4, 2e-3, -2e-3;
  v << 0.1, 0.2, -0.2;
  accept(t, Fn, q, v);
  ASSERT_EQ(t.slip_direction(0), 0);
  ASSERT_EQ(t.slip_direction(1), 1);
  ASSERT_EQ(t.slip_direction(2), -1);
  for (int e = 0; e < 3; ++e) {
    std::vector<test::LocalState> states{{{q[e]}, {v[e]}}, {{q[e] + 3e-4}, {-0.5}}, {{0.0}, {0.0}}};
    test::FdOptions opt;
    opt.constant_force = e != 0;  // slipping: −μF_n sign − d_f u̇ does not depend on u
    auto r = test::check_element(t, e, states, opt);
    EXPECT_TRUE(r.ok) << r.detail;
  }
}

TEST(CirioFrictionTerm, StickIsASpringAndKeepsItsAnchor) {
  std::vector<double> Fn{2.0};
  CirioFrictionTerm t(0.5, 1000, 20, 10);
  t.add(0, 0, 0.3);
  Vec q(1), v(1);
  q << 0.3 + 9e-4;  // k_f|δ| = 0.9 < μF_n = 1
  v << 0.4;
  accept(t, Fn, q, v);
  EXPECT_EQ(t.anchor(0), 0.3);
  EXPECT_EQ(t.sliding_state()[0], 0.0);
  EXPECT_NEAR(force_of(t, 0, 0.3 + 5e-4, 0.1), -1000 * 5e-4 - 20 * 0.1, 1e-12);
}

TEST(CirioFrictionTerm, SlipMovesAnchorToTheFrictionLimit) {
  std::vector<double> Fn{2.0};
  const double mu = 0.5, kf = 1000, df = 20;
  CirioFrictionTerm t(mu, kf, df, 10);
  t.add(0, 0, 0.3);
  Vec q(1), v(1);
  q << 0.3 - 3e-3;  // k_f|δ| = 3 > μF_n = 1, pulled towards −u
  v << -0.2;
  accept(t, Fn, q, v);
  EXPECT_EQ(t.sliding_state()[0], 1.0);
  EXPECT_EQ(t.slip_direction(0), -1);
  EXPECT_NEAR(kf * std::abs(q[0] - t.anchor(0)), mu * Fn[0], 1e-12);
  EXPECT_LT(q[0], t.anchor(0));  // the anchor trails the crossing
  // Continuous at the switch: spring force at the moved anchor = slip force.
  EXPECT_NEAR(-kf * (q[0] - t.anchor(0)), mu * Fn[0], 1e-12);
  EXPECT_NEAR(force_of(t, 0, q[0], v[0]), mu * Fn[0] - df * v[0], 1e-12);
  EXPECT_NEAR(force_of(t, 0, q[0] - 1e-3, v[0]), mu * Fn[0] - df * v[0], 1e-12);

  // Keeps slipping while it moves on; sticks again when the motion reverses.
  const double anchor = t.anchor(0);
  // A clone carries the history (anchor, slip mode) and the frozen F_n, and
  // moves on alone (docs/design.md §3.4).
  auto copy = t.clone();
  const auto& c = static_cast<const CirioFrictionTerm&>(*copy);
  EXPECT_EQ(c.anchor(0), anchor);
  EXPECT_EQ(c.slip_direction(0), -1);
  EXPECT_EQ(force_of(c, 0, q[0] - 1e-3, v[0]), force_of(t, 0, q[0] - 1e-3, v[0]));
  q[0] -= 1e-3;
  accept(t, Fn, q, v);
  EXPECT_EQ(c.anchor(0), anchor);
  EXPECT_EQ(t.slip_direction(0), -1);
  EXPECT_NEAR(t.anchor(0), anchor - 1e-3, 1e-15);
  q[0] += 2e-4;
  v[0] = 0.2;
  const double before = t.anchor(0);
  accept(t, Fn, q, v);
  EXPECT_EQ(t.slip_direction(0), 0);
  EXPECT_EQ(t.anchor(0), before);
}

// One crossing of mass m pulled by F_ext, advanced by backward Euler with the
// term's force and Jacobians (Newton on the step velocity).
struct PulledCrossing {
  double m = 1e-3, h = 1e-3, u = 0.0, v = 0.0;
  void step(CirioFrictionTerm& t, const std::vector<double>& Fn, double F_ext) {
    Vec q(1), vv(1);
    double v1 = v;
    for (int it = 0; it < 5; ++it) {
      const double u1 = u + h * v1;
      double f = 0, K = 0, D = 0;
      t.evaluate(0, &u1, &v1, ElementOutput{&f, &K, &D});
      const double r = m * (v1 - v) / h - F_ext - f;
      v1 -= r / (m / h - h * K - D);
    }
    v = v1;
    u += h * v1;
    q << u;
    vv << v;
    accept(t, Fn, q, vv, h);
  }
};

TEST(CirioFrictionTerm, PulledCrossingSticksBelowAndSlidesAboveTheLimit) {
  std::vector<double> Fn{1.0};
  const double mu = 0.5, kf = 1000, df = 1;
  {
    CirioFrictionTerm t(mu, kf, df, 10);
    t.add(0, 0, 0.0);
    PulledCrossing c;
    for (int i = 0; i < 2000; ++i) c.step(t, Fn, 0.3);
    EXPECT_NEAR(c.u, 0.3 / kf, 1e-9);  // a spring at rest
    EXPECT_EQ(t.anchor(0), 0.0);
    EXPECT_EQ(t.sliding_state()[0], 0.0);
  }
  {
    CirioFrictionTerm t(mu, kf, df, 10);
    t.add(0, 0, 0.0);
    PulledCrossing c;
    for (int i = 0; i < 1000; ++i) c.step(t, Fn, 0.8);
    EXPECT_NEAR(c.v, (0.8 - mu * Fn[0]) / df, 1e-6);  // kinetic friction + damping balance the pull
    EXPECT_EQ(t.sliding_state()[0], 1.0);
    EXPECT_NEAR(kf * (c.u - t.anchor(0)), mu * Fn[0], 1e-9);
  }
}

TEST(CirioFrictionTerm, ReadsNormalForceInPrepareAndRejectsBadInput) {
  std::vector<double> Fn{0.0, 3.0};
  CirioFrictionTerm t(0.5, 1000, 1, 10);
  t.add(0, 1, 0.0);
  Vec q = Vec::Zero(1), v = Vec::Zero(1);
  EvalContext ctx{0.0, &q, &v, &q, Fn};
  t.prepare(ctx);
  EXPECT_EQ(t.contact_force(0), 3.0);
  EXPECT_FALSE(t.conservative());
  EXPECT_TRUE(t.has_velocity_jacobian());
  EXPECT_EQ(t.stage(), 1);
  EXPECT_EQ(t.name(), "friction");
  EXPECT_THROW(CirioFrictionTerm(0.5, 0.0, 1, 10), std::invalid_argument);
  t.add(0, 2, 0.0);  // node 2 of a two-node table
  EXPECT_THROW(t.prepare(ctx), std::out_of_range);
}

}  // namespace
}  // namespace wl
