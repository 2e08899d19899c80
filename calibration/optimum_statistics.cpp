#include "calibration/optimum_statistics.h"

#include <cmath>
#include <limits>

#include <Eigen/SVD>
#include <ceres/ceres.h>

namespace wl {

OptimumStatistics optimum_statistics(ceres::Problem& problem, double* theta, int n) {
  OptimumStatistics s;
  std::vector<double> residuals;
  ceres::CRSMatrix crs;
  problem.Evaluate(ceres::Problem::EvaluateOptions(), &s.cost, &residuals, nullptr, &crs);
  s.jacobian = Eigen::MatrixXd::Zero(crs.num_rows, crs.num_cols);
  for (int r = 0; r < crs.num_rows; ++r)
    for (int i = crs.rows[r]; i < crs.rows[r + 1]; ++i) s.jacobian(r, crs.cols[i]) = crs.values[i];
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(s.jacobian);
  for (int i = 0; i < svd.singularValues().size(); ++i) s.singular_values.push_back(svd.singularValues()[i]);

  const int m = crs.num_rows;
  if (m <= n) {
    s.covariance_message = "fewer residuals than parameters";
    return s;
  }
  ceres::Covariance::Options copt;
  copt.algorithm_type = ceres::DENSE_SVD;
  ceres::Covariance cov(copt);
  const std::vector<std::pair<const double*, const double*>> blocks{{theta, theta}};
  if (!cov.Compute(blocks, &problem)) {
    s.covariance_message = "the Jacobian is rank deficient: some parameter is not identifiable (singular values)";
    return s;
  }
  s.covariance.resize(n, n);
  cov.GetCovarianceBlock(theta, theta, s.covariance.data());  // row-major; the matrix is symmetric
  s.covariance *= 2.0 * s.cost / (m - n);
  return s;
}

std::vector<std::vector<double>> OptimumStatistics::correlation() const {
  const int n = static_cast<int>(covariance.rows());
  std::vector<std::vector<double>> c(n, std::vector<double>(n, 0.0));
  for (int a = 0; a < n; ++a)
    for (int b = 0; b < n; ++b) {
      const double d = std::sqrt(covariance(a, a) * covariance(b, b));
      c[a][b] = d > 0 ? covariance(a, b) / d : (a == b ? 1.0 : 0.0);
    }
  return c;
}

}  // namespace wl
