// What a least-squares optimum says about its parameters (docs/calibration.md §4.3):
// the Jacobian in θ, its singular values and ceres::Covariance (DENSE_SVD) of θ
// scaled by the residual variance σ² = 2·cost/(m − n). A parameter the data
// cannot tell (it dominates a singular vector whose singular value is below
// 1e-7 of the largest) is reported as unidentifiable and held while the
// covariance of the others is computed. Shared by the static calibration and
// the trajectory fit.
#pragma once
#include <string>
#include <vector>

#include <ceres/problem.h>
#include <Eigen/Core>

namespace wl {

struct OptimumStatistics {
  double cost = 0.0;
  Eigen::MatrixXd jacobian;  // m × n at θ
  std::vector<double> singular_values;
  std::vector<int> unidentifiable;  // indices into θ
  Eigen::MatrixXd covariance;       // n × n of θ (zero rows for unidentifiable ones); empty when unavailable
  std::string covariance_message;   // why it is unavailable
  // Correlation matrix from `covariance` (empty when it is empty).
  std::vector<std::vector<double>> correlation() const;
};

// The columns of a Jacobian J (m × n) the data cannot tell (a zero column, or one
// collinear with others), in increasing order: while the smallest singular value of
// the columns not yet held is at most 1e-7 of their largest, the dominant entry of
// its right singular vector is held. An all-zero or empty J tells none; one with a
// non-finite entry is not decomposed (nothing held).
// `singular_values`, when given, receives J's, largest first.
std::vector<int> unidentifiable_columns(const Eigen::MatrixXd& jacobian,
                                        std::vector<double>* singular_values = nullptr);

// `theta` is the problem's one parameter block, of size n. When the residuals
// or the Jacobian cannot be evaluated or are not finite (a non-finite target
// or simulation), the statistics are empty: a 0 × n Jacobian, every parameter
// unidentifiable, no covariance, and covariance_message says why.
OptimumStatistics optimum_statistics(ceres::Problem& problem, double* theta, int n);

}  // namespace wl
