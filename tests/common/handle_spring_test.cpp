// HandleSpringTerm: FD check, and the force pulls the point toward its anchor.
#include <gtest/gtest.h>

#include "models/common/handle_spring.h"
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

TEST(HandleSpringTerm, RejectsBadParameters) {
  HandleSpringTerm t;
  EXPECT_THROW(t.add({0, 1, 2}, Vec3::Zero(), -1.0), std::invalid_argument);
  EXPECT_THROW(t.add({0, 1, 2}, Vec3(0, std::nan(""), 0), 1.0), std::invalid_argument);
}

}  // namespace
}  // namespace wl
