// The finite-difference checker must pass a correct term and fail terms that
// are wrong on purpose (wrong force, wrong ∂f/∂q, missing ∂f/∂v).
#include <gtest/gtest.h>

#include <cmath>

#include "tests/support/fd_check.h"
#include "tests/support/test_models.h"

namespace wl {
namespace {

// A zero-rest-length spring between two points with a dashpot: V = ½k|x1−x0|²,
// f_damp = −c(v1−v0) on x1. `bug` selects a deliberate error.
class SpringTerm : public StencilTerm<6> {
 public:
  enum Bug { none, force_sign, stiffness_scale, no_damping_jacobian };
  explicit SpringTerm(Bug bug) : bug_(bug) { stencils_.push_back({0, 1, 2, 3, 4, 5}); }
  std::unique_ptr<Term> clone() const override { return std::make_unique<SpringTerm>(*this); }
  std::string name() const override { return "test-spring"; }
  bool has_velocity_jacobian() const override { return bug_ != no_damping_jacobian; }
  double energy(int, const double* q) const override {
    Eigen::Map<const Vec3> x0(q), x1(q + 3);
    return 0.5 * k_ * (x1 - x0).squaredNorm();
  }
  void evaluate(int, const double* q, const double* v, const ElementOutput& out) const override {
    Eigen::Map<const Vec3> x0(q), x1(q + 3), v0(v), v1(v + 3);
    const Vec3 fx1 = -k_ * (x1 - x0) - c_ * (v1 - v0);
    const double sign = bug_ == force_sign ? -1.0 : 1.0;
    VecMap f(out.force);
    f.head<3>() = -sign * fx1;
    f.tail<3>() = sign * fx1;
    const double ks = bug_ == stiffness_scale ? 1.1 * k_ : k_;
    MatMap K(out.dfdq);
    K.setZero();
    K.topLeftCorner<3, 3>() = K.bottomRightCorner<3, 3>() = -ks * Mat3::Identity();
    K.topRightCorner<3, 3>() = K.bottomLeftCorner<3, 3>() = ks * Mat3::Identity();
    if (out.dfdv) {
      MatMap D(out.dfdv);
      D.setZero();
      D.topLeftCorner<3, 3>() = D.bottomRightCorner<3, 3>() = -c_ * Mat3::Identity();
      D.topRightCorner<3, 3>() = D.bottomLeftCorner<3, 3>() = c_ * Mat3::Identity();
    }
  }

