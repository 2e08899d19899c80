// Roll of the two yarns about a stitch segment (docs/models.md §11.4; Cirio et
// al. 2016 supplement eqs. (52)–(71), with the signed angle): triangles
// a = (x0, x1, x5) and b = (x0, x3, x1) share the stitch segment x0→x1; x3 is
// the next node of the head yarn after the segment, x5 the next node of the leg
// yarn. With v_a = (x5−x1)×(x0−x1), v_b = (x0−x1)×(x3−x1), n = v/‖v‖ and
// e = (x1−x0)/‖x1−x0‖:
//   ψ = atan2(e·(n_a×n_b), n_a·n_b),
//   ∂ψ/∂x_i = (eᵀx_bi/‖v_b‖) n_b − (eᵀx_ai/‖v_a‖) n_a   (eq. (67), signed),
// x_a0 = x5−x1, x_a1 = x0−x5, x_a5 = x1−x0, x_b0 = x1−x3, x_b1 = x3−x0,
// x_b3 = x0−x1 (the others 0). ψ is undefined where a triangle degenerates
// (x3 or x5 on the segment's line), so the energy is weighted by the
// triangles' opening S = sin²α_a sin²α_b (α the triangle's angle at x1),
// relative to the rest shape's S̄ (§11.4.1):
//   V = k_t L (S/S̄)(1 − cos(ψ − ψ̄)),
// which is ½ k_t L (ψ − ψ̄)² to second order about the rest, periodic in ψ and
// continuously differentiable through a degenerate triangle (V, F → 0 there).
// The force is −∇V; its Jacobian the exact derivative of that expression by
// forward-mode automatic differentiation (Eigen's AutoDiffScalar), which
// replaces eq. (71). ψ̄, S̄: the rest shape's; L the stitch segment's rest
// length. Local stencil (12): x0, x1, x3, x5.
#pragma once
#include <array>
#include <vector>

#include "models/core/term.h"

namespace wl {

class StitchRollTerm : public ProportionalParameterTerm<12> {
 public:
  // kt ≥ 0 [N], rest_length > 0 [m], rest_angle ψ̄ [rad], rest_opening S̄ ∈ (0, 1].
  void add(const std::array<int, 12>& stencil, double kt, double rest_length, double rest_angle, double rest_opening);

  std::string name() const override { return "stitch_roll"; }
  std::unique_ptr<Term> clone() const override { return std::make_unique<StitchRollTerm>(*this); }
  double energy(int e, const double* q) const override;
  void evaluate(int e, const double* q, const double* v, const ElementOutput& out) const override;

  // The signed roll angle ψ of a local state (x0, x1, x3, x5).
  static double angle(const double* q);
  // The opening S = sin²α_a sin²α_b of a local state (0 when a triangle degenerates).
  static double opening(const double* q);

 private:
  std::vector<double> kt_, rest_length_, rest_angle_, rest_opening_;
};

}  // namespace wl
