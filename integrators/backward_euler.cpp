#include "integrators/backward_euler.h"

#include <cmath>

namespace wl {
namespace {

void zero_fixed(Vec& x, const std::vector<int>& fixed) {
  for (int i : fixed) x[i] = 0.0;
}

}  // namespace

void BackwardEuler::initialize(Model& model, double t0, const Vec& q0, const Vec& v0, const IntegratorOptions& opt) {
  bind(model, t0, q0, v0, opt);
  // The model shapes what each evaluation asks for: be-linear's one-pass step
  // (Model::evaluate_step) holds no ∂f/∂q, ∂f/∂v or M beside A.
  ev_ = Evaluation{};
  have_mass_ = false;
  dv_step_ = 0.0;
  a_ = model.pattern();
  solver_ = std::make_unique<SparseSolver>(model.pattern(), model.fixed_dofs(), step_solver_options());
}

void BackwardEuler::form_step_matrix(double h, const SparseMatrix* mass) {
  form_step(ev_, {.dfdv = -h, .dfdq = -h * h, .constant_mass = mass}, a_, nullptr);
}

StepResult BackwardEuler::step_linear(double h, int* iters) {
  // A mass that does not depend on q (the continuum's) is assembled once: ev_.mass keeps it.
  if (!have_mass_ && !model_->mass_depends_on_q()) model_->evaluate(t_, q_, v_, kMass, ev_);
  have_mass_ = true;
  const bool mass_known = !model_->mass_depends_on_q();
  // A = M − hD − h²K and r = f + hKv₀ (K with the projected step stiffness,
  // docs/models.md §3.11.2); the sensitivities need K and D apart (and exact).
  const StepWeights weights{.mass = 1.0,
                            .dfdv = -h,
                            .dfdq = -h * h,
                            .rhs_dfdq = h,
                            .w = &v_,
                            .constant_mass = mass_known ? &ev_.mass : nullptr};
  if (dq_dp_.cols() > 0) {
    model_->evaluate(t_, q_, v_, kForce | kDfdq | kDfdv | (mass_known ? 0u : kMass), ev_);
    form_step(ev_, weights, a_, &rhs_);
  } else {
    model_->evaluate_step(t_, q_, v_, weights, ev_, a_, rhs_);
  }
  ++stats_.rhs_evals;
  ++stats_.jac_evals;
  ++stats_.linear_setups;
  if (!solver_->factorize(a_)) return {Outcome::diverged, solver_->failure()};
  rhs_ *= h;
  // GMRES starts from the previous step's Δv ≈ h a, scaled to this step
  // (a warm start, docs/design.md §6.3).
  const bool warm = dv_step_ > 0.0;
  if (warm && dv_step_ != h) dv_ *= h / dv_step_;
  dv_step_ = 0.0;
  if (!solver_->solve(rhs_, dv_, warm)) return {Outcome::diverged, solver_->failure()};
  dv_step_ = h;
  ++stats_.linear_solves;
  if (dq_dp_.cols() > 0 && !propagate_linear_sensitivities(h, dv_))
    return {Outcome::diverged, "sensitivity solve: " + solver_->failure()};
  v_ += dv_;
  zero_fixed(v_, fixed_);
  q_ += h * v_;
  *iters = 1;
  return {};
}

StepResult BackwardEuler::step_newton(double h, int* iters) {
  const Vec q0 = q_, v0 = v_;
  // M(q₀) and the first Jacobian come from the start of the step.
  model_->evaluate(t_, q0, v0, kForce | kDfdq | kStepStiffness | kDfdv | kMass, ev_);
  ++stats_.rhs_evals;
  ++stats_.jac_evals;
  const SparseMatrix m0 = ev_.mass;
  Vec v = v0;
  auto residual = [&](const Vec& vv, Vec& g) {
    g = m0 * (vv - v0) - h * ev_.force;
    zero_fixed(g, fixed_);
  };
  // Initial guess v₁ = v₀, evaluated at the end-of-step position q₀ + h v₀.
  Vec g;
  model_->evaluate(t_ + h, q0 + h * v, v, kForce | kDfdq | kStepStiffness | kDfdv, ev_);
  ++stats_.rhs_evals;
  ++stats_.jac_evals;
  residual(v, g);
  const double g0 = std::max(g.norm(), 1e-300);
  for (int it = 1; it <= opt_.newton_max_iters; ++it) {
    form_step_matrix(h, &m0);
    ++stats_.linear_setups;
    if (!solver_->factorize(a_))
      return {Outcome::diverged, "Newton matrix: " + solver_->failure(), FailureCause::newton};
    Vec dv;
    if (!solver_->solve(-g, dv))
      return {Outcome::diverged, "Newton matrix: " + solver_->failure(), FailureCause::newton};
    ++stats_.linear_solves;
    ++stats_.nonlinear_iters;
    // Backtracking line search on ‖G‖, from the admissible fraction of the
    // update (docs/design.md §3.6; 1 without admissible states).
    const double gn = g.norm();
    const double reach = admissible_reach(t_ + h, q0 + h * v, t_ + h, q0 + h * (v + dv));
    double alpha = reach;
    Vec v_try, g_try;
    for (int ls = 0; ls < 10; ++ls) {
      v_try = v + alpha * dv;
      model_->evaluate(t_ + h, q0 + h * v_try, v_try, kForce | kDfdq | kStepStiffness | kDfdv, ev_);
      ++stats_.rhs_evals;
      ++stats_.jac_evals;
      residual(v_try, g_try);
      if (g_try.norm() <= (1.0 - 1e-4 * alpha) * gn || ls == 9) break;
      alpha *= 0.5;
    }
    v = v_try;
    g = g_try;
    *iters = it;
    const double vscale = 1.0 + v.lpNorm<Eigen::Infinity>();
    if (!g.allFinite()) return {Outcome::nan, "NaN in Newton residual", FailureCause::newton};
    const bool small_update = reach == 1.0 && alpha * dv.lpNorm<Eigen::Infinity>() <= opt_.newton_tol * vscale;
    if (small_update || g.norm() <= opt_.newton_tol * g0) {
      v_ = v;
      zero_fixed(v_, fixed_);
      q_ = q0 + h * v_;
      if (dq_dp_.cols() > 0 && !propagate_newton_sensitivities(h, q0, v0, m0)) {
        q_ = q0;  // the step is not taken
        v_ = v0;
        return {Outcome::diverged, "sensitivity solve: singular step matrix"};
      }
      return {};
    }
  }
  return {Outcome::diverged, "Newton did not converge in " + std::to_string(opt_.newton_max_iters) + " iterations",
          FailureCause::newton};
}

StepResult BackwardEuler::step(double h) {
  StepResult r = fixed_step(h, [this](double hh, int& iters) {
    return variant_ == Variant::linear ? step_linear(hh, &iters) : step_newton(hh, &iters);
  });
  record_solver(*solver_);
  return r;
}

StepResult BackwardEuler::advance_to(double t_out) {
  return advance_fixed_steps(t_out, [this](double h) { return step(h); });
}

}  // namespace wl