 private:
  Bug bug_;
  double k_ = 3.0, c_ = 0.5;
};

std::vector<test::LocalState> states() {
  return {{{0, 0, 0, 1, 0.2, -0.3}, {0.1, 0, 0, 0, 0.3, 0}}, {{0.5, -1, 2, 0.1, 0.4, 0.9}, {1, 2, 3, -1, 0, 1}}};
}

TEST(FdCheck, PassesCorrectTerm) {
  SpringTerm t(SpringTerm::none);
  auto r = test::check_element(t, 0, states());
  EXPECT_TRUE(r.ok) << r.detail;
}

TEST(FdCheck, CatchesWrongForceSign) {
  SpringTerm t(SpringTerm::force_sign);
  auto r = test::check_element(t, 0, states());
  EXPECT_FALSE(r.ok);
  EXPECT_GT(r.force_error, 0.5);
}

TEST(FdCheck, CatchesWrongStiffness) {
  SpringTerm t(SpringTerm::stiffness_scale);
  auto r = test::check_element(t, 0, states());
  EXPECT_FALSE(r.ok);
  EXPECT_GT(r.dfdq_error, 0.01);
  EXPECT_LT(r.force_error, 1e-6);
}

TEST(FdCheck, CatchesMissingVelocityJacobian) {
  SpringTerm t(SpringTerm::no_damping_jacobian);
  auto r = test::check_element(t, 0, states());
  EXPECT_FALSE(r.ok);
}

TEST(FdCheck, RelativeStepWorksAtMillimetreAndKilometreScales) {
  SpringTerm t(SpringTerm::none);
  for (double scale : {1e-3, 1e3}) {
    std::vector<test::LocalState> scaled = states();
    for (auto& s : scaled)
      for (double& x : s.q) x *= scale;
    auto r = test::check_element(t, 0, scaled);
    EXPECT_TRUE(r.ok) << "scale " << scale << ": " << r.detail;
    EXPECT_LT(r.dfdq_error, 1e-7) << scale;
  }
}

// A term whose force is zero everywhere: comparing zero with zero checks nothing.
class NothingTerm : public StencilTerm<3> {
 public:
  NothingTerm() { stencils_.push_back({0, 1, 2}); }
  std::unique_ptr<Term> clone() const override { return std::make_unique<NothingTerm>(*this); }
  std::string name() const override { return "nothing"; }
  double energy(int, const double*) const override { return 0.0; }
  void evaluate(int, const double*, const double*, const ElementOutput&) const override {}
};

TEST(FdCheck, ZeroAgainstZeroFails) {
  NothingTerm t;
  auto r = test::check_element(t, 0, {{{0.1, 0.2, 0.3}, {0, 0, 0}}});
  EXPECT_FALSE(r.ok);
  EXPECT_NE(r.detail.find("zero at every state"), std::string::npos) << r.detail;
}

// One DoF with mass m(q) = m0(1 + αq²) whose inertial force has the wrong sign
// (+½m′q̇² instead of −½m′q̇²) but Jacobians consistent with that wrong force:
// only the mass check can see it.
class WrongInertiaTerm : public StencilTerm<1> {
 public:
  WrongInertiaTerm() { stencils_.push_back({0}); }
  std::unique_ptr<Term> clone() const override { return std::make_unique<WrongInertiaTerm>(*this); }
  std::string name() const override { return "wrong-inertia"; }
  bool conservative() const override { return false; }
  bool has_velocity_jacobian() const override { return true; }
  bool provides_mass() const override { return true; }
  double energy(int, const double*) const override { return 0.0; }
  void evaluate(int, const double* q, const double* v, const ElementOutput& out) const override {
    out.force[0] = a_ * q[0] * v[0] * v[0];
    if (out.dfdq) out.dfdq[0] = a_ * v[0] * v[0];
    if (out.dfdv) out.dfdv[0] = 2.0 * a_ * q[0] * v[0];
    if (out.mass) out.mass[0] = 1.0 + a_ * q[0] * q[0];
  }

 private:
  double a_ = 2.0;
};

TEST(FdCheck, MassBlockIsChecked) {
  const std::vector<test::LocalState> st = {{{0.4}, {0.7}}, {{-1.1}, {0.3}}};
  auto right = test::make_variable_mass_term(1.0, 2.0);
  auto r = test::check_element(*right, 0, st);
  EXPECT_TRUE(r.ok) << r.detail;
  EXPECT_LT(r.mass_error, 1e-7);
  WrongInertiaTerm wrong;
  r = test::check_element(wrong, 0, st);
  EXPECT_FALSE(r.ok);
  EXPECT_GT(r.mass_error, 0.5) << r.detail;
  EXPECT_LT(r.dfdq_error, 1e-7);
}

// V = q⁴/4 with a ∂f/∂q that is right only at q = 0.5: the given state alone
// cannot see the error, the seeded random states around it do.
class RightOnlyAtOneStateTerm : public StencilTerm<1> {
 public:
  RightOnlyAtOneStateTerm() { stencils_.push_back({0}); }
  std::unique_ptr<Term> clone() const override { return std::make_unique<RightOnlyAtOneStateTerm>(*this); }
  std::string name() const override { return "right-at-one-state"; }
  double energy(int, const double* q) const override { return 0.25 * std::pow(q[0], 4); }
  void evaluate(int, const double* q, const double*, const ElementOutput& out) const override {
    out.force[0] = -std::pow(q[0], 3);
    if (out.dfdq) out.dfdq[0] = -3.0 * q[0] * q[0] + 100.0 * (q[0] - 0.5);
  }
};

TEST(FdCheck, SeededRandomStatesCatchWhatTheGivenStateHides) {
  RightOnlyAtOneStateTerm t;
  const std::vector<test::LocalState> st = {{{0.5}, {0.0}}};
  test::FdOptions given_only;
  given_only.random_states = 0;
  EXPECT_TRUE(test::check_element(t, 0, st, given_only).ok);
  const auto a = test::check_element(t, 0, st), b = test::check_element(t, 0, st);
  EXPECT_FALSE(a.ok);
  EXPECT_GT(a.dfdq_error, 1e-3);
  EXPECT_EQ(a.dfdq_error, b.dfdq_error);  // same seed, same states
}

}  // namespace
}  // namespace wl
