// The statistics of an optimum whose residuals or Jacobian are not finite (a
// target with a NaN coordinate): empty statistics that say why, not a crash.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include <ceres/ceres.h>

#include "calibration/optimum_statistics.h"

namespace wl {
namespace {

// r_i = θ0 − d_i, r_{i+3} = θ1 − d_i: each data point d_i is seen by both parameters.
class LinearResiduals : public ceres::CostFunction {
 public:
  LinearResiduals(double nan_at, bool succeed) : nan_at_(nan_at), succeed_(succeed) {
    set_num_residuals(6);
    mutable_parameter_block_sizes()->push_back(2);
  }
  bool Evaluate(double const* const* p, double* r, double** jacobians) const override {
    const double data[3] = {1.0, 2.0, nan_at_};
    for (int i = 0; i < 3; ++i) {
      r[i] = p[0][0] - data[i];
      r[i + 3] = p[0][1] - data[i];
    }
    if (jacobians && jacobians[0]) {
      for (int k = 0; k < 12; ++k) jacobians[0][k] = 0.0;
      for (int i = 0; i < 3; ++i) {
        jacobians[0][2 * i] = std::isfinite(nan_at_) ? 1.0 : nan_at_;
        jacobians[0][2 * (i + 3) + 1] = 1.0;
      }
    }
    return succeed_;
  }

 private:
  double nan_at_;
  bool succeed_;
};

OptimumStatistics statistics_of(double third, bool succeed) {
  double theta[2] = {0.5, 0.5};
  ceres::Problem problem;
  problem.AddResidualBlock(new LinearResiduals(third, succeed), nullptr, theta);
  return optimum_statistics(problem, theta, 2);
}

TEST(OptimumStatistics, AFiniteProblemHasItsCovariance) {
  const OptimumStatistics s = statistics_of(3.0, true);
  EXPECT_TRUE(s.unidentifiable.empty());
  ASSERT_EQ(s.covariance.rows(), 2);
  // JᵀJ = 3·I, σ² = 2·cost/(m − n) = Σr²/4 with r = (−0.5, −1.5, −2.5) twice: 17.5/4.
  EXPECT_NEAR(s.covariance(0, 0), (17.5 / 4.0) / 3.0, 1e-12);
  EXPECT_NEAR(s.covariance(0, 1), 0.0, 1e-12);
}

TEST(OptimumStatistics, ANonFiniteJacobianGivesEmptyStatisticsThatSayWhy) {
  const OptimumStatistics s = statistics_of(std::numeric_limits<double>::quiet_NaN(), true);
  EXPECT_EQ(s.covariance.size(), 0);
  EXPECT_EQ(s.unidentifiable, (std::vector<int>{0, 1}));
  EXPECT_EQ(s.jacobian.rows(), 0);
  EXPECT_EQ(s.jacobian.cols(), 2);
  EXPECT_NE(s.covariance_message.find("not finite"), std::string::npos) << s.covariance_message;
}

TEST(OptimumStatistics, AFailedEvaluationGivesEmptyStatisticsThatSayWhy) {
  const OptimumStatistics s = statistics_of(3.0, false);
  EXPECT_EQ(s.covariance.size(), 0);
  EXPECT_EQ(s.unidentifiable, (std::vector<int>{0, 1}));
  EXPECT_NE(s.covariance_message.find("not finite"), std::string::npos) << s.covariance_message;
}

// A zero column and a column that repeats another are each held; the SVD's
// singular values come back largest first.
TEST(OptimumStatistics, ZeroAndCollinearColumnsAreUnidentifiable) {
  Eigen::MatrixXd j(4, 3);
  j << 1, 0, 0.5, 0, 1, 0, 1, 1, 0.5, 2, 0, 1;  // column 2 = ½ column 0: the null vector (½, 0, −1)
  std::vector<double> sv;
  EXPECT_EQ(unidentifiable_columns(j, &sv), (std::vector<int>{2}));
  ASSERT_EQ(sv.size(), 3u);
  EXPECT_GT(sv[0], sv[1]);
  EXPECT_LT(sv[2], 1e-12 * sv[0]);
  j.col(2).setZero();
  j.col(1).setZero();
  EXPECT_EQ(unidentifiable_columns(j), (std::vector<int>{1, 2}));
  EXPECT_EQ(unidentifiable_columns(Eigen::MatrixXd::Zero(4, 2)), (std::vector<int>{0, 1}));
  j.col(1) << 0, 1, 1, 0;
  j.col(2) << 0, 0, 1e-3, 1;  // small but independent: told
  EXPECT_TRUE(unidentifiable_columns(j).empty());
  j(0, 0) = std::numeric_limits<double>::quiet_NaN();  // not decomposed
  EXPECT_TRUE(unidentifiable_columns(j).empty());
}

}  // namespace
}  // namespace wl
