#include "models/core/step_stiffness.h"

#include <Eigen/Eigenvalues>

namespace wl {

// K_e ← −V max(Λ, 0) Vᵀ with −K_e = V Λ Vᵀ (docs/models.md §3.11.2).
void project_step_stiffness(int n, double* k) {
  Eigen::Map<Eigen::MatrixXd> K(k, n, n);
  if (K.isZero(0.0)) return;
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(-K);
  const Eigen::VectorXd lambda = eig.eigenvalues();
  if (lambda.minCoeff() >= 0.0) return;
  const Eigen::MatrixXd& V = eig.eigenvectors();
  K.noalias() = -(V * lambda.cwiseMax(0.0).asDiagonal() * V.transpose());
}

}  // namespace wl
