#include "integrators/gmres.h"

#include <cmath>

namespace wl {

Gmres::Gmres(int n, int restart)
    : n_(n),
      m_(restart),
      v_(n, restart + 1),
      z_(n, restart),
      h_(restart + 1, restart),
      cs_(restart),
      sn_(restart),
      g_(restart + 1),
      y_(restart),
      w_(n),
      r_(n) {}

Gmres::Result Gmres::solve(const Apply& a, const Apply& precond, const Vec& b, Vec& x, double tol, int max_iters) {
  Result res;
  const double bnorm = b.norm();
  if (bnorm == 0.0) {
    x.setZero(n_);
    res.converged = true;
    return res;
  }
  if (x.size() != n_) x.setZero(n_);
  while (true) {
    // r = b − A x (the true residual, also at every restart).
    a(x, r_);
    r_ = b - r_;
    const double beta = r_.norm();
    res.relative_residual = beta / bnorm;
    if (res.relative_residual <= tol) {
      res.converged = true;
      return res;
    }
    if (res.iterations >= max_iters || !std::isfinite(beta)) return res;
    v_.col(0) = r_ / beta;
    g_.setZero();
    g_[0] = beta;
    int j = 0;
    for (; j < m_ && res.iterations < max_iters; ++j) {
      // Arnoldi step with modified Gram–Schmidt: w = A P⁻¹ v_j.
      precond(v_.col(j), z_.col(j));
      a(z_.col(j), w_);
      ++res.iterations;
      for (int i = 0; i <= j; ++i) {
        h_(i, j) = w_.dot(v_.col(i));
        w_.noalias() -= h_(i, j) * v_.col(i);
      }
      h_(j + 1, j) = w_.norm();
      if (h_(j + 1, j) > 0.0) v_.col(j + 1) = w_ / h_(j + 1, j);
      // Apply the earlier Givens rotations, then one that zeroes h(j+1, j).
      for (int i = 0; i < j; ++i) {
        const double t = cs_[i] * h_(i, j) + sn_[i] * h_(i + 1, j);
        h_(i + 1, j) = -sn_[i] * h_(i, j) + cs_[i] * h_(i + 1, j);
        h_(i, j) = t;
      }
      const double d = std::hypot(h_(j, j), h_(j + 1, j));
      cs_[j] = d > 0.0 ? h_(j, j) / d : 1.0;
      sn_[j] = d > 0.0 ? h_(j + 1, j) / d : 0.0;
      h_(j, j) = d;
      h_(j + 1, j) = 0.0;
      g_[j + 1] = -sn_[j] * g_[j];
      g_[j] = cs_[j] * g_[j];
      // |g_{j+1}| is the residual norm of the least-squares problem.
      if (std::abs(g_[j + 1]) <= tol * bnorm || h_(j, j) == 0.0) {
        ++j;
        break;
      }
    }
    // x += Z y with H y = g (upper triangular, j×j).
    y_.head(j) = h_.topLeftCorner(j, j).triangularView<Eigen::Upper>().solve(g_.head(j));
    x.noalias() += z_.leftCols(j) * y_.head(j);
  }
}

}  // namespace wl
