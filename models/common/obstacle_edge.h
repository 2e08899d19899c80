// Segment–edge contact against an obstacle's sharp edges (docs/models.md
// §3.11.10): the node barrier (obstacle_barrier.h) keeps nodes out, this term
// keeps the cloth's segments (yarn segments, FEM triangle edges) off the
// obstacle's sharp edges (a box's 12 edges, a cylinder's or disk's two rims),
// which a segment between two admissible nodes could otherwise cut.
// With p(s) = (1 − s) x_a + s x_b the segment and D_k the distance from a point
// to edge k (a straight segment, or a circle),
//   d_k = min_{s ∈ [0,1]} D_k(p(s)),   E = Σ_k κ b(d_k)   (b of §3.11.2),
//   F = −κ b'(d_k) ∇d_k,  ∇_{x_a} d_k = (1 − s*) n, ∇_{x_b} d_k = s* n,
// n the unit vector from the edge's closest point to p(s*) (envelope theorem).
// ∂F/∂x by forward-mode AD of F with s* carried as s* − f_s/f_ss (f = D_k∘p:
// the implicit function's derivative at an interior minimum; an end of the
// segment stays fixed), f_ss floored where the segment runs nearly along the
// edge (there the exact ∂s*/∂x is unbounded). Continuous collision: conservative advancement on d_k
// over each step's straight move (§3.11.10).
//
// One element per (cloth segment, obstacle with sharp edges); local stencil:
// the segment's two nodes (6 DoFs), coupled already by the cloth's own terms.
#pragma once
#include <array>
#include <memory>
#include <vector>

#include "models/common/obstacle.h"
#include "models/core/term.h"

namespace wl {

// A sharp edge in world coordinates at one time: a segment a–b, or the circle
// of radius r about centre a in the plane normal to the unit axis k.
struct SharpEdge {
  bool circle = false;
  Vec3 a, b, k;
  double r = 0.0;
};
// The sharp edges of obstacle o at time t (none for a plane, a sphere or a mesh).
std::vector<SharpEdge> sharp_edges(const Obstacle& o, double t);

// The closest point of segment x_a–x_b to edge e: its parameter s* ∈ [0, 1]
// along the segment and the distance d = D(p(s*)).
struct SegmentEdgeClosest {
  double s = 0.0, distance = 0.0;
};
SegmentEdgeClosest closest_to_edge(const SharpEdge& e, const Vec3& xa, const Vec3& xb);

class ObstacleEdgeTerm : public StencilTerm<6> {
 public:
  // The barrier's d̂ [m] and κ [N/m] (obstacle_contact_rule).
  ObstacleEdgeTerm(std::shared_ptr<const std::vector<Obstacle>> obstacles, double dhat, double kappa);
  // Segment with position DoFs `stencil` (node a's 3, then node b's), against obstacle k.
  void add(const std::array<int, 6>& stencil, int obstacle);

  std::string name() const override { return "obstacle_edge_contact"; }
  std::unique_ptr<Term> clone() const override { return std::make_unique<ObstacleEdgeTerm>(*this); }
  void prepare(const EvalContext& ctx) override;
  double energy(int e, const double* q) const override;
  void evaluate(int e, const double* q, const double* v, const ElementOutput& out) const override;

  bool constrains_steps() const override { return true; }
  // Smallest over the elements and edges of the fraction of the straight move
  // over which the segment stays farther than η·min(d(from), d̂) from the edge, η = 0.1.
  double admissible_fraction(const EvalContext& from, const EvalContext& to) const override;

  // The force on element e's segment (node a's 3, node b's 3) at time t [N].
  LVec force(int e, double t, const double* q) const;

  static constexpr double kApproachFraction = 0.1;  // η
  // The floor of f_ss in ∂F/∂x, in units of ‖x_b − x_a‖²/d̂ (§3.11.10).
  static constexpr double kCurvatureFloor = 0.1;

 private:
  // Adds the force of the edges (and ∂F/∂x when asked) at local q.
  void add_edges(const std::vector<SharpEdge>& edges, const double* q, const ElementOutput& out) const;
  // The edges of element e's obstacle that may be within `reach` of the segment
  // x_a–x_b (the obstacle's distance of its ends, less half its length, is below it).
  bool near(int e, const Vec3& xa, const Vec3& xb, double t, double reach) const;
  std::shared_ptr<const std::vector<Obstacle>> obstacles_;
  double dhat_, kappa_, t_ = 0.0;
  std::vector<int> obstacle_;
  std::vector<std::vector<SharpEdge>> edges_;  // per obstacle at t_
};

}  // namespace wl
