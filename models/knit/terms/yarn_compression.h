// Contact compression between two yarn segments (docs/models.md §11.6): a
// penalty on the distance between the two yarn centrelines against the contact
// distance D = 2R. With segments x0→x1 and y0→y1, their closest points
// p = x0 + s(x1−x0), p' = y0 + t(y1−y0) (s, t ∈ [0, 1], the clamped minimiser
// of ‖p − p'‖) and d = ‖p − p'‖:
//   V = ½ κ (D − d)² for d < D, else 0,
//   F = κ (D − d) ∇d,  ∇d = ((1−s) n, s n, −(1−t) n, −t n),  n = (p − p')/d,
// (∇d by the envelope theorem: s, t minimise d). The Jacobian
// −κ ∇d ∇dᵀ + κ (D − d) ∇²d takes ∇²d as the exact derivative of ∇d, s and t
// included, by forward-mode automatic differentiation (Eigen's AutoDiffScalar).
// Local stencil (12): x0, x1, y0, y1. Precondition: d > 0 (the centrelines do
// not meet); at d = 0 the direction n is undefined and the element exerts no force.
#pragma once
#include <array>
#include <vector>

#include "models/core/term.h"

namespace wl {

class YarnCompressionTerm : public ProportionalParameterTerm<12> {
 public:
  // kappa ≥ 0 [N/m], contact distance D > 0 [m].
  void add(const std::array<int, 12>& stencil, double kappa, double contact_distance);

  std::string name() const override { return "yarn_compression"; }
  std::unique_ptr<Term> clone() const override { return std::make_unique<YarnCompressionTerm>(*this); }
  double energy(int e, const double* q) const override;
  void evaluate(int e, const double* q, const double* v, const ElementOutput& out) const override;

  // The distance d between the two segments of a local state (x0, x1, y0, y1).
  static double distance(const double* q);

 private:
  std::vector<double> kappa_, contact_distance_;
};

}  // namespace wl
