// In-house second-order implicit integrator (docs/models.md §7.7): the
// two-stage, L-stable, stiffly accurate SDIRK of Alexander (1977),
// γ = 1 − 1/√2, on the second-order system q′ = v, M(q) v′ = f(t, q, v):
//   stage 1:  M(Q₁)(V₁ − v₀) = γh f(t₀ + γh, Q₁, V₁),                Q₁ = q₀ + γh V₁
//   stage 2:  M(Q₂)(V₂ − v₀ − (1−γ)h A₁) = γh f(t₀ + h, Q₂, V₂),     Q₂ = q₀ + (1−γ)h V₁ + γh V₂
//   A₁ = (V₁ − v₀)/(γh);  q₁ = Q₂, v₁ = V₂.
// Each stage is a backward-Euler-shaped solve of step γh: both stages share one
// factorization of M − γhD − γ²h²K (modified Newton), kept across steps (for a
// constant mass) while the iterations converge fast and the step changes by at
// most 20 %, refreshed at the current iterate when they stall. The mass is taken at the stage state,
// which keeps the method second order when M depends on q.
// Error estimate (adaptive mode): the first-order embedded solution
// b̂ = (1, 0) differs by ê = γh (V₂ − V₁, A₂ − A₁), filtered through the
// iteration matrix as for stiff problems, (I − γhJ)⁻¹ê (Hairer & Wanner IV.8),
// measured on the positions q alone in the weighted RMS norm of rtol and atol
// (docs/models.md §7.7: velocity errors of the unresolved stiff stretch
// vibrations are damped, not accumulated; the lab reports positions).
// Friction anchors and the frozen F_n, F_u are handled as by backward Euler:
// every evaluation freezes them at its own state, the anchors move once per
// accepted step (Model::accept_step).
#pragma once
#include <memory>

#include "integrators/integrator.h"
#include "integrators/sparse_solver.h"

namespace wl {

class Sdirk2 : public Integrator {
 public:
  std::string name() const override { return "sdirk2"; }
  IntegratorCapabilities capabilities() const override {
    return {.controls_error = true,
            .fixed_step_order = 2,
            .state_dependent_mass = true,
            .sensitivities = true,
            .replays_steps = true,
            .energy = EnergyBehaviour::dissipative,
            .admissible_steps = true};
  }
  void initialize(Model& model, double t0, const Vec& q0, const Vec& v0, const IntegratorOptions& opt) override;
  StepResult advance_to(double t_out) override;

  static constexpr double kGamma = 0.29289321881345248;  // 1 − 1/√2

 private:
  struct Attempt {
    StepResult result;
    double error = 0.0;  // weighted RMS error estimate (adaptive mode); ≤ 1 accepts
    int iters = 0;
  };
  // One step of size h from (t_, q_, v_) into (q_new_, v_new_).
  Attempt attempt(double h);
  Attempt failed(Attempt a);  // a failed stage: no matrix reuse next
  // Solves the stage M(Q)(V − w) = γh f(t, Q, V), Q = q_base + γh V, for V
  // (initial guess in V) by modified Newton on the factorization in hand.
  StepResult solve_stage(double t, double h, const Vec& q_base, const Vec& w, Vec& V, int& iters);
  // Evaluates K, D, M at (t, q, v) and factorizes M − γhD − γ²h²K.
  StepResult refresh_matrix(double t, double h, const Vec& q, const Vec& v);
  // ‖e‖ = sqrt(mean_i (e_i / (atol + rtol·max(|q₀ᵢ|, |q₁ᵢ|)))²) over the free DoFs.
  double weighted_rms(const Vec& eq) const;
  StepResult advance(double t_out);
  StepResult adaptive_step(double t_out);
  // Takes the attempt's end state (and carries the sensitivities to it).
  StepResult accept(double h);
  // Forward sensitivities through both stages (sdirk2_sensitivity.cpp, docs/models.md §9.2).
  StepResult propagate_sensitivities(double h);

  Evaluation jac_, res_;  // Jacobians at the matrix point; force (and mass) at Newton iterates
  SparseMatrix a_;        // M − γhD − γ²h²K
  std::unique_ptr<SparseSolver> solver_;
  double matrix_h_ = 0.0;      // the step the factorization belongs to (0: none)
  bool reuse_matrix_ = false;  // the last stages converged fast on it: the next step may keep it
  double h_next_ = 0.0;        // adaptive mode: the proposed next step
  Vec q_new_, v_new_;
  Vec a_last_;  // v′ at the end of the last accepted step (the next stage's starting guess)
  // The stages of the last attempt (for sensitivities and the estimate).
  Vec V1_, V2_, Q1_, w2_, qb2_;
};

}  // namespace wl
