// Quasi-static equilibrium of a Model under prescribed boundary motion
// (docs/calibration.md §1): find the free DoFs q_f with f_f(q, v = 0) = 0 by
// Newton's method on the assembled stiffness K = ∂f/∂q, with a backtracking
// line search on ‖f_f‖. The model's own pinned DoFs and the prescribed DoFs
// hold the values the caller put into q.
//
// Which forces take part is the caller's choice of model: the virtual material
// tests build their patches with stretch, bending, shear and (when sliding)
// parallel contact only — gravity, wind, handles, friction and inertia are
// switched off (material_test_scene(), virtual_tests.h). Velocities are zero.
#pragma once
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "integrators/sparse_solver.h"
#include "models/core/model.h"

namespace wl {

struct EquilibriumOptions {
  int max_iterations = 60;
  // Converged when ‖f_f‖∞ ≤ rtol·‖f_prescribed‖∞ + atol (reactions set the force scale).
  double rtol = 1e-10;
  double atol = 1e-13;  // [N]
  int max_backtracks = 20;
  // > 0: where Newton fails, energy descent (models/core/energy_descent.h) from the
  // same start to ‖f_f‖∞ ≤ descent_tolerance [N] (a knit's free edges or self-stressed
  // rest shape: indefinite stiffness, docs/models.md §11.8); 0: Newton alone.
  double descent_tolerance = 0.0;
  int descent_max_steps = 4000;
  // Asked before each Newton iteration and descent step: true ends the solve
  // there, unconverged (EquilibriumResult::stopped; the command line's SIGINT/SIGTERM).
  std::function<bool()> stop_requested;
};

struct EquilibriumResult {
  bool converged = false;
  int iterations = 0;
  double residual = 0.0;  // ‖f_f‖∞ at the returned state [N]
  std::string message;    // why it did not converge
  int descent_steps = 0;  // energy descent steps after a failed Newton solve (descent_tolerance > 0)
  bool stopped = false;   // EquilibriumOptions::stop_requested ended it
};

class EquilibriumSolver {
 public:
  // `prescribed`: DoFs whose values the caller sets (in addition to the model's pinned DoFs).
  EquilibriumSolver(Model& model, std::vector<int> prescribed);

  // Solves in place: q holds the prescribed values and the initial guess of the free DoFs.
  // After a converged solve the stiffness at q is factorized (solve_free()).
  // With options.descent_tolerance > 0 a failed Newton solve is followed by energy
  // descent from the same start; `iterations` then counts Newton's, `descent_steps`
  // the descent's, and a failure's message names both.
  EquilibriumResult solve(Vec& q, const EquilibriumOptions& options = {});

  // Makes the next solve() what it is on a new solver for the same model and
  // DoFs (the sparse solver restart()s), keeping the pattern work.
  void restart() {
    solver_->restart();
    factored_ = false;
  }

  // Force and ∂f/∂q at the state of the last solve.
  const Evaluation& evaluation() const { return eval_; }
  // x = (−K_ff)⁻¹ b_f on the free DoFs (zero on the held DoFs), with the
  // factorization of the last converged solve: dq_f/dp = solve_free(∂f/∂p).
  void solve_free(const Vec& b, Vec& x) const;

 private:
  EquilibriumResult newton(Vec& q, const EquilibriumOptions& options);
  double free_norm(const Vec& f) const;
  double held_norm(const Vec& f) const;
  // Factorizes −K at eval_ for the Newton step and solve_free(); false when singular.
  bool factorize_stiffness();

  Model& model_;
  std::vector<int> held_;  // pinned ∪ prescribed, sorted
  std::vector<char> is_held_;
  std::unique_ptr<SparseSolver> solver_;
  Evaluation eval_;
  SparseMatrix neg_k_;
  bool factored_ = false;  // −K at the current state is factorized
  Vec zero_v_;
};

}  // namespace wl
