// The finite-difference checker must pass a correct term and fail terms that
// are wrong on purpose (wrong force, wrong ∂f/∂q, missing ∂f/∂v).
#include <gtest/gtest.h>

#include "tests/support/fd_check.h"

namespace wl {
namespace {

// A zero-rest-length spring between two points with a dashpot: V = ½k|x1−x0|²,
// f_damp = −c(v1−v0) on x1. `bug` selects a deliberate error.
class SpringTerm : public StencilTerm<6> {
 public:
  enum Bug { none, force_sign, stiffness_scale, no_damping_jacobian };
  explicit SpringTerm(Bug bug) : bug_(bug) { stencils_.push_back({0, 1, 2, 3, 4, 5}); }
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

}  // namespace
}  // namespace wl
