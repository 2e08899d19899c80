// Node–obstacle contact barrier (docs/models.md §3.11.2), after incremental
// potential contact (Li et al. 2020): with d the node's signed distance to the
// obstacle and d̂ the activation distance,
//   E = κ b(d),  b(d) = −(d − d̂)² ln(d/d̂) for 0 < d < d̂, 0 for d ≥ d̂,
//   F = −κ b'(d) ∇d,  ∂F/∂x = −κ (b''(d) ∇d ∇dᵀ + b'(d) ∇²d).
// b is C² at d̂ and grows without bound as d → 0. Below d_f = 10⁻⁹ d̂ it is
// continued by its second-order Taylor polynomial at d_f, so that a Newton
// iterate that overshoots sees a finite, strongly repelling force; no accepted
// state gets there: the step control keeps every node outside (admissible_fraction,
// §3.11.4). Obstacles move with the time of the evaluation (prepare).
//
// One element per (node, obstacle); local stencil x[3] of the node.
#pragma once
#include <array>
#include <memory>
#include <vector>

#include "models/common/obstacle.h"
#include "models/core/term.h"

namespace wl {

// b(d) of §3.11.2 and its first two derivatives (the Taylor continuation below d_f).
struct BarrierValue {
  double b = 0.0, db = 0.0, d2b = 0.0;
};
BarrierValue contact_barrier(double d, double dhat);

class ObstacleBarrierTerm : public StencilTerm<3> {
 public:
  // d̂ > 0 [m], κ > 0 [N/m]; the obstacles are shared with the friction term.
  ObstacleBarrierTerm(std::shared_ptr<const std::vector<Obstacle>> obstacles, double dhat, double kappa);
  // Node `node` (an id for output) with position DoFs `stencil`, against obstacle k.
  void add(const std::array<int, 3>& stencil, int node, int obstacle);

  std::string name() const override { return "obstacle_contact"; }
  std::unique_ptr<Term> clone() const override { return std::make_unique<ObstacleBarrierTerm>(*this); }
  void prepare(const EvalContext& ctx) override { t_ = ctx.t; }
  double energy(int e, const double* q) const override;
  void evaluate(int e, const double* q, const double* v, const ElementOutput& out) const override;

  // The step matrix takes κ(b''∇d∇dᵀ + b'∇²d) projected to its positive
  // semi-definite part (docs/models.md §3.11.2; [obstacle_contact] step_hessian).
  void set_projected_step_stiffness(bool on) { projected_ = on; }
  bool projects_step_stiffness() const override { return projected_; }

  bool constrains_steps() const override { return true; }
  // Smallest over the elements of the fraction of the straight move from
  // `from` to `to` over which every node stays farther than
  // η·min(d(from), d̂) from its obstacle, η = 0.1 (§3.11.4).
  double admissible_fraction(const EvalContext& from, const EvalContext& to) const override;

  // The contact force on element e's node at time t [N].
  Vec3 force(int e, double t, const Vec3& x) const;
  int node(int e) const { return node_[e]; }
  double activation_distance() const { return dhat_; }
  double stiffness() const { return kappa_; }
  const Obstacle& obstacle(int e) const { return (*obstacles_)[obstacle_[e]]; }

  static constexpr double kApproachFraction = 0.1;  // η

 private:
  std::shared_ptr<const std::vector<Obstacle>> obstacles_;
  double dhat_, kappa_, t_ = 0.0;
  bool projected_ = false;
  std::vector<int> node_, obstacle_;
};

}  // namespace wl
