// The Integrator interface: advances a Model through time knowing nothing of
// yarns or triangles (docs/design.md §6.1). Every integrator reports
// the same statistics and ends in a structured outcome instead of aborting.
#pragma once
#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "integrators/sparse_solver.h"
#include "models/core/model.h"

namespace wl {

// invalid_state: the model cannot represent the state reached (Model::invalid_state;
// e.g. sliding coordinates that meet, docs/models.md §2.2); the message names where.
enum class Outcome { ok, diverged, nan, step_too_small, max_steps, not_offered, interrupted, invalid_state };
const char* to_string(Outcome o);

struct IntegratorStats {
  long steps = 0;
  long rejected_steps = 0;
  long rhs_evals = 0;      // force evaluations
  long jac_evals = 0;      // Jacobian (∂f/∂q, ∂f/∂v) evaluations
  long linear_setups = 0;  // numeric factorizations
  long linear_solves = 0;
  long nonlinear_iters = 0;            // Newton iterations (implicit methods)
  long factorizations = 0;             // sparse numeric factorizations (fewer than setups when gmres keeps one)
  long krylov_iters = 0;               // GMRES iterations (linear solver gmres)
  std::string linear_solver;           // the step matrix solver in use (SparseSolver::description())
  double step_matrix_asymmetry = 0.0;  // largest ‖A − Aᵀ‖_F / ‖A‖_F seen
  double wall_s = 0.0;
  double cpu_s = 0.0;
};

struct IntegratorOptions {
  double dt = 1e-3;  // fixed step, or initial step when adaptive [s]
  bool adaptive = false;
  double rtol = 1e-6;
  double atol = 1e-9;
  long max_steps = 10000000;  // over the whole run
  double min_step = 1e-12;    // [s]
  // Newton (implicit methods)
  double newton_tol = 1e-8;  // relative residual / update tolerance
  int newton_max_iters = 20;
  // A state whose max |v| exceeds this is a divergence [m/s].
  double runaway_speed = 1e4;
  // Solver of the step matrices (integrators/sparse_solver.h).
  LinearSolverMethod linear_solver = LinearSolverMethod::automatic;
};

// One accepted step, for metrics and progress.
struct StepRecord {
  double t = 0.0;
  double h = 0.0;
  int nonlinear_iters = 0;
  double wall_s = 0.0;
};

// What detected a failure that no library reported (a library's failure
// carries its flag in StepResult instead), for callers that classify failures
// without reading messages (docs/design.md §6.1).
enum class FailureCause {
  other,          // no failure, or one the outcome and message describe (a singular matrix, an invalid state)
  runaway_speed,  // a speed beyond IntegratorOptions::runaway_speed or beyond a caller's bound
  newton,         // the Newton iteration of an in-house implicit method (its matrix, its residual, no convergence)
};

struct StepResult {
  StepResult() = default;
  StepResult(Outcome o, std::string msg, int flag = 0, std::string flag_name = {})
      : outcome(o), message(std::move(msg)), library_flag(flag), library_flag_name(std::move(flag_name)) {}
  StepResult(Outcome o, std::string msg, FailureCause c) : outcome(o), message(std::move(msg)), cause(c) {}

  Outcome outcome = Outcome::ok;
  std::string message;  // filled when outcome != ok
  // The return flag of the library that reported the failure (SUNDIALS:
  // e.g. -4 and "ARK_CONV_FAILURE"); 0 and "" when the failure is not a library's.
  int library_flag = 0;
  std::string library_flag_name;
  FailureCause cause = FailureCause::other;
};

// How a method's energy behaves on an undamped oscillator (docs/design.md §6.1).
enum class EnergyBehaviour {
  dissipative,        // decays monotonically (numerical damping: backward Euler)
  bounded,            // oscillates within O(h) of the initial energy, no drift (symplectic)
  follows_tolerance,  // conserved to the error tolerance (error-controlled methods)
};

// What a method is and offers, declared once by each integrator and read by
// the experiments and the test suite (docs/design.md §6.1).
struct IntegratorCapabilities {
  bool controls_error = false;        // adapts its step to rtol/atol (honours IntegratorOptions::adaptive)
  int fixed_step_order = 0;           // classical order at fixed steps; 0: no fixed-step mode (variable order)
  bool explicit_method = false;       // no linear solves with the Jacobian; step bounded by stability
  bool state_dependent_mass = false;  // integrates models whose M depends on q
  bool sensitivities = false;         // carries forward parameter sensitivities
  // A one-step method that can retake a recorded step sequence in fixed-step
  // mode (advance_to each step end with dt ≥ the step): its global error is
  // estimated by halving every recorded step (driver/time_error.h).
  bool replays_steps = false;
  EnergyBehaviour energy = EnergyBehaviour::dissipative;
  // Honours a model's admissible states (Model::constrains_steps, docs/design.md
  // §3.6): no accepted step leaves them (a step that would is retaken shorter)
  // and Newton iterates stay within the admissible fraction. A method without
  // it refuses such a model (Outcome::not_offered).
  bool admissible_steps = false;
};

class Integrator {
 public:
  virtual ~Integrator() = default;
  virtual std::string name() const = 0;
  virtual IntegratorCapabilities capabilities() const = 0;
  // Binds the model and the initial state (t0, q0, v0).
  virtual void initialize(Model& model, double t0, const Vec& q0, const Vec& v0, const IntegratorOptions& opt) = 0;
  // Advances to exactly t_out (stepping or interpolating as the method does).
  virtual StepResult advance_to(double t_out) = 0;
  // From now on, fixed steps of dt (a fixed-step run's settling phase,
  // docs/models.md §3.11.6); the state, history and statistics carry on.
  // Honoured by the methods that replay steps (IntegratorCapabilities::replays_steps).
  void set_fixed_step(double dt) { opt_.dt = dt; }
  double t() const { return t_; }
  const Vec& q() const { return q_; }
  const Vec& v() const { return v_; }
  const IntegratorStats& stats() const { return stats_; }
  std::function<void(const StepRecord&)> on_step;  // called after each accepted step

