// Cloth–cloth contact barrier of one primitive pair (docs/models.md §3.11.7):
// a point and a triangle, or two edges, of the cloth surface, with d their
// distance (primitive_distance.h) and the barrier b of the obstacles
// (§3.11.2, contact_barrier) on the gap g = d − D, D the contact distance
// (0 for a surface; 2R for two yarn capsules of radius R, §11.7):
//   E = κ b(g),  F = −κ b'(g) ∇d,  ∇_{xᵢ} d = λᵢ r/d,
// ∂F/∂x by forward-mode AD of F within the closest points' support.
//
// One element per pair; local stencil: the 4 nodes' positions (12 DoFs),
// ordered as in primitive_distance.h. The pairs change with the state: the
// self-contact term (self_contact.h) rebuilds them and gathers their results;
// this term is the unit its elements are checked as.
#pragma once
#include <array>
#include <string>
#include <vector>

#include "models/common/primitive_distance.h"
#include "models/core/term.h"

namespace wl {

class SelfContactPairTerm : public StencilTerm<12> {
 public:
  // d̂ > 0 [m], κ > 0 [N/m], contact distance D ≥ 0 [m].
  SelfContactPairTerm(double dhat, double kappa, double contact_distance = 0.0);
  void clear();
  void add(const std::array<int, 12>& stencil, PairKind kind);

  std::string name() const override { return "self_contact_pair"; }
  std::unique_ptr<Term> clone() const override { return std::make_unique<SelfContactPairTerm>(*this); }
  double energy(int e, const double* q) const override;
  void evaluate(int e, const double* q, const double* v, const ElementOutput& out) const override;

 private:
  double dhat_, kappa_, contact_distance_;
  std::vector<PairKind> kind_;
};

// The 4 nodes of a local stencil of 12 position DoFs.
std::array<Vec3, 4> pair_nodes(const double* q);

}  // namespace wl
