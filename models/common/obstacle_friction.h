// Friction of a node against an obstacle (docs/models.md §3.11.3): smoothed
// Coulomb with a lagged normal force, after incremental potential contact, and
// a lagged slip speed. With the normal force λ = −κ b'(d) ≥ 0 of the barrier
// (obstacle_barrier.h), the contact normal n = ∇d and the slip speed
// y₀ = ‖T (ẋ₀ − v_o)‖, all frozen at the last accepted state (accept_step; at
// the first evaluation before any), T = I − n nᵀ and the tangential slip
// velocity u = T (ẋ − v_o) relative to the obstacle:
//   F = −μ λ m(y₀) u,   m(y) = 2/ε − y/ε² for y < ε, 1/y for y ≥ ε,
// so at a steady slip (y = y₀) ‖F‖ = μλ f₁(y) with f₁(y) = 2y/ε − y²/ε² rising
// to the Coulomb bound μλ at y = ε (ε: friction_speed_m_per_s). F is linear in
// ẋ with the coefficient μλ m(y₀) ≥ 0, so F·(ẋ − v_o) = −μλ m(y₀)‖u‖² ≤ 0 for
// every ẋ: dissipative within any step, whatever the integrator linearizes.
//   ∂F/∂ẋ = −μλ m(y₀) T,  ∂F/∂x = 0 (λ, n and y₀ lagged).
//
// One element per (node, obstacle) with μ > 0; local stencil x[3] of the node.
#pragma once
#include <array>
#include <memory>
#include <vector>

#include "models/common/obstacle.h"
#include "models/core/term.h"

namespace wl {

class ObstacleFrictionTerm : public StencilTerm<3> {
 public:
  // The barrier's d̂ [m] and κ [N/m] give λ; ε > 0 [m/s].
  ObstacleFrictionTerm(std::shared_ptr<const std::vector<Obstacle>> obstacles, double dhat, double kappa, double speed);
  void add(const std::array<int, 3>& stencil, int node, int obstacle);

  std::string name() const override { return "obstacle_friction"; }
  std::unique_ptr<Term> clone() const override { return std::make_unique<ObstacleFrictionTerm>(*this); }
  bool conservative() const override { return false; }
  bool has_velocity_jacobian() const override { return true; }
  // Freezes λ, n and y₀ at the first evaluation (no history yet) and after every accepted step.
  void prepare(const EvalContext& ctx) override;
  void accept_step(const EvalContext& ctx, double h) override;
  double energy(int, const double*) const override { return 0.0; }
  void evaluate(int e, const double* q, const double* v, const ElementOutput& out) const override;

  // Sets the frozen normal force λ [N], unit normal n and slip speed y₀ [m/s] of element e (tests).
  void set_lagged(int e, double lambda, const Vec3& n, double slip_speed);
  double lagged_normal_force(int e) const { return lambda_[e]; }
  Vec3 force(int e, const Vec3& xdot) const;
  int node(int e) const { return node_[e]; }

 private:
  void lag(const EvalContext& ctx);
  std::shared_ptr<const std::vector<Obstacle>> obstacles_;
  double dhat_, kappa_, eps_;
  bool lagged_ = false;
  std::vector<int> node_, obstacle_;
  std::vector<double> lambda_, slip_;  // λ [N], y₀ [m/s]
  std::vector<Vec3> normal_;
};

}  // namespace wl
