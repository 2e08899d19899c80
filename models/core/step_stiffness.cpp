#include "models/core/step_stiffness.h"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>

namespace wl {
namespace {

// K ← −V max(Λ, 0) Vᵀ with −K = V Λ Vᵀ, unless LDLᵀ (pivoted; its D has the
// inertia of −K) shows −K ⪰ 0 already: most blocks are, and the test is cheap.
template <typename Matrix>
void project(Eigen::Map<Eigen::MatrixXd> K) {
  const Matrix H = -K;
  const Eigen::LDLT<Matrix> ldlt(H);
  if (ldlt.info() == Eigen::Success && ldlt.vectorD().minCoeff() >= 0.0) return;
  const Eigen::SelfAdjointEigenSolver<Matrix> eig(H);
  const auto lambda = eig.eigenvalues();
  if (lambda.minCoeff() >= 0.0) return;
  K.noalias() = -(eig.eigenvectors() * lambda.cwiseMax(0.0).asDiagonal() * eig.eigenvectors().transpose());
}

}  // namespace

// docs/models.md §3.11.2
void project_step_stiffness(int n, double* k) {
  Eigen::Map<Eigen::MatrixXd> K(k, n, n);
  if (K.isZero(0.0)) return;
  constexpr int kSmall = 12;  // the barrier's 3 and the stretch's 8 DoFs: no allocation
  if (n <= kSmall) project<Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::ColMajor, kSmall, kSmall>>(K);
  else project<Eigen::MatrixXd>(K);
}

}  // namespace wl
