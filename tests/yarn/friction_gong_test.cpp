// Gong friction (docs/models.md §3.7.2): the law's partial derivatives (sign of §4.16),
// element Jacobians against finite differences with F_u, F_n frozen in each
// regime, the regimes themselves (stick ≈ spring, breakaway = average, kinetic
// ≈ −μF_n − d_f u̇, also for negative pulls, §4.15), and the anchor update.
#include <gtest/gtest.h>

#include <cmath>

#include "models/yarn/terms/friction_gong.h"
#include "tests/support/fd_check.h"

namespace wl {
namespace {

// Force of element e at local u, u̇.
double force_of(const Term& t, int e, double u, double udot) {
  double f = 0.0;
  t.evaluate(e, &u, &udot, ElementOutput{&f});
  return f;
}

// Freezes F_u (the stage-0 force per DoF) and F_n (per node) as the model would.
void prepare(Term& t, const Vec& Fu, const std::vector<double>& Fn, const Vec& q, const Vec& v) {
  EvalContext ctx{0.0, &q, &v, &Fu, Fn};
  t.prepare(ctx);
}

TEST(GongFrictionLaw, PartialDerivativesMatchFiniteDifferences) {
  const double mu = 0.5, kf = 1000, p = 10, h = 1e-6;
  for (double d : {-0.2, -0.01, 0.0, 0.03, 0.3})
    for (double Fu : {-2.0, -0.4, 0.1, 0.45, 0.5, 0.7, 3.0})
      for (double Fn : {0.0, 1.0, 1.3}) {
        const auto r = gong_friction_law(d, Fu, Fn, mu, kf, p);
        auto F = [&](double dd, double fu, double fn) { return gong_friction_law(dd, fu, fn, mu, kf, p).force; };
        const double fd_d = (F(d + h, Fu, Fn) - F(d - h, Fu, Fn)) / (2 * h);
        const double fd_u = (F(d, Fu + h, Fn) - F(d, Fu - h, Fn)) / (2 * h);
        const double fd_n = (F(d, Fu, Fn + h) - F(d, Fu, Fn - h)) / (2 * h);
        const std::string at =
            " at du=" + std::to_string(d) + " Fu=" + std::to_string(Fu) + " Fn=" + std::to_string(Fn);
        EXPECT_NEAR(r.d_delta, fd_d, 1e-6 * (1 + std::abs(fd_d))) << at;
        EXPECT_NEAR(r.d_Fu, fd_u, 1e-6 * (1 + std::abs(fd_u))) << at;
        EXPECT_NEAR(r.d_Fn, fd_n, 1e-6 * (1 + std::abs(fd_n))) << at;
      }
}

TEST(GongFrictionTerm, DerivativesMatchFiniteDifferencesInEveryRegime) {
  // μF_n = 0.5; F_u from far below to far above breakaway, both signs.
  std::vector<double> Fn{1.0};
  const std::vector<double> pulls{0.0, 0.05, 0.45, 0.5, 0.55, 2.0, -2.0};
  GongFrictionTerm t(0.5, 1000, 1000, 10);
  for (size_t i = 0; i < pulls.size(); ++i) t.add(static_cast<int>(i), 0, 0.1 * i);
  Vec Fu = Eigen::Map<const Vec>(pulls.data(), pulls.size());
  Vec q = Vec::Zero(pulls.size()), v = Vec::Zero(pulls.size());
  prepare(t, Fu, Fn, q, v);
  for (int e = 0; e < t.num_elements(); ++e) {
    std::vector<test::LocalState> states;
    for (double d : {-0.3, -0.02, 0.0, 0.01, 0.2}) states.push_back({{0.1 * e + d}, {0.3 - d}});
    auto r = test::check_element(t, e, states);
    EXPECT_TRUE(r.ok) << "F_u = " << pulls[e] << "\n" << r.detail;
  }
}

TEST(GongFrictionTerm, RegimesOfTheLaw) {
  const double mu = 0.5, kf = 1000, df = 200, p = 1e4;
  std::vector<double> Fn{2.0};  // μF_n = 1 N
  GongFrictionTerm t(mu, kf, df, p);
  for (int i = 0; i < 5; ++i) t.add(i, 0, 0.0);
  Vec Fu(5);
  Fu << 0.0, 0.1, 1.0, 3.0, -3.0;  // rest, stick, breakaway, kinetic, kinetic (negative pull)
  prepare(t, Fu, Fn, Vec::Zero(5), Vec::Zero(5));
  const double ud = 0.02;

  EXPECT_NEAR(force_of(t, 0, 0.0, 0.0), 0.0, 1e-15);  // F_u = 0, δu = 0: no force

  const double d = 2e-4;  // stick: Hooke spring plus damping
  EXPECT_NEAR(force_of(t, 1, d, ud), -kf * d - df * ud, 1e-6 * kf * d);

  const double at_break = -0.5 * (kf * d + std::tanh(p * d) * mu * Fn[0]) - df * ud;
  EXPECT_NEAR(force_of(t, 2, d, ud), at_break, 1e-12);

  const double far = 1e-3;  // p δu = 10: kinetic friction, independent of δu
  EXPECT_NEAR(force_of(t, 3, far, ud), -mu * Fn[0] - df * ud, 1e-6);
  EXPECT_NEAR(force_of(t, 3, 3 * far, ud), -mu * Fn[0] - df * ud, 1e-6);
  EXPECT_NEAR(force_of(t, 4, -far, -ud), mu * Fn[0] + df * ud, 1e-6);  // docs/models.md §4.15: |F_u|

  const auto s = t.sliding_state();
  EXPECT_LT(s[1], 1e-12);
  EXPECT_GT(s[3], 1 - 1e-12);
  EXPECT_GT(s[4], 1 - 1e-12);
}

TEST(GongFrictionTerm, AnchorMovesOnlyWhenSliding) {
  std::vector<double> Fn{1.0, 1.0};
  GongFrictionTerm t(0.5, 1000, 1000, 10);
  t.add(0, 0, 0.25);  // stick: |F_u| = 0.2 < μF_n = 0.5
  t.add(1, 1, 0.75);  // slide: |F_u| = 0.9 > μF_n
  Vec Fu(2), q(2), v(2);
  Fu << 0.2, -0.9;
  q << 0.26, 0.74;
  v << 0.3, -0.4;
  prepare(t, Fu, Fn, q, v);
  const double h = 1e-3;
  EvalContext ctx{0.0, &q, &v, nullptr};  // F_u from the last prepare
  t.accept_step(ctx, h);
  EXPECT_NEAR(t.anchor(0), 0.25, 1e-15);
  EXPECT_NEAR(t.anchor(1), 0.75 + v[1] * h, 1e-15);
  // With the accepted stage-0 force in the context, that force decides.
  Fu << 0.9, 0.1;
  ctx.force_so_far = &Fu;
  t.accept_step(ctx, h);
  EXPECT_NEAR(t.anchor(0), 0.25 + v[0] * h, 1e-15);
  EXPECT_NEAR(t.anchor(1), 0.75 + v[1] * h, 1e-15);
}

TEST(GongFrictionTerm, ReadsFrozenInputsInPrepare) {
  std::vector<double> Fn{0.0, 4.0};
  GongFrictionTerm t(0.5, 1000, 10, 10);
  t.add(1, 1, 0.0);
  Vec Fu(2);
  Fu << 9.0, -0.3;
  prepare(t, Fu, Fn, Vec::Zero(2), Vec::Zero(2));
  EXPECT_EQ(t.tangential_force(0), -0.3);
  EXPECT_EQ(t.contact_force(0), 4.0);
  EXPECT_FALSE(t.conservative());
  EXPECT_TRUE(t.has_velocity_jacobian());
  EXPECT_EQ(t.stage(), 1);
  EXPECT_EQ(t.name(), "friction");
}

TEST(GongFrictionTerm, RejectsBadParameters) {
  std::vector<double> Fn{0.0};
  EXPECT_THROW(GongFrictionTerm(-0.1, 1000, 1000, 10), std::invalid_argument);
  EXPECT_THROW(GongFrictionTerm(0.5, 1000, 1000, 0), std::invalid_argument);
  GongFrictionTerm t(0.5, 1000, 1000, 10);
  t.add(0, 3, 0.0);  // node 3 of a one-node table
  EXPECT_THROW(prepare(t, Vec::Zero(1), Fn, Vec::Zero(1), Vec::Zero(1)), std::out_of_range);
}

}  // namespace
}  // namespace wl
