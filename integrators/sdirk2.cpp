#include "integrators/sdirk2.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "integrators/step_clock.h"

namespace wl {
namespace {

void zero_at_fixed(Vec& x, const std::vector<int>& fixed) {
  for (int i : fixed) x[i] = 0.0;
}

// Step-size controller (Hairer & Wanner II.4): the estimate is of a
// first-order solution, so the error scales as h²; safety 0.9, growth within
// [0.2, 5], no growth right after a rejection.
double step_factor(double error, bool after_rejection) {
  const double grow = after_rejection ? 1.0 : 5.0;
  if (error <= 0.0) return grow;
  return std::clamp(0.9 / std::sqrt(error), 0.2, grow);
}

}  // namespace

void Sdirk2::initialize(Model& model, double t0, const Vec& q0, const Vec& v0, const IntegratorOptions& opt) {
  bind(model, t0, q0, v0, opt);
  allocate_evaluation(model, jac_);
  allocate_evaluation(model, res_);
  a_ = model.pattern();
  solver_ = std::make_unique<SparseSolver>(model.pattern(), model.fixed_dofs(), step_solver_options());
  solver_->set_refinement_steps(0);  // the Newton iteration refines
  h_next_ = opt.dt;
  a_last_ = Vec::Zero(model.num_dofs());
  matrix_h_ = 0.0;
  reuse_matrix_ = false;
  q_new_ = q_;  // the error weights read the last end state
  v_new_ = v_;
}

StepResult Sdirk2::refresh_matrix(double t, double h, const Vec& q, const Vec& v) {
  model_->evaluate(t, q, v, kForce | kDfdq | kStepStiffness | kDfdv | kMass, jac_);
  ++stats_.rhs_evals;
  ++stats_.jac_evals;
  const double gh = kGamma * h, gh2 = gh * gh;
  const int nnz = static_cast<int>(a_.nonZeros());
  const double* m = jac_.mass.valuePtr();
  const double* k = jac_.dfdq.valuePtr();
  const double* d = jac_.dfdv.valuePtr();
  double* a = a_.valuePtr();
  for (int i = 0; i < nnz; ++i) a[i] = m[i] - gh * d[i] - gh2 * k[i];
  ++stats_.linear_setups;
  matrix_h_ = 0.0;
  if (!solver_->factorize(a_)) return {Outcome::diverged, "stage matrix: " + solver_->failure(), FailureCause::newton};
  matrix_h_ = h;
  return {};
}

double Sdirk2::weighted_rms(const Vec& eq) const {
  double sum = 0.0;
  for (Eigen::Index i = 0; i < eq.size(); ++i) {
    const double wq = opt_.atol + opt_.rtol * std::max(std::abs(q_[i]), std::abs(q_new_[i]));
    sum += (eq[i] / wq) * (eq[i] / wq);
  }
  const double count = double(eq.size() - Eigen::Index(fixed_.size()));
  return std::sqrt(sum / std::max(count, 1.0));
}

StepResult Sdirk2::solve_stage(double t, double h, const Vec& q_base, const Vec& w, Vec& V, int& iters) {
  const double gh = kGamma * h;
  const bool varying_mass = model_->mass_depends_on_q();
  const unsigned flags = kForce | (varying_mass ? kMass : 0u);
  double previous = std::numeric_limits<double>::infinity();
  int refreshes = 0, since_refresh = 0, done = 0;
  Vec Q, G, dV;
  for (int it = 0; it < opt_.newton_max_iters; ++it, ++since_refresh) {
    done = it + 1;
    Q = q_base + gh * V;
    model_->evaluate(t, Q, V, flags, res_);
    ++stats_.rhs_evals;
    G = (varying_mass ? res_.mass : jac_.mass) * (V - w) - gh * res_.force;
    zero_at_fixed(G, fixed_);
    if (!G.allFinite()) return {Outcome::nan, "NaN in the stage residual", FailureCause::newton};
    if (!solver_->solve(-G, dV))
      return {Outcome::diverged, "stage matrix: " + solver_->failure(), FailureCause::newton};
    ++stats_.linear_solves;
    ++stats_.nonlinear_iters;
    ++iters;
    V += dV;
    // The distance to the solution of a linearly converging iteration with
    // rate θ is about θ/(1 − θ)·‖ΔV‖ (Hairer & Wanner IV.8).
    const double size = dV.lpNorm<Eigen::Infinity>();
    const double rate = std::isfinite(previous) ? size / previous : 1.0;  // unknown on a fresh matrix
    const double remaining = rate < 1.0 ? rate / (1.0 - rate) * size : size;
    // Converged to newton_tol, or to round-off (64 ε) where nothing is left to correct.
    const double floor = std::max(opt_.newton_tol, 64 * std::numeric_limits<double>::epsilon());
    const bool tight = remaining <= floor * (1.0 + V.lpNorm<Eigen::Infinity>());
    // Adaptive mode: the iteration error of the positions, γh·remaining, is a
    // small fraction of the tolerance.
    const bool within_tolerance = opt_.adaptive && weighted_rms(gh * (remaining / std::max(size, 1e-300)) * dV) <= 1e-2;
    if (tight || within_tolerance) {
      reuse_matrix_ = reuse_matrix_ && refreshes == 0 && it < 4;
      return {};
    }
    // Modified Newton stalls (rate ≥ 0.9, or slow, ≥ 0.3, after 8 iterations on
    // one matrix): refresh the Jacobian at the current iterate, at most 3 times.
    const bool known = std::isfinite(previous);
    if ((known && rate >= 0.9) || (known && rate >= 0.3 && since_refresh >= 8)) {
      if (refreshes == 3) break;
      if (StepResult r = refresh_matrix(t, h, q_base + gh * V, V); r.outcome != Outcome::ok) return r;
      ++refreshes;
      since_refresh = -1;
      previous = std::numeric_limits<double>::infinity();
      continue;
    }
    previous = size;
  }
  reuse_matrix_ = false;
  return {Outcome::diverged,
          "stage Newton iteration did not converge in " + std::to_string(done) + " iterations (" +
              std::to_string(refreshes) + " Jacobian refreshes)",
          FailureCause::newton};
}

Sdirk2::Attempt Sdirk2::failed(Attempt a) {
  reuse_matrix_ = false;  // the next attempt starts from a fresh Jacobian
  return a;
}

Sdirk2::Attempt Sdirk2::attempt(double h) {
  Attempt a;
  const double gh = kGamma * h;
  // The last step's matrix serves again while its Newton iterations converged
  // fast, the step changed by at most 20 % and the mass is constant (the
  // iteration matrix only steers Newton: the residual is exact).
  if (!(reuse_matrix_ && !model_->mass_depends_on_q() && matrix_h_ > 0.0 && std::abs(h / matrix_h_ - 1.0) <= 0.2)) {
    a.result = refresh_matrix(t_, h, q_, v_);
    if (a.result.outcome != Outcome::ok) return a;
  }
  reuse_matrix_ = true;  // each stage below withdraws it if it converged slowly
  // Stage 1, started from the last step's end acceleration.
  V1_ = v_ + gh * a_last_;
  zero_at_fixed(V1_, fixed_);
  a.result = solve_stage(t_ + gh, h, q_, v_, V1_, a.iters);
  if (a.result.outcome != Outcome::ok) return failed(a);
  Q1_ = q_ + gh * V1_;
  const Vec A1 = (V1_ - v_) / gh;
  // Stage 2, started from the first stage's acceleration.
  w2_ = v_ + (1.0 - kGamma) * h * A1;
  qb2_ = q_ + (1.0 - kGamma) * h * V1_;
  V2_ = v_ + h * A1;
  a.result = solve_stage(t_ + h, h, qb2_, w2_, V2_, a.iters);
  if (a.result.outcome != Outcome::ok) return failed(a);
  q_new_ = qb2_ + gh * V2_;
  v_new_ = V2_;
  if (!opt_.adaptive) return a;
  // ê = γh (V₂ − V₁, A₂ − A₁), filtered: (M − γhD − γ²h²K) x_v = M ê_v + γh K ê_q, x_q = ê_q + γh x_v.
  const Vec eq = gh * (V2_ - V1_);
  const Vec ev = (V2_ - w2_) - (V1_ - v_);
  Vec rhs = jac_.mass * ev + gh * (jac_.dfdq * eq), xv;
  zero_at_fixed(rhs, fixed_);
  if (!solver_->solve(rhs, xv)) {
    a.result = {Outcome::diverged, "error filter: " + solver_->failure(), FailureCause::newton};
    return a;
  }
  ++stats_.linear_solves;
  Vec xq = eq + gh * xv;
  zero_at_fixed(xq, fixed_);
  a.error = weighted_rms(xq);
  if (!std::isfinite(a.error)) a.result = {Outcome::nan, "NaN in the error estimate", FailureCause::newton};
  return a;
}

StepResult Sdirk2::accept(double h) {
  if (dq_dp_.cols() > 0)
    if (StepResult r = propagate_sensitivities(h); r.outcome != Outcome::ok) return r;
  a_last_ = (V2_ - w2_) / (kGamma * h);
  q_ = q_new_;
  v_ = v_new_;
  return {};
}

StepResult Sdirk2::adaptive_step(double t_out) {
  double h = 0.0, wall = 0.0;
  int iters = 0;
  StepResult result;
  {
    StepClock clock(stats_);
    bool rejected = false;
    for (;;) {
      h = std::min(h_next_, t_out - t_);
      const bool clipped = h < h_next_;
      if (h < opt_.min_step && !clipped) {
        char below[96];
        std::snprintf(below, sizeof below, "step %.3g s below the minimum %.3g s", h, opt_.min_step);
        return {Outcome::step_too_small,
                below + (result.message.empty() ? std::string() : " (last failure: " + result.message + ")")};
      }
      Attempt a = attempt(h);
      iters += a.iters;
      // A step that would take a node out of the admissible states is rejected
      // and retaken shorter (docs/design.md §3.6).
      const bool passed = a.result.outcome == Outcome::ok && a.error <= 1.0;
      const double reach = passed ? admissible_reach(t_, q_, t_ + h, q_new_) : 1.0;
      if (reach < 1.0) a.result = {Outcome::invalid_state, "a node would enter an obstacle"};
      if (passed && reach == 1.0) {
        result = accept(h);
        if (result.outcome != Outcome::ok) return result;
        const double proposal = h * step_factor(a.error, rejected);
        h_next_ = clipped ? std::min(h_next_, std::max(proposal, h)) : proposal;
        break;
      }
      ++stats_.rejected_steps;
      rejected = true;
      result = a.result;
      h_next_ = reach < 1.0                       ? h * std::clamp(0.9 * reach, 0.1, 0.5)
                : a.result.outcome == Outcome::ok ? h * step_factor(a.error, true)
                                                  : 0.25 * h;
    }
    wall = clock.elapsed_wall();
  }
  return finish_step(t_ + h, h, iters, wall);
}

StepResult Sdirk2::advance_to(double t_out) {
  StepResult r = advance(t_out);
  record_solver(*solver_);
  return r;
}

StepResult Sdirk2::advance(double t_out) {
  if (!opt_.adaptive) {
    return advance_fixed_steps(t_out, [this](double h) {
      return fixed_step(h, [this](double hh, int& iters) {
        Attempt a = attempt(hh);
        iters = a.iters;
        return a.result.outcome == Outcome::ok ? accept(hh) : a.result;
      });
    });
  }
  const double eps = 1e-12 * std::max(1.0, std::abs(t_out));
  while (t_out - t_ > eps) {
    if (stats_.steps >= opt_.max_steps)
      return {Outcome::max_steps, "step limit reached (" + std::to_string(opt_.max_steps) + " steps)"};
    if (StepResult r = adaptive_step(t_out); r.outcome != Outcome::ok) return r;
  }
  t_ = t_out;
  return {};
}

}  // namespace wl
