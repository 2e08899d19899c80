// Forward parameter sensitivities of the SDIRK2 steps (docs/models.md §9.2),
// by differentiating each converged stage equation
//   M(Q)(V − w) − γh f(Q, V; p) = 0,   Q = q_b + γh V,
// with respect to p:
//   (M − γhD − γ²h²K) S_V = M S_w + γh K S_qb + γh ∂f/∂p − (∂M/∂p + ∂M/∂q·S_Q)(V − w),
// K, D, M at the converged stage state (one Jacobian and factorization per
// stage); where M depends on q the term ∂M/∂q·S_Q, S_Q = S_qb + γh S_V, is
// solved for by fixed-point passes. Between the stages:
//   S_w₂ = S_v₀ + ((1−γ)/γ)(S_V₁ − S_v₀),  S_qb₂ = S_q₀ + (1−γ)h S_V₁;
// and after them S_q₁ = S_qb₂ + γh S_V₂, S_v₁ = S_V₂.
#include "integrators/sdirk2.h"

namespace wl {

StepResult Sdirk2::propagate_sensitivities(double h) {
  const double gh = kGamma * h;
  // One stage: S_V for every tracked key, given S_w and S_qb (columns per key).
  auto stage = [&](double t, const Vec& Q, const Vec& V, const Vec& w, const Eigen::MatrixXd& sw,
                   const Eigen::MatrixXd& sqb, Eigen::MatrixXd& sV) -> StepResult {
    if (StepResult r = refresh_matrix(t, h, Q, V); r.outcome != Outcome::ok) return r;
    const Vec dv = V - w;
    Vec dfdp, rhs, x, mw(dv.size());
    sV.resize(dq_dp_.rows(), dq_dp_.cols());
    // ∂M/∂q·S_Q with S_Q = S_qb + γh S_V is linear in the unknown: a few
    // fixed-point passes, S_V from the last (one pass for a constant mass).
    const int passes = model_->mass_depends_on_q() ? 4 : 1;
    for (Eigen::Index k = 0; k < dq_dp_.cols(); ++k) {
      const std::string& key = sensitivity_keys_[k];
      model_->force_parameter_derivative(key, t, Q, V, dfdp);
      const Vec base = jac_.mass * sw.col(k) + gh * (jac_.dfdq * sqb.col(k)) + gh * dfdp;
      x.setZero(dv.size());
      for (int pass = 0; pass < passes; ++pass) {
        mw.setZero();
        model_->mass_parameter_product(key, Q, dv, mw);
        model_->mass_directional_product(Q, sqb.col(k) + gh * x, dv, mw);
        rhs = base - mw;
        for (int i : fixed_) rhs[i] = 0.0;
        if (!solver_->solve(rhs, x)) return {Outcome::diverged, "sensitivity solve: " + solver_->failure()};
        ++stats_.linear_solves;
        for (int i : fixed_) x[i] = 0.0;
      }
      sV.col(k) = x;
    }
    return {};
  };
  Eigen::MatrixXd sV1, sV2;
  if (StepResult r = stage(t_ + gh, Q1_, V1_, v_, dv_dp_, dq_dp_, sV1); r.outcome != Outcome::ok) return r;
  const Eigen::MatrixXd sw2 = dv_dp_ + ((1.0 - kGamma) / kGamma) * (sV1 - dv_dp_);
  const Eigen::MatrixXd sqb2 = dq_dp_ + (1.0 - kGamma) * h * sV1;
  if (StepResult r = stage(t_ + h, q_new_, V2_, w2_, sw2, sqb2, sV2); r.outcome != Outcome::ok) return r;
  dq_dp_ = sqb2 + gh * sV2;
  dv_dp_ = sV2;
  return {};
}

}  // namespace wl
