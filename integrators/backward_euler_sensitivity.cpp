// Forward parameter sensitivities of the backward-Euler steps (docs/models.md §9.2).
// S_q = ∂q/∂p and S_v = ∂v/∂p, one column per tracked parameter, are carried by
// differentiating the discrete step that was taken; each column costs one solve
// with the step's own matrix (be-newton: one direct factorization per step).
#include <stdexcept>

#include "integrators/backward_euler.h"

namespace wl {

// be-linear: A₀Δv = h(f₀ + hK₀v₀). Differentiated with K₀, D₀ held (their
// derivatives are second derivatives of f, O(h²) per step, docs/models.md §9.2):
//   A₀ ∂Δv/∂p = h(∂f/∂p + K₀(S_q + hS_v) + D₀S_v) − (∂M/∂p + ∂M/∂q·S_q)Δv.
void BackwardEuler::propagate_linear_sensitivities(double h, const Vec& dv) {
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
    solver_->solve(rhs, x);
    ++stats_.linear_solves;
    dv_dp_.col(k) = sv + x;
    for (int i : fixed_) dv_dp_(i, k) = 0.0;
    dq_dp_.col(k) = sq + h * dv_dp_.col(k);
  }
}

// be-newton: G(v₁) = M(q₀)(v₁ − v₀) − h f(q₀ + hv₁, v₁; p) = 0 at convergence, so
//   A₁ S_v₁ = M₀S_v₀ + hK₁S_q₀ − (∂M/∂p + ∂M/∂q·S_q₀)(v₁ − v₀) + h ∂f/∂p(q₁, v₁),
//   A₁ = M₀ − hD₁ − h²K₁ at the converged state (ev_ holds its Jacobians).
// A₁ is factorized once, directly, and every column is solved with it.
void BackwardEuler::propagate_newton_sensitivities(double h, const Vec& q0, const Vec& v0, const SparseMatrix& m0) {
  form_step_matrix(h);
  if (!factorize_sensitivity_matrix())
    throw std::runtime_error("sensitivity solve: step matrix: " + sensitivity_solver_->failure());
  const Vec dv = v_ - v0;
  sens_mw_.resize(dv.size());
  for (Eigen::Index k = 0; k < dq_dp_.cols(); ++k) {
    const std::string& key = sensitivity_keys_[k];
    model_->force_parameter_derivative(key, t_ + h, q_, v_, sens_dfdp_);
    const auto sq = dq_dp_.col(k), sv = dv_dp_.col(k);
    sens_rhs_.noalias() = m0 * sv;
    sens_rhs_.noalias() += h * (ev_.dfdq * sq);
    sens_rhs_ += h * sens_dfdp_;
    sens_mw_.setZero();
    model_->mass_parameter_product(key, q0, dv, sens_mw_);
    model_->mass_directional_product(q0, sq, dv, sens_mw_);
    sens_rhs_ -= sens_mw_;
    for (int i : fixed_) sens_rhs_[i] = 0.0;
    if (!sensitivity_solver_->solve(sens_rhs_, sens_x_))
      throw std::runtime_error("sensitivity solve: " + sensitivity_solver_->failure());
    ++stats_.linear_solves;
    dv_dp_.col(k) = sens_x_;
    for (int i : fixed_) dv_dp_(i, k) = 0.0;
    dq_dp_.col(k) = sq + h * dv_dp_.col(k);
  }
}

bool BackwardEuler::factorize_sensitivity_matrix() {
  if (!sensitivity_solver_) {
    SparseSolver::Options o = step_solver_options();
    o.method = LinearSolverMethod::umfpack;  // any matrix; the step's own may be gmres
    sensitivity_solver_ = std::make_unique<SparseSolver>(a_, fixed_, o);
  }
  ++stats_.linear_setups;
  return sensitivity_solver_->factorize(a_);
}

}  // namespace wl
