// The force of a knit term's element and its exact Jacobian ∂F/∂q by
// forward-mode automatic differentiation (Eigen's AutoDiffScalar): `force`
// maps the local state (N entries, in the AD scalar) to the force (N entries).
#pragma once
#include <Eigen/Core>
#include <unsupported/Eigen/AutoDiff>

namespace wl {

template <int N>
using AutoDiff = Eigen::AutoDiffScalar<Eigen::Matrix<double, N, 1>>;

template <int N, class Force>
void force_and_jacobian_by_autodiff(const double* q, const Force& force, double* f, double* dfdq) {
  Eigen::Matrix<AutoDiff<N>, N, 1> x;
  for (int a = 0; a < N; ++a) x[a] = AutoDiff<N>(q[a], N, a);
  const Eigen::Matrix<AutoDiff<N>, N, 1> F = force(x);
  Eigen::Map<Eigen::Matrix<double, N, N>> K(dfdq);
  for (int a = 0; a < N; ++a) {
    f[a] = F[a].value();
    K.row(a) = F[a].derivatives().transpose();  // ∂F_a/∂q
  }
}

}  // namespace wl
