// `symplectic`: symplectic Euler, in-house, fixed step (the cheap explicit
// baseline):  v₁ = v₀ + h M(q₀)⁻¹ f(t₀, q₀, v₀),  q₁ = q₀ + h v₁.
// M is factorized once when constant and refactorized every step when it
// depends on q. Pinned DoFs keep q and v = 0. IntegratorOptions::adaptive is
// ignored: the method always steps with dt (the last step shortened to hit
// t_out).
#pragma once
#include <memory>

#include "integrators/integrator.h"
#include "integrators/sparse_solver.h"

namespace wl {

class SymplecticEuler : public Integrator {
 public:
  std::string name() const override { return "symplectic"; }
  IntegratorCapabilities capabilities() const override {
    return {.fixed_step_order = 1,
            .explicit_method = true,
            .state_dependent_mass = true,
            .replays_steps = true,
            .energy = EnergyBehaviour::bounded};
  }
  void initialize(Model& model, double t0, const Vec& q0, const Vec& v0, const IntegratorOptions& opt) override;
  StepResult advance_to(double t_out) override;
  // One step of size h from the current state, with the shared bookkeeping.
  StepResult step(double h);

 private:
  StepResult move(double h);  // v₁, q₁ from (q₀, v₀)
  Vec a_;
  Evaluation ev_;
  std::unique_ptr<SparseSolver> solver_;
  bool factorized_ = false;
};

}  // namespace wl
