// `ida`: SUNDIALS IDA (variable-order, variable-step BDF) on the residual form
//   G(t, y, y′) = [ q′ − v ; M(q) v′ − f(t, q, v) ] = 0,   y = (q, v),
// with the analytic sparse Jacobian ∂G/∂y + c_j ∂G/∂y′ =
//   [ c_j I      −I              ]
//   [ −∂f/∂q     c_j M − ∂f/∂v   ]
// APPROXIMATION: the term ∂(M(q) v′)/∂q is neglected (it is zero for a
// constant mass; for the yarn model's M(q) the Newton iteration converges with
// this inexact Jacobian). Pinned DoFs get the equations q′ = 0, v′ = 0.
// The Newton systems J x = b are solved by ReducedLinearSolver
// (integrators/reduced_linear_solver.h): x_q = (b_q + x_v)/c_j eliminated, one
// n×n sparse solve (c_j M − ∂f/∂v − ∂f/∂q / c_j) x_v = b_v + ∂f/∂q b_q / c_j;
// the 2n×2n block matrix is never formed. As IDA does for its matrix-based
// solvers, the matrix is re-formed when c_j left [0.6, 1/0.6]·c_j,setup or a
// Newton iteration failed, and a solution computed with a stale c_j is scaled
// by 2/(1 + c_j/c_j,setup). Initial accelerations are consistent:
// v′₀ = M⁻¹ f(t0, q0, v0).
// Stepping: IDA_ONE_STEP with the stop time set to t_out, so every return is
// one accepted step (on_step, model.accept_step, check_state per step) and the
// state at t_out is IDA's own, not interpolated.
// Fixed-step mode (adaptive = false) has no exact equivalent in IDA: the step
// is capped at dt (initial step dt) and IDA's error control still uses
// rtol/atol.
#pragma once
#include <string>

#include "integrators/integrator.h"
#include "integrators/reduced_linear_solver.h"
#include "integrators/sundials_handles.h"

namespace wl {

class IdaIntegrator : public Integrator {
 public:
  IdaIntegrator() = default;
  ~IdaIntegrator() override;
  std::string name() const override { return "ida"; }
  // Variable order (BDF 1–5): no fixed-step mode (see above).
  IntegratorCapabilities capabilities() const override {
    return {.controls_error = true, .state_dependent_mass = true, .energy = EnergyBehaviour::follows_tolerance};
  }
  void initialize(Model& model, double t0, const Vec& q0, const Vec& v0, const IntegratorOptions& opt) override;
  StepResult advance_to(double t_out) override;

 private:
  static int residual(double t, N_Vector y, N_Vector yp, N_Vector r, void* self);
  static void error_handler(int code, const char* module, const char* function, char* msg, void* self);
  StepResult failure(int flag);
  void update_stats();

  int n_ = 0;
  Evaluation ev_;
  SparseMatrix mass_;      // constant mass (when !mass_depends_on_q)
  double cj_setup_ = 1.0;  // c_j of the last Newton-matrix setup
  long ncf_setup_ = 0;     // IDA's Newton convergence failures at that setup
  IntegratorStats own_;    // wall/CPU time accumulated here
  std::string last_error_;
  // SUNDIALS objects: context first, memory last (destroyed first).
  sun::Context ctx_;
  sun::Vector y_, yp_;
  std::unique_ptr<ReducedLinearSolver> ls_;
  sun::IdaMemory mem_;
};

}  // namespace wl
