#include "calibration/optimum_statistics.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <ceres/ceres.h>
#include <Eigen/SVD>

namespace wl {

std::vector<int> unidentifiable_columns(const Eigen::MatrixXd& jacobian, std::vector<double>* singular_values) {
  const int n = static_cast<int>(jacobian.cols());
  if (singular_values) {
    const Eigen::VectorXd sv =
        jacobian.rows() ? Eigen::VectorXd(jacobian.jacobiSvd().singularValues()) : Eigen::VectorXd::Zero(0);
    singular_values->assign(sv.data(), sv.data() + sv.size());
  }
  // One column at a time: the dominant entry of the weakest right singular vector
  // of the columns still held free, until the weakest is above the threshold. A
  // tie (two zero columns, whose null vectors may mix them) then costs one more pass.
  std::vector<int> free(n), held;
  for (int k = 0; k < n; ++k) free[k] = k;
  if (jacobian.rows() == 0) return free;   // no residual tells any
  if (!jacobian.allFinite()) return held;  // nothing to decompose: JacobiSVD is undefined on it
  while (!free.empty()) {
    Eigen::MatrixXd part(jacobian.rows(), static_cast<Eigen::Index>(free.size()));
    for (size_t k = 0; k < free.size(); ++k) part.col(static_cast<Eigen::Index>(k)) = jacobian.col(free[k]);
    const Eigen::JacobiSVD<Eigen::MatrixXd> svd(part, Eigen::ComputeFullV);
    const Eigen::VectorXd& sv = svd.singularValues();
    const Eigen::Index count = part.cols(), weakest = count - 1;  // missing values (fewer rows) are zero
    const double largest = sv.size() ? sv[0] : 0.0, least = weakest < sv.size() ? sv[weakest] : 0.0;
    if (largest > 0.0 && least > 1e-7 * largest) break;
    Eigen::Index dominant = 0;
    svd.matrixV().col(weakest).cwiseAbs().maxCoeff(&dominant);
    held.push_back(free[dominant]);
    free.erase(free.begin() + dominant);
  }
  std::sort(held.begin(), held.end());
  return held;
}

OptimumStatistics optimum_statistics(ceres::Problem& problem, double* theta, int n) {
  OptimumStatistics s;
  std::vector<double> residuals;
  ceres::CRSMatrix crs;
  const bool evaluated = problem.Evaluate(ceres::Problem::EvaluateOptions(), &s.cost, &residuals, nullptr, &crs);
  const auto finite = [](double x) { return std::isfinite(x); };
  if (!evaluated || !std::isfinite(s.cost) || !std::all_of(residuals.begin(), residuals.end(), finite) ||
      !std::all_of(crs.values.begin(), crs.values.end(), finite) || crs.num_rows == 0) {
    // Nothing to decompose: no parameter can be told, no covariance formed.
    s.jacobian = Eigen::MatrixXd::Zero(0, n);
    for (int k = 0; k < n; ++k) s.unidentifiable.push_back(k);
    s.covariance_message =
        crs.num_rows == 0 && evaluated
            ? "no residuals at the optimum"
            : "the residuals or their Jacobian cannot be evaluated or are not finite at the optimum: no statistics";
    return s;
  }
  s.jacobian = Eigen::MatrixXd::Zero(crs.num_rows, crs.num_cols);
  for (int r = 0; r < crs.num_rows; ++r)
    for (int i = crs.rows[r]; i < crs.rows[r + 1]; ++i) s.jacobian(r, crs.cols[i]) = crs.values[i];
  s.unidentifiable = unidentifiable_columns(s.jacobian, &s.singular_values);

  const int m = crs.num_rows;
  if (m <= n) {
    s.covariance_message = "fewer residuals than parameters";
    return s;
  }
  if (static_cast<int>(s.unidentifiable.size()) == n) {
    s.covariance_message = "no parameter is identifiable: the residuals do not depend on them";
    return s;
  }
  // Hold the unidentifiable parameters: Ceres then computes the covariance in
  // the remaining directions (zero rows and columns for the held ones).
  if (!s.unidentifiable.empty()) problem.SetManifold(theta, new ceres::SubsetManifold(n, s.unidentifiable));
  ceres::Covariance::Options copt;
  copt.algorithm_type = ceres::DENSE_SVD;
  ceres::Covariance cov(copt);
  const std::vector<std::pair<const double*, const double*>> blocks{{theta, theta}};
  const bool ok = cov.Compute(blocks, &problem);
  if (ok) {
    s.covariance.resize(n, n);
    cov.GetCovarianceBlock(theta, theta, s.covariance.data());  // row-major; the matrix is symmetric
    s.covariance *= 2.0 * s.cost / (m - n + static_cast<int>(s.unidentifiable.size()));
  }
  if (!s.unidentifiable.empty()) problem.SetManifold(theta, nullptr);
  if (!ok)
    s.covariance_message = "the Jacobian is rank deficient: some parameter is not identifiable (singular values)";
  else if (!s.unidentifiable.empty())
    s.covariance_message = "some parameters are not identifiable (held for the covariance)";
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
