#include "integrators/symplectic_euler.h"

namespace wl {

void SymplecticEuler::initialize(Model& model, double t0, const Vec& q0, const Vec& v0, const IntegratorOptions& opt) {
  bind(model, t0, q0, v0, opt);
  allocate_evaluation(model, ev_);
  solver_ = std::make_unique<SparseSolver>(model.pattern(), model.fixed_dofs());
  factorized_ = false;
}

StepResult SymplecticEuler::step(double h) {
  return fixed_step(h, [this](double hh, int&) { return move(hh); });
}

StepResult SymplecticEuler::move(double h) {
  const bool refactor = model_->mass_depends_on_q() || !factorized_;
  model_->evaluate(t_, q_, v_, kForce | (refactor ? kMass : 0u), ev_);
  ++stats_.rhs_evals;
  if (refactor) {
    ++stats_.linear_setups;
    if (!solver_->factorize(ev_.mass)) return {Outcome::diverged, "singular mass matrix"};
    factorized_ = true;
  }
  solver_->solve(ev_.force, a_);  // zero on pinned DoFs
  ++stats_.linear_solves;
  v_ += h * a_;
  for (int i : fixed_) v_[i] = 0.0;
  q_ += h * v_;
  return {};
}

StepResult SymplecticEuler::advance_to(double t_out) {
  return advance_fixed_steps(t_out, [this](double h) { return step(h); });
}

}  // namespace wl
