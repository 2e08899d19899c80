#include "driver/modal_match.h"

#include <algorithm>
#include <stdexcept>

namespace wl {

Eigen::MatrixXd mac_matrix(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
  if (a.rows() != b.rows()) throw std::invalid_argument("mac_matrix: shapes sampled at different points");
  const Eigen::MatrixXd cross = a.transpose() * b;
  const Eigen::VectorXd na = a.colwise().squaredNorm().transpose(), nb = b.colwise().squaredNorm().transpose();
  Eigen::MatrixXd mac(a.cols(), b.cols());
  for (Eigen::Index i = 0; i < a.cols(); ++i)
    for (Eigen::Index j = 0; j < b.cols(); ++j) mac(i, j) = cross(i, j) * cross(i, j) / (na[i] * nb[j]);
  return mac;
}

std::vector<ModePair> match_modes(const Eigen::MatrixXd& mac) {
  std::vector<char> row_used(mac.rows(), 0), col_used(mac.cols(), 0);
  std::vector<ModePair> pairs;
  const Eigen::Index n = std::min(mac.rows(), mac.cols());
  for (Eigen::Index k = 0; k < n; ++k) {
    ModePair best{-1, -1, -1.0};
    for (Eigen::Index i = 0; i < mac.rows(); ++i)
      for (Eigen::Index j = 0; j < mac.cols(); ++j)
        if (!row_used[i] && !col_used[j] && mac(i, j) > best.mac)
          best = {static_cast<int>(i), static_cast<int>(j), mac(i, j)};
    row_used[best.a] = col_used[best.b] = 1;
    pairs.push_back(best);
  }
  std::sort(pairs.begin(), pairs.end(), [](const ModePair& x, const ModePair& y) { return x.a < y.a; });
  return pairs;
}

}  // namespace wl
