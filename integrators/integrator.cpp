// The Integrator base: outcomes, state checks, binding and the step
// bookkeeping every method shares (docs/design.md §6.1).
#include "integrators/integrator.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "integrators/step_clock.h"
#include "models/core/sliding_coordinates.h"
#include "models/core/term_model.h"

namespace wl {

const char* to_string(Outcome o) {
  switch (o) {
    case Outcome::ok: return "ok";
    case Outcome::diverged: return "diverged";
    case Outcome::nan: return "nan";
    case Outcome::step_too_small: return "step_too_small";
    case Outcome::max_steps: return "max_steps";
    case Outcome::not_offered: return "not_offered";
    case Outcome::interrupted: return "interrupted";
    case Outcome::invalid_state: return "invalid_state";
  }
  return "unknown";
}

StepResult check_state(const Vec& q, const Vec& v, const IntegratorOptions& opt) {
  if (!q.allFinite() || !v.allFinite()) return {Outcome::nan, "NaN or Inf in the state"};
  const double vmax = v.lpNorm<Eigen::Infinity>();
  if (vmax > opt.runaway_speed)
    return {Outcome::diverged,
            "runaway state: max |v| = " + std::to_string(vmax) + " exceeds " + std::to_string(opt.runaway_speed),
            FailureCause::runaway_speed};
  return {};
}

namespace {

// What restricts a model's states, in words: "rigid obstacles", "self-contact" or both,
// from its terms that constrain steps ("admissible states" for a model without terms).
std::string step_constraints_of(const Model& model) {
  const auto* terms = dynamic_cast<const TermModel*>(&model);
  if (!terms) return "its own restrictions";
  bool obstacles = false, self_contact = false;
  for (const auto& t : terms->terms()) {
    if (!t->constrains_steps()) continue;
    (t->name() == "self_contact" ? self_contact : obstacles) = true;
  }
  if (obstacles && self_contact) return "rigid obstacles and self-contact";
  return self_contact ? "self-contact" : "rigid obstacles";
}

}  // namespace

StepResult Integrator::check_state(const Vec& q, const Vec& v, const IntegratorOptions& opt) const {
  if (std::string why = model_->invalid_state(q); !why.empty()) return {Outcome::invalid_state, why};
  return wl::check_state(q, v, opt);
}

void Integrator::bind(Model& model, double t0, const Vec& q0, const Vec& v0, const IntegratorOptions& opt) {
  model_ = &model;
  opt_ = opt;
  t_ = t0;
  q_ = q0;
  v_ = v0;
  fixed_.assign(model.fixed_dofs().begin(), model.fixed_dofs().end());
  refusal_.clear();
  if (model.constrains_steps() && !capabilities().admissible_steps)
    refusal_ = "integrator '" + name() + "' is not offered for a model with admissible states (" +
               step_constraints_of(model) + "): its library steps cannot be shortened to keep them (docs/design.md " +
               "§3.6)";
  for (int i : fixed_) v_[i] = 0.0;
  stats_ = {};
  if (!sensitivity_keys_.empty()) {
    if (!offers_sensitivities())
      throw std::invalid_argument("integrator '" + name() + "' does not offer parameter sensitivities");
    if (model.projects_step_stiffness())  // they differentiate the step with the exact ∂f/∂q
      throw std::invalid_argument(
          "parameter sensitivities need the exact step matrix; this scene projects a term's Hessian in it: set "
          "[obstacle_contact] step_hessian = \"exact\" and [terms] stretch_step_hessian = \"exact\" "
          "(docs/models.md §3.11.2, §3.2)");
    const std::vector<std::string> known = model.parameter_keys();
    for (const std::string& key : sensitivity_keys_)
      if (std::find(known.begin(), known.end(), key) == known.end())
        throw std::invalid_argument("the " + model.name() + " model of this scene does not differentiate '" + key +
                                    "'");
  }
  dq_dp_ = Eigen::MatrixXd::Zero(model.num_dofs(), static_cast<Eigen::Index>(sensitivity_keys_.size()));
  dv_dp_ = dq_dp_;
}

StepResult Integrator::advance_fixed_steps(double t_out, const std::function<StepResult(double)>& step) {
  if (!refusal_.empty()) return {Outcome::not_offered, refusal_};
  while (t_out - t_ > 1e-9 * opt_.dt) {
    if (stats_.steps >= opt_.max_steps) return {Outcome::max_steps, "step limit reached"};
    double h = std::min(opt_.dt, t_out - t_);
    if (t_out - t_ - h < 1e-9 * opt_.dt) h = t_out - t_;
    StepResult r = step(h);
    if (r.outcome != Outcome::ok) return r;
  }
  t_ = t_out;
  return {};
}

double Integrator::admissible_reach(double t0, const Vec& q0, double t1, const Vec& q1) const {
  return model_->constrains_steps() ? model_->admissible_fraction(t0, q0, t1, q1) : 1.0;
}

StepResult Integrator::fixed_step(double h, const std::function<StepResult(double, int&)>& move) {
  return fixed_step_part(h, 0, move);
}

StepResult Integrator::fixed_step_part(double h, int halvings, const std::function<StepResult(double, int&)>& move) {
  // A step whose Newton iteration fails is retaken as two halves, for every
  // model, at most kMaxNewtonHalvings times in a row; a model with admissible
  // states (docs/design.md §3.6) also retakes a step whose move leaves them,
  // down to opt_.min_step.
  const bool constrained = model_->constrains_steps();
  const Vec q0 = q_, v0 = v_;
  const Eigen::MatrixXd sq = dq_dp_, sv = dv_dp_;
  int iters = 0;
  double wall = 0.0;
  StepResult r;
  {
    StepClock clock(stats_);
    r = move(h, iters);
    wall = clock.elapsed_wall();
  }
  const bool inadmissible = constrained && r.outcome == Outcome::ok && admissible_reach(t_, q0, t_ + h, q_) < 1.0;
  const bool newton_failed = r.outcome != Outcome::ok && r.cause == FailureCause::newton;
  if (!inadmissible && !newton_failed) return r.outcome != Outcome::ok ? r : finish_step(t_ + h, h, iters, wall);
  q_ = q0;
  v_ = v0;
  dq_dp_ = sq;
  dv_dp_ = sv;
  ++stats_.rejected_steps;
  if (0.5 * h < opt_.min_step) {
    char below[96];
    std::snprintf(below, sizeof below, "step %.3g s below the minimum %.3g s", 0.5 * h, opt_.min_step);
    return {Outcome::step_too_small, below + std::string(constrained ? " while keeping nodes outside obstacles" : "") +
                                         (r.message.empty() ? "" : " (last failure: " + r.message + ")")};
  }
  if (newton_failed && !constrained && halvings == kMaxNewtonHalvings) {
    char where[160];
    std::snprintf(where, sizeof where, " (the step retaken in halves %d times, down to %.4g s, at t = %.9g s)",
                  kMaxNewtonHalvings, h, t_);
    r.message += where;
    return r;
  }
  if (StepResult first = fixed_step_part(0.5 * h, halvings + 1, move); first.outcome != Outcome::ok) return first;
  return fixed_step_part(0.5 * h, halvings + 1, move);
}

StepResult Integrator::finish_step(double t_new, double h, long nonlinear_iters, double wall_s) {
  StepResult r = check_state(q_, v_, opt_);
  if (r.outcome != Outcome::ok) return r;
  t_ = t_new;
  ++stats_.steps;
  if (SlidingCoordinates* sliding = sliding_coordinates(*model_); sliding && dq_dp_.cols() > 0)
    sliding->accept_step_sensitivities(sensitivity_keys_, q_, v_, dq_dp_, dv_dp_, h);
  model_->accept_step(t_, q_, v_, h);
  if (on_step) on_step({t_, h, static_cast<int>(nonlinear_iters), wall_s});
  return r;
}

StepResult Integrator::advance_library_steps(double t_out, IntegratorStats& timing, const LibraryStepper& library) {
  if (!refusal_.empty()) return {Outcome::not_offered, refusal_};
  const int n = model_->num_dofs();
  StepResult result;
  {
    StepClock clock(timing);
    const double eps = 1e-12 * std::max(1.0, std::abs(t_out));
    if (t_out - t_ > eps) library.set_stop_time(t_out);
    long last_nonlinear_iters = stats_.nonlinear_iters;
    while (t_out - t_ > eps) {
      if (stats_.steps >= opt_.max_steps) {
        result = {Outcome::max_steps, "step limit reached (" + std::to_string(opt_.max_steps) + " steps)"};
        break;
      }
      const double wall0 = clock.elapsed_wall();
      double t_reached = t_;
      const int flag = library.step(t_out, t_reached);
      library.update_stats();
      if (flag < 0) {
        result = library.failure(flag);
        break;
      }
      q_ = Eigen::Map<const Vec>(library.y, n);
      v_ = Eigen::Map<const Vec>(library.y + n, n);
      result = finish_step(t_reached, t_reached - t_, stats_.nonlinear_iters - last_nonlinear_iters,
                           clock.elapsed_wall() - wall0);
      last_nonlinear_iters = stats_.nonlinear_iters;
      if (result.outcome != Outcome::ok) break;
    }
    if (result.outcome == Outcome::ok) t_ = t_out;
  }
  library.update_stats();
  return result;
}

SparseSolver::Options Integrator::step_solver_options() const {
  return {opt_.linear_solver, model_->asymmetric_terms()};
}

void Integrator::record_solver(const SparseSolver& solver) {
  const SparseSolver::Statistics& s = solver.statistics();
  stats_.factorizations = s.factorizations;
  stats_.krylov_iters = s.krylov_iterations;
  stats_.step_matrix_asymmetry = s.max_asymmetry;
  stats_.linear_solver = solver.description();
}

}  // namespace wl
