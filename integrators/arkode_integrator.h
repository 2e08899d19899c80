// SUNDIALS ARKODE (ARKStep) on the first-order system in y = (q, v):
//   arkode-erk:  explicit adaptive Runge–Kutta (default order 4),
//   arkode-dirk: diagonally implicit RK (default order 4, SDIRK),
//   arkode-imex: additive RK (ARK4(3)6L): internal forces implicit, terms with
//                Term::imex_explicit() (gravity, wind) explicit; the Newton
//                matrix holds the Jacobian of the implicit terms only.
// Mass:
//  - constant M (FEM, mass_depends_on_q() false): given to ARKODE directly as
//    the time-independent block mass [I 0 ; 0 M] with the right-hand side
//    (v, f): a matrix-embedded mass solver (ReducedLinearSolver: x_q = b_q,
//    M x_v = b_v, factorized once) and the product M_blk·x (ARKStepSetMassTimes).
//  - M(q) (yarn): ARKODE accepts only a time-dependent mass, so the right-hand
//    side is the explicit form y′ = (v, M(q)⁻¹ f), one sparse factorization of
//    M(q) per distinct state (the IMEX parts at one stage share it). The RK
//    method is then applied to the exact ODE; only its Newton matrix is
//    approximate (below).
// Newton systems (dirk, imex) go to ReducedLinearSolver: with the block mass,
// A = M_blk − γJ = [I, −γI ; −γK, M − γD] is solved as
// (M − γD − γ²K) x_v = b_v + γK b_q, x_q = b_q + γ x_v; in the explicit form,
// A = I − γ[0 I ; M⁻¹K M⁻¹D] has its v rows multiplied by M(q) first, giving
// the same n×n matrix with b_v → M b_v. APPROXIMATION (explicit form): the
// ∂(M(q)⁻¹)/∂q · f term of the Jacobian is neglected and M is taken at the
// Newton iterate of the setup; the Newton iteration tolerates this.
// Fixed step (adaptive = false): ARKStepSetFixedStep(dt); the Newton iteration
// may then take up to IntegratorOptions::newton_max_iters iterations (ARKODE's
// default of 3 is tuned for adaptive steps, where a failure just shrinks h).
// Pinned DoFs: zero right-hand side (and identity mass rows): q, v stay fixed.
// Stepping: ARK_ONE_STEP with the stop time set to t_out; every return is one
// accepted step (on_step, model.accept_step and check_state per step).
#pragma once
#include <memory>
#include <string>

#include "integrators/integrator.h"
#include "integrators/reduced_linear_solver.h"
#include "integrators/sparse_solver.h"
#include "integrators/sundials_handles.h"

namespace wl {

class ArkodeIntegrator : public Integrator {
 public:
  enum class Variant { erk, dirk, imex };
  explicit ArkodeIntegrator(Variant variant) : variant_(variant) {}
  ~ArkodeIntegrator() override;
  std::string name() const override;
  IntegratorCapabilities capabilities() const override {
    return {.controls_error = true,
            .fixed_step_order = 4,
            .explicit_method = variant_ == Variant::erk,
            .state_dependent_mass = true,
            .energy = EnergyBehaviour::follows_tolerance};
  }
  void initialize(Model& model, double t0, const Vec& q0, const Vec& v0, const IntegratorOptions& opt) override;
  StepResult advance_to(double t_out) override;

 private:
  static int rhs_full(double t, N_Vector y, N_Vector ydot, void* self);
  static int rhs_explicit(double t, N_Vector y, N_Vector ydot, void* self);
  static int rhs_implicit(double t, N_Vector y, N_Vector ydot, void* self);
  static int mass_times(N_Vector x, N_Vector mx, double t, void* self);
  static void error_handler(int code, const char* module, const char* function, char* msg, void* self);
  int rhs(double t, N_Vector y, N_Vector ydot, unsigned filter, bool with_velocity);
  bool factor_mass_at(const Vec& q, double t, const SparseMatrix* mass);
  bool mass_current(const Vec& q) const { return mass_factored_ && mass_q_.size() == q.size() && mass_q_ == q; }
  StepResult failure(int flag);
  void update_stats();

  Variant variant_;
  Vec qtmp_, vtmp_, acc_;
  int n_ = 0;
  Evaluation ev_, mev_;
  bool mass_in_arkode_ = false;
  SparseMatrix mass_;                      // constant M (mass in ARKODE)
  std::unique_ptr<SparseSolver> msolver_;  // M(q) solves in the explicit-form right-hand side
  Vec mass_q_;                             // the q of msolver_'s factorization
  bool mass_factored_ = false;
  long own_setups_ = 0, own_solves_ = 0;
  long attempts_setup_ = -1;
  double t_setup_ = 0.0;  // ARKODE's step attempts at the last Newton-matrix setup
  IntegratorStats own_;   // wall/CPU time accumulated here
  std::string last_error_;
  // SUNDIALS objects: context first, memory last (destroyed first).
  sun::Context ctx_;
  sun::Vector y_;
  std::unique_ptr<ReducedLinearSolver> ls_, mls_;
  sun::ArkStepMemory mem_;
};

}  // namespace wl
