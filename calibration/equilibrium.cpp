#include "calibration/equilibrium.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "models/core/energy_descent.h"

namespace wl {

EquilibriumSolver::EquilibriumSolver(Model& model, std::vector<int> prescribed) : model_(model) {
  held_ = std::move(prescribed);
  for (int d : model.fixed_dofs()) held_.push_back(d);
  std::sort(held_.begin(), held_.end());
  held_.erase(std::unique(held_.begin(), held_.end()), held_.end());
  is_held_.assign(model.num_dofs(), 0);
  for (int d : held_) is_held_[d] = 1;
  // The method by what the model declares of ∂f/∂q (auto: CHOLMOD's LLᵀ of −K when it is
  // symmetric, with the LU where −K is not positive definite; docs/design.md §6.3).
  solver_ = std::make_unique<SparseSolver>(
      model.pattern(), held_, SparseSolverOptions{LinearSolverMethod::automatic, model.asymmetric_terms()});
  allocate_evaluation(model, eval_);
  zero_v_ = Vec::Zero(model.num_dofs());
}

double EquilibriumSolver::free_norm(const Vec& f) const {
  double m = 0.0;
  for (Eigen::Index i = 0; i < f.size(); ++i)
    if (!is_held_[i]) m = std::max(m, std::abs(f[i]));
  return m;
}

double EquilibriumSolver::held_norm(const Vec& f) const {
  double m = 0.0;
  for (int d : held_) m = std::max(m, std::abs(f[d]));
  return m;
}

EquilibriumResult EquilibriumSolver::solve(Vec& q, const EquilibriumOptions& opt) {
  if (!(opt.descent_tolerance > 0.0)) return newton(q, opt);
  const Vec start = q;
  EquilibriumResult res = newton(q, opt);
  if (res.converged || res.stopped) return res;
  // Energy descent from the same start (docs/models.md §11.8), then the stiffness
  // at its end factorized for solve_free().
  q = start;
  factored_ = false;  // Newton's last factor is of another state
  const DescentResult d =
      descend_energy(model_, q, held_, opt.descent_tolerance, opt.descent_max_steps, opt.stop_requested);
  res.descent_steps = d.steps;
  model_.evaluate(0.0, q, zero_v_, kForce | kDfdq, eval_);
  res.residual = d.residual_N;
  if (opt.stop_requested && opt.stop_requested()) {
    res.stopped = true;
    res.message = "stopped after " + std::to_string(d.steps) + " energy descent steps";
    return res;
  }
  if (!(d.residual_N <= opt.descent_tolerance)) {
    std::ostringstream why;
    why << res.message << "; energy descent then stopped at residual " << d.residual_N << " N > "
        << opt.descent_tolerance << " N after " << d.steps << " steps";
    res.message = why.str();
    return res;
  }
  res.converged = true;  // a minimum; only solve_free() needs the factorization
  res.message = factorize_stiffness() ? "" : "singular stiffness at the energy minimum: no solve_free()";
  return res;
}

bool EquilibriumSolver::factorize_stiffness() {
  if (neg_k_.nonZeros() != eval_.dfdq.nonZeros()) neg_k_ = eval_.dfdq;  // the pattern, once
  std::transform(eval_.dfdq.valuePtr(), eval_.dfdq.valuePtr() + eval_.dfdq.nonZeros(), neg_k_.valuePtr(),
                 [](double k) { return -k; });
  factored_ = solver_->factorize(neg_k_);
  return factored_;
}

EquilibriumResult EquilibriumSolver::newton(Vec& q, const EquilibriumOptions& opt) {
  EquilibriumResult res;
  Vec dx, trial;
  model_.evaluate(0.0, q, zero_v_, kForce | kDfdq, eval_);
  for (;;) {
    res.residual = free_norm(eval_.force);
    if (!std::isfinite(res.residual)) {
      res.message = "the force is not finite";
      return res;
    }
    const double tol = opt.rtol * held_norm(eval_.force) + opt.atol;
    const bool factored = factorize_stiffness();
    if (res.residual <= tol) {
      res.converged = factored;
      if (!factored) res.message = "singular stiffness at equilibrium";
      return res;
    }
    if (!factored) {
      res.message = "singular stiffness after " + std::to_string(res.iterations) + " iterations";
      return res;
    }
    if (opt.stop_requested && opt.stop_requested()) {
      res.stopped = true;
      res.message = "stopped after " + std::to_string(res.iterations) + " Newton iterations";
      return res;
    }
    if (res.iterations >= opt.max_iterations) {
      std::ostringstream s;
      s << "no equilibrium after " << res.iterations << " Newton iterations (residual " << res.residual
        << " N, tolerance " << tol << " N)";
      res.message = s.str();
      return res;
    }
    ++res.iterations;
    solver_->solve(eval_.force, dx);  // −K dx = f
    // Backtracking on ‖f_f‖: accept the first step that reduces the residual.
    double alpha = 1.0;
    bool accepted = false;
    for (int b = 0; b <= opt.max_backtracks; ++b, alpha *= 0.5) {
      trial = q + alpha * dx;
      model_.evaluate(0.0, trial, zero_v_, kForce | kDfdq, eval_);
      const double r = free_norm(eval_.force);
      if (std::isfinite(r) && r < (1.0 - 1e-4 * alpha) * res.residual) {
        accepted = true;
        break;
      }
    }
    if (!accepted) {
      // No decrease along the Newton direction (an inexact Jacobian, e.g. the
      // yarn model's frozen F_n, or a non-smooth response): report it.
      model_.evaluate(0.0, q, zero_v_, kForce | kDfdq, eval_);
      std::ostringstream s;
      s << "line search failed after " << res.iterations << " iterations (residual " << res.residual << " N)";
      res.message = s.str();
      return res;
    }
    q = trial;
  }
}

void EquilibriumSolver::solve_free(const Vec& b, Vec& x) const {
  if (!factored_) throw std::runtime_error("equilibrium: no factorized stiffness at this state for solve_free()");
  solver_->solve(b, x);
}

}  // namespace wl
