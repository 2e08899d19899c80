// Cloth–cloth contact (docs/models.md §3.11.7): point–triangle and edge–edge
// barriers (self_contact_pair.h) over the cloth's surface triangles, the pairs
// found at every evaluation by CGAL's box intersection over the primitives'
// boxes widened by d̂/2 on every side, and continuous collision over every step's move.
// Yarn–yarn contact of a knit (§11.10) is the same term over capsules: yarn
// segments of radius R whose edge–edge barrier acts on the gap d − 2R; the
// pairs a penalty already models (ContactCapsules::modelled) get the barrier
// on a smaller contact distance, their hard core, so they too never pass
// through each other.
//
// The pairs couple nodes far apart in the mesh, which the model's fixed
// sparsity pattern (docs/design.md §3.1) does not hold: this term has one
// element per surface node (stencil: its 3 position DoFs). prepare() finds and
// evaluates the pairs; each node receives its exact force and, as ∂f/∂q, the
// 3×3 diagonal blocks of the pairs' Hessians, each projected to positive
// semi-definite and scaled by the pair's number of non-zero blocks, which
// bounds the pair's Hessian from above (the couplings between nodes are left out).
#pragma once
#include <array>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include "models/common/obstacle_contact.h"
#include "models/common/self_contact_pair.h"
#include "models/core/term.h"
#include "models/scene/scene.h"

namespace wl {

// d̂ and κ (docs/models.md §3.11.7): the obstacles' rule (obstacle_contact_rule)
// unless [self_contact] sets them; its friction speed is not used.
ObstacleContactRule self_contact_rule(const Scene& scene, double node_spacing_m, double max_node_mass_kg);

// The cloth surface: triangles over nodes, node k's position DoFs node_x[k] … +2.
struct ContactSurface {
  std::vector<std::array<int, 3>> triangles;
  std::vector<int> node_x;
};

// Yarn segments between surface nodes, as capsules of radius R (docs/models.md
// §11.10): their edge–edge pairs act on the gap d − 2R; the segment pairs in
// `modelled` (indices into `segments`), whose soft contact another term
// models, act on the gap d − core_distance instead (core_distance < 2R).
struct ContactCapsules {
  std::vector<std::array<int, 2>> segments;
  double radius = 0.0;
  std::vector<std::array<int, 2>> modelled;
  double core_distance = 0.0;
};

class SelfContactTerm : public StencilTerm<3> {
 public:
  SelfContactTerm(ContactSurface surface, double dhat, double kappa, const ContactCapsules& capsules = {});

  std::string name() const override { return "self_contact"; }
  std::unique_ptr<Term> clone() const override { return std::make_unique<SelfContactTerm>(*this); }
  // The pairs' energy is not a sum over the per-node elements.
  bool conservative() const override { return false; }
  bool symmetric_jacobian() const override { return true; }
  void prepare(const EvalContext& ctx) override;
  double energy(int, const double*) const override { return 0.0; }
  void evaluate(int e, const double* q, const double* v, const ElementOutput& out) const override;

  bool constrains_steps() const override { return true; }
  // Smallest over the pairs whose boxes swept over the move overlap of the
  // fraction over which the pair's gap stays above η·min(g(from), d̂), η = 0.1,
  // by conservative advancement (docs/models.md §3.11.7).
  double admissible_fraction(const EvalContext& from, const EvalContext& to) const override;

  struct Pair {
    PairKind kind;
    std::array<int, 4> node;  // surface nodes, ordered as in primitive_distance.h
    bool core = false;        // a modelled capsule pair: its gap is taken to the core distance
  };
  // The pairs (not excluded) whose boxes, swept from q0 to q1 and widened by
  // R + margin/2 on every side, overlap.
  std::vector<Pair> candidates(const Vec& q0, const Vec& q1, double margin) const;
  // Their gap at q: the distance less the pair's contact distance (2R, the
  // core distance for a modelled pair; 0 for a surface).
  double distance(const Pair& p, const Vec& q) const;
  // The pairs (not excluded) whose gap at q is negative: capsules that
  // overlap, or modelled pairs whose cores overlap.
  long overlapping_pairs(const Vec& q) const;
  double radius() const { return radius_; }

  static constexpr double kApproachFraction = 0.1;  // η

 private:
  bool excluded(const int* a, int na, const int* b, int nb) const;
  double contact_distance(const Pair& p) const;
  // Adds the force and step stiffness of the kernel's elements (the pairs `active`) to their nodes.
  void gather(const SelfContactPairTerm& kernel, const std::vector<Pair>& active, const Vec& q);
  std::array<Vec3, 4> nodes(const Pair& p, const Vec& q) const;

  ContactSurface surface_;
  std::vector<std::array<int, 2>> edges_;
  std::set<std::array<int, 4>> modelled_;  // modelled edge pairs, each edge's nodes sorted, the pair sorted
  double dhat_, radius_, core_distance_;
  std::array<SelfContactPairTerm, 2> kernels_;  // capsule (or surface) pairs, modelled pairs' cores
  std::vector<Vec3> force_;
  std::vector<Mat3> block_;
};

// Adds the self-contact term when scene.self_contact.enabled; throws
// std::invalid_argument naming the scene's [self_contact] line when d̂ ≥ the
// node spacing ℓ (for capsules: the length scale passed, R) or a pair starts
// with a gap below d̂ (the cloth would feel itself at rest).
void add_self_contact(const Scene& scene, const ObstacleContactRule& rule, double node_spacing_m,
                      ContactSurface surface, const Vec& q0, std::vector<std::unique_ptr<Term>>& terms,
                      const ContactCapsules& capsules = {});

// Throws std::invalid_argument naming the scene's [self_contact] line when it is
// enabled: `what` needs the exact ∂f/∂q, of which self-contact assembles a bound.
void refuse_self_contact(const Scene& scene, const std::string& what);

}  // namespace wl