  // Forward parameter sensitivities (docs/models.md §9.2): a method that offers
  // them carries S_q = ∂q/∂p and S_v = ∂v/∂p (num_dofs × keys, zero at t0)
  // for the model's parameter keys named here. Call before initialize(), which
  // throws std::invalid_argument for a key the model does not differentiate.
  bool offers_sensitivities() const { return capabilities().sensitivities; }
  void track_sensitivities(std::vector<std::string> keys) { sensitivity_keys_ = std::move(keys); }
  const std::vector<std::string>& sensitivity_keys() const { return sensitivity_keys_; }
  const Eigen::MatrixXd& dq_dp() const { return dq_dp_; }
  const Eigen::MatrixXd& dv_dp() const { return dv_dp_; }

 protected:
  // Fixed steps of opt_.dt from t_ to exactly t_out (the last one shortened),
  // honouring opt_.max_steps; `step(h)` is one fixed_step of size h.
  StepResult advance_fixed_steps(double t_out, const std::function<StepResult(double)>& step);
  // One step of size h of an in-house method: `move(h, nonlinear_iters)`
  // advances q_ and v_ (timed into stats_), then finish_step does the rest. A
  // step whose Newton iteration fails is retaken as two halves (docs/design.md
  // §6.1), at most kMaxNewtonHalvings times in a row; a model with admissible
  // states also retakes a step that leaves them (§3.6), down to opt_.min_step.
  StepResult fixed_step(double h, const std::function<StepResult(double h, int& nonlinear_iters)>& move);
  static constexpr int kMaxNewtonHalvings = 10;
  // The bookkeeping after every step of every method: checks the state
  // (q_, v_) reached by a step of size h at t_new (check_state); when it is
  // sound, sets t_ = t_new, counts the step, lets the model update its history
  // (Model::accept_step) and reports the step (on_step). A failed check leaves
  // t_ and the count.
  StepResult finish_step(double t_new, double h, long nonlinear_iters, double wall_s);
  // fixed_step at `halvings` halvings below the step first asked for.
  StepResult fixed_step_part(double h, int halvings, const std::function<StepResult(double, int&)>& move);
  // Shared part of initialize(): binds the model and options, sets the state
  // (pinned DoFs at rest) and clears the statistics.
  void bind(Model& model, double t0, const Vec& q0, const Vec& v0, const IntegratorOptions& opt);
  // A library integrator in one-step mode (SUNDIALS), for advance_library_steps.
  struct LibraryStepper {
    std::function<void(double t_out)> set_stop_time;
    std::function<int(double t_out, double& t_reached)> step;  // one step towards t_out: the library's flag
    std::function<void()> update_stats;                        // the library's counters into stats_
    std::function<StepResult(int flag)> failure;               // the outcome of a negative flag
    const double* y = nullptr;                                 // the library's state (q, v) after a step
  };
  // Library steps from t_ to exactly t_out (the library's stop time), each
  // through finish_step, honouring opt_.max_steps; wall and CPU time go to
  // `timing`.
  StepResult advance_library_steps(double t_out, IntegratorStats& timing, const LibraryStepper& library);
  // The options of the step matrix solver for this model (opt_ and the model's asymmetric terms).
  SparseSolver::Options step_solver_options() const;
  // Copies a step matrix solver's statistics into stats_.
  void record_solver(const SparseSolver& solver);
  // The model's admissible fraction of the move (t0, q0) → (t1, q1); 1 for a
  // model without admissible states (docs/design.md §3.6).
  double admissible_reach(double t0, const Vec& q0, double t1, const Vec& q1) const;
  // The free check_state below, preceded by the model's own rule for states it
  // cannot represent (Outcome::invalid_state with the model's message).
  StepResult check_state(const Vec& q, const Vec& v, const IntegratorOptions& opt) const;

  Model* model_ = nullptr;
  IntegratorOptions opt_;
  double t_ = 0.0;
  Vec q_, v_;
  std::vector<int> fixed_;  // pinned DoFs (model.fixed_dofs())
  std::string refusal_;     // why this method does not take the bound model (not_offered), or empty
  IntegratorStats stats_;
  std::vector<std::string> sensitivity_keys_;
  Eigen::MatrixXd dq_dp_, dv_dp_;
};

// Names accepted by make_integrator, in documentation order.
std::vector<std::string> integrator_names();
// Creates an integrator by name; throws std::invalid_argument for an unknown name.
std::unique_ptr<Integrator> make_integrator(const std::string& name);

// Checks a state for NaN/Inf and runaway speed; used by every integrator.
StepResult check_state(const Vec& q, const Vec& v, const IntegratorOptions& opt);

}  // namespace wl
