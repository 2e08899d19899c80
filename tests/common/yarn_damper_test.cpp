// YarnDamperTerm: FD check, the force opposes the stretch rate only, and it
// removes energy at the rate c ṡ².
#include <gtest/gtest.h>

#include <cmath>

#include "models/common/yarn_damper.h"
#include "tests/support/fd_check.h"

namespace wl {
namespace {

TEST(YarnDamperTerm, ForcesAndJacobiansMatchFiniteDifferences) {
  YarnDamperTerm t;
  t.add({0, 1, 2, 3, 4, 5}, 0.05);
  // Stretching, shortening, and turning (ṡ = 0) segments, with velocities in every direction.
  std::vector<test::LocalState> states = {{{0, 0, 0, 1e-3, 0, 0}, {0.1, 0.2, -0.3, 0.5, -0.1, 0.4}},
                                          {{0.1, -0.2, 0.3, 0.1005, -0.1993, 0.3008}, {0, 0, 0, -1, 2, 0.5}},
                                          {{0, 0, 0, 0, 1e-3, 0}, {0, 0, 0, 0.3, 0, 0}}};
  auto r = test::check_element(t, 0, states);
  EXPECT_TRUE(r.ok) << r.detail;
}

TEST(YarnDamperTerm, OpposesTheStretchRateAndDissipatesCSDotSquared) {
  YarnDamperTerm t;
  const double c = 0.2;
  t.add({0, 1, 2, 3, 4, 5}, c);
  const Eigen::Matrix<double, 6, 1> q = (Eigen::Matrix<double, 6, 1>() << 0, 0, 0, 3e-3, 4e-3, 0).finished();
  const Eigen::Matrix<double, 6, 1> v = (Eigen::Matrix<double, 6, 1>() << 0.1, 0, 0, 0.4, -0.2, 0.7).finished();
  Eigen::Matrix<double, 6, 1> f;
  t.evaluate(0, q.data(), v.data(), ElementOutput{f.data(), nullptr, nullptr, nullptr});
  const Vec3 d = Vec3(3, 4, 0) / 5;
  const double rate = d.dot(v.tail<3>() - v.head<3>());
  EXPECT_LT((f.tail<3>() + c * rate * d).norm(), 1e-15);
  EXPECT_LT((f.head<3>() + f.tail<3>()).norm(), 1e-15);  // no net force
  EXPECT_NEAR(f.dot(v), -c * rate * rate, 1e-15);        // power
  // A rigid rotation of the segment (ṡ = 0) is not damped.
  const Eigen::Matrix<double, 6, 1> spin = (Eigen::Matrix<double, 6, 1>() << 0, 0, 0, -4, 3, 1).finished();
  t.evaluate(0, q.data(), spin.data(), ElementOutput{f.data(), nullptr, nullptr, nullptr});
  EXPECT_LT(f.norm(), 1e-15);
}

TEST(YarnDamperTerm, CoefficientFromTheViscosityAndRejectsBadValues) {
  EXPECT_NEAR(yarn_damper_coefficient(10.0, 5e-4, 1e-3), 10.0 * M_PI * 2.5e-7 / 1e-3, 1e-15);
  YarnDamperTerm t;
  EXPECT_THROW(t.add({0, 1, 2, 3, 4, 5}, -1.0), std::invalid_argument);
  EXPECT_THROW(t.add({0, 1, 2, 3, 4, 5}, std::nan("")), std::invalid_argument);
}

}  // namespace
}  // namespace wl
