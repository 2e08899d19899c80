// Matching the modes of two models by shape (docs/models.md §10.3): the modal
// assurance criterion of two shapes sampled at the same points,
//   MAC(φ, ψ) = |φᵀψ|² / ((φᵀφ)(ψᵀψ))  ∈ [0, 1],
// 1 for parallel shapes, 0 for orthogonal ones, blind to scale and sign.
#pragma once
#include <vector>

#include <Eigen/Core>

namespace wl {

// MAC of every column of a (rows) against every column of b (columns); a and b
// have the same number of rows (the sampled components).
Eigen::MatrixXd mac_matrix(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b);

struct ModePair {
  int a = 0, b = 0;  // column of a, column of b
  double mac = 0.0;
};

// One-to-one pairs by largest MAC: repeatedly the largest entry among the rows
// and columns not yet paired; min(rows, columns) pairs, in the order of a.
std::vector<ModePair> match_modes(const Eigen::MatrixXd& mac);

}  // namespace wl
