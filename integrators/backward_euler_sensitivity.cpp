// Forward parameter sensitivities of the backward-Euler steps (docs/models.md §9.2).
// S_q = ∂q/∂p and S_v = ∂v/∂p, one column per tracked parameter, are carried by
// differentiating the discrete step that was taken; each column costs one solve
// with the step's own matrix.
#include "integrators/backward_euler.h"

namespace wl {

// be-linear: A₀Δv = h(f₀ + hK₀v₀). Differentiated with K₀, D₀ held (their
// derivatives are second derivatives of f, O(h²) per step, docs/models.md §9.2):
//   A₀ ∂Δv/∂p = h(∂f/∂p + K₀(S_q + hS_v) + D₀S_v) − (∂M/∂p + ∂M/∂q·S_q)Δv.
bool BackwardEuler::propagate_linear_sensitivities(double h, const Vec& dv) {
  Vec dfdp, rhs, x, mw(dv.size());
  for (Eigen::Index k = 0; k < dq_dp_.cols(); ++k) {
    const std::string& key = sensitivity_keys_[k];
    model_->force_parameter_derivative(key, t_, q_, v_, dfdp);
    const auto sq = dq_dp_.col(k), sv = dv_dp_.col(k);
    rhs = h * (dfdp + ev_.dfdq * (sq + h * sv) + ev_.dfdv * sv);
    mw.setZero();
    model_->mass_parameter_product(key, q_, dv, mw);
    model_->mass_directional_product(q_, sq, dv, mw);
    rhs -= mw;
    if (!solver_->solve(rhs, x)) return false;
    ++stats_.linear_solves;
    dv_dp_.col(k) = sv + x;
    for (int i : fixed_) dv_dp_(i, k) = 0.0;
    dq_dp_.col(k) = sq + h * dv_dp_.col(k);
  }
  return true;
}

// be-newton: G(v₁) = M(q₀)(v₁ − v₀) − h f(q₀ + hv₁, v₁; p) = 0 at convergence, so
//   A₁ S_v₁ = M₀S_v₀ + hK₁S_q₀ − (∂M/∂p + ∂M/∂q·S_q₀)(v₁ − v₀) + h ∂f/∂p(q₁, v₁),
//   A₁ = M₀ − hD₁ − h²K₁ at the converged state (ev_ holds its Jacobians).
bool BackwardEuler::propagate_newton_sensitivities(double h, const Vec& q0, const Vec& v0, const SparseMatrix& m0) {
  form_step_matrix(h);
  const Vec dv = v_ - v0;
  Vec dfdp, rhs, x, mw(dv.size());
  for (Eigen::Index k = 0; k < dq_dp_.cols(); ++k) {
    const std::string& key = sensitivity_keys_[k];
    model_->force_parameter_derivative(key, t_ + h, q_, v_, dfdp);
    const auto sq = dq_dp_.col(k), sv = dv_dp_.col(k);
    rhs = m0 * sv + h * (ev_.dfdq * sq) + h * dfdp;
    mw.setZero();
    model_->mass_parameter_product(key, q0, dv, mw);
    model_->mass_directional_product(q0, sq, dv, mw);
    rhs -= mw;
    for (int i : fixed_) rhs[i] = 0.0;
    if (!solve_step_matrix(rhs, x)) return false;
    dv_dp_.col(k) = x;
    for (int i : fixed_) dv_dp_(i, k) = 0.0;
    dq_dp_.col(k) = sq + h * dv_dp_.col(k);
  }
  return true;
}

bool BackwardEuler::solve_step_matrix(const Vec& b, Vec& x) {
  const double target = 1e-12 * std::max(b.norm(), 1e-300);
  auto residual = [&](Vec& r) {
    r = b - a_ * x;
    for (int i : fixed_) r[i] = 0.0;
    return r.norm();
  };
  Vec r, dx;
  for (int attempt = 0; attempt < 2; ++attempt) {
    solver_->solve(b, x);
    ++stats_.linear_solves;
    for (int it = 0; it < 30; ++it) {
      if (residual(r) <= target) return true;
      solver_->solve(r, dx);
      ++stats_.linear_solves;
      x += dx;
    }
    if (residual(r) <= target) return true;
    ++stats_.linear_setups;
    if (!solver_->factorize(a_)) return false;  // the refinement stalled: factor a_ itself
  }
  return residual(r) <= 1e3 * target;
}

}  // namespace wl
