// SUNDIALS ARKODE (ARKStep) on the first-order system in y = (q, v):
//   arkode-erk:  explicit adaptive Runge–Kutta (default order 4),
//   arkode-dirk: diagonally implicit RK (default order 4) with the analytic
//                sparse Jacobian [0 I ; ∂f/∂q ∂f/∂v] and a sparse direct solver,
//   arkode-imex: additive RK (ARK4(3)6L): internal forces implicit, terms with
//                Term::imex_explicit() (gravity, wind) explicit.
// Mass: a constant M (FEM, mass_depends_on_q() false) is given to ARKODE
// directly as the time-independent block mass [I 0 ; 0 M]
// (ARKStepSetMassLinearSolver), with the right-hand side (v, f). A mass M(q)
// (yarn) is offered for arkode-erk only: the right-hand side is
// (v, M(q)⁻¹ f), refactorizing M with SparseSolver on every evaluation (one
// sparse LU per RK stage, i.e. ~6 per step for the default ERK). For
// arkode-dirk/-imex it is NOT OFFERED: ARKODE accepts only a time-dependent
// mass matrix, and the Jacobian of (v, M(q)⁻¹f) contains M⁻¹∂f/∂q, which is
// dense; advance_to then returns Outcome::not_offered saying so.
// Pinned DoFs: zero right-hand side (and identity mass rows): q, v stay fixed.
// Stepping: ARK_ONE_STEP with the stop time set to t_out; every return is one
// accepted step (on_step, model.accept_step and check_state per step).
// Fixed step (adaptive = false): ARKStepSetFixedStep(dt).
#pragma once
#include <memory>
#include <string>

#include "integrators/integrator.h"
#include "integrators/sparse_solver.h"
#include "integrators/sundials_handles.h"
#include "integrators/sundials_sparse.h"

namespace wl {

class ArkodeIntegrator : public Integrator {
 public:
  enum class Variant { erk, dirk, imex };
  explicit ArkodeIntegrator(Variant variant) : variant_(variant) {}
  ~ArkodeIntegrator() override;
  std::string name() const override;
  void initialize(Model& model, double t0, const Vec& q0, const Vec& v0, const IntegratorOptions& opt) override;
  StepResult advance_to(double t_out) override;
  double t() const override { return t_; }
  const Vec& q() const override { return q_; }
  const Vec& v() const override { return v_; }
  const IntegratorStats& stats() const override { return stats_; }
  // Empty when the model/integrator pair is offered, else the reason.
  const std::string& not_offered_reason() const { return not_offered_; }

 private:
  static int rhs_full(double t, N_Vector y, N_Vector ydot, void* self);
  static int rhs_explicit(double t, N_Vector y, N_Vector ydot, void* self);
  static int rhs_implicit(double t, N_Vector y, N_Vector ydot, void* self);
  static int jacobian(double t, N_Vector y, N_Vector fy, SUNMatrix J, void* self, N_Vector, N_Vector, N_Vector);
  static int mass_fn(double t, SUNMatrix M, void* self, N_Vector, N_Vector, N_Vector);
  static void error_handler(int code, const char* module, const char* function, char* msg, void* self);
  int rhs(double t, N_Vector y, N_Vector ydot, unsigned filter, bool with_velocity);
  StepResult failure(int flag);
  void update_stats();

  Variant variant_;
  Model* model_ = nullptr;
  IntegratorOptions opt_;
  double t_ = 0.0;
  Vec q_, v_, qtmp_, vtmp_, acc_;
  int n_ = 0;
  std::vector<int> fixed_;
  Evaluation ev_;
  bool mass_in_arkode_ = false;
  std::string not_offered_;
  std::unique_ptr<sun::BlockSystem> jblock_, mblock_;
  std::unique_ptr<SparseSolver> msolver_;  // M(q) solves in the ERK right-hand side
  long own_setups_ = 0, own_solves_ = 0, last_nni_ = 0;
  IntegratorStats stats_, own_;
  std::string last_error_;
  // SUNDIALS objects: context first, memory last (destroyed first).
  sun::Context ctx_;
  sun::Vector y_;
  sun::Matrix jac_, mass_;
  sun::LinearSolver ls_, mls_;
  sun::ArkStepMemory mem_;
};

}  // namespace wl
