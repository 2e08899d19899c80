// In-house backward Euler (docs/models.md §7.2), two variants:
//   be-linear: one linearized solve per step,
//     (M − h∂f/∂v − h²∂f/∂q) Δv = h (f + h ∂f/∂q v₀),  v₁ = v₀ + Δv,  q₁ = q₀ + h v₁;
//   be-newton: Newton on  G(v₁) = M(q₀)(v₁ − v₀) − h f(q₀ + h v₁, v₁) = 0
//     with a backtracking line search on ‖G‖.
// M is taken at the start of the step in both (Gong et al. 2022 eq. (2)). The sparse
// factorization reuses one symbolic analysis for the whole run.
#pragma once
#include <memory>

#include "integrators/integrator.h"
#include "integrators/sparse_solver.h"

namespace wl {

class BackwardEuler : public Integrator {
 public:
  enum class Variant { linear, newton };
  explicit BackwardEuler(Variant variant) : variant_(variant) {}
  std::string name() const override { return variant_ == Variant::linear ? "be-linear" : "be-newton"; }
  IntegratorCapabilities capabilities() const override {
    return {.fixed_step_order = 1,
            .state_dependent_mass = true,
            .sensitivities = true,
            .replays_steps = true,
            .energy = EnergyBehaviour::dissipative,
            .admissible_steps = true};
  }
  void initialize(Model& model, double t0, const Vec& q0, const Vec& v0, const IntegratorOptions& opt) override;
  StepResult advance_to(double t_out) override;

  // One step of size h from the current state (exposed for benchmarks).
  StepResult step(double h);
  // The solver of the last step: solve() solves with that step's matrix
  // (to kGmresTolerance under gmres); the step matrix it was given.
  const SparseSolver& solver() const { return *solver_; }
  const SparseMatrix& step_matrix() const { return a_; }

 private:
  StepResult step_linear(double h, int* iters);
  StepResult step_newton(double h, int* iters);
  // a_ = M − hD − h²K from ev_ (M: `mass` when given, else ev_.mass).
  void form_step_matrix(double h, const SparseMatrix* mass = nullptr);
  // Sensitivity updates (backward_euler_sensitivity.cpp, docs/models.md §9.2), called
  // after the step's solve and before the state moves on.
  // false when a sensitivity solve fails (the step then ends as diverged).
  bool propagate_linear_sensitivities(double h, const Vec& dv);
  bool propagate_newton_sensitivities(double h, const Vec& q0, const Vec& v0, const SparseMatrix& m0);
  // x = a_⁻¹ b by iterative refinement on the factorization in hand (of a_ or
  // of a nearby matrix); refactorizes a_ when that does not converge.
  bool solve_step_matrix(const Vec& b, Vec& x);

  Variant variant_;
  Evaluation ev_;
  SparseMatrix a_;
  std::unique_ptr<SparseSolver> solver_;
  Vec rhs_, dv_;            // be-linear's right-hand side and solution, kept between steps
  double dv_step_ = 0.0;    // the step h whose solution dv_ holds (0: none to start from)
  bool have_mass_ = false;  // ev_.mass holds M (be-linear: kept when M does not depend on q)
};

}  // namespace wl
