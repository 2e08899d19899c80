// Roll of the two yarns about a stitch segment (docs/models.md §11.4; Cirio et
// al. 2016 supplement eqs. (52)–(71), with the signed angle): triangles
// a = (x0, x1, x5) and b = (x0, x3, x1) share the stitch segment x0→x1; x3 is
// the next node of the head yarn after the segment, x5 the next node of the leg
// yarn. With v_a = (x5−x1)×(x0−x1), v_b = (x0−x1)×(x3−x1), n = v/‖v‖ and
// e = (x1−x0)/‖x1−x0‖:
//   ψ = atan2(e·(n_a×n_b), n_a·n_b),   V = ½ k_t L (ψ − ψ̄)² (ψ − ψ̄ taken in (−π, π]),
//   ∂ψ/∂x_i = (eᵀx_bi/‖v_b‖) n_b − (eᵀx_ai/‖v_a‖) n_a   (eq. (67), signed),
// x_a0 = x5−x1, x_a1 = x0−x5, x_a5 = x1−x0, x_b0 = x1−x3, x_b1 = x3−x0,
// x_b3 = x0−x1 (the others 0). The force is −k_t L (ψ−ψ̄)∇ψ; its Jacobian is
// the exact derivative of that expression by forward-mode automatic
// differentiation (Eigen's AutoDiffScalar), which replaces eq. (71).
// ψ̄ is the angle of the rest shape; L the stitch segment's rest length.
// Local stencil (12): x0, x1, x3, x5. Precondition: non-degenerate triangles.
#pragma once
#include <array>
#include <vector>

#include "models/core/term.h"

namespace wl {

class StitchRollTerm : public ProportionalParameterTerm<12> {
 public:
  // kt ≥ 0 [N], rest_length > 0 [m], rest_angle ψ̄ [rad].
  void add(const std::array<int, 12>& stencil, double kt, double rest_length, double rest_angle);

  std::string name() const override { return "stitch_roll"; }
  std::unique_ptr<Term> clone() const override { return std::make_unique<StitchRollTerm>(*this); }
  double energy(int e, const double* q) const override;
  void evaluate(int e, const double* q, const double* v, const ElementOutput& out) const override;

  // The signed roll angle ψ of a local state (x0, x1, x3, x5).
  static double angle(const double* q);

 private:
  std::vector<double> kt_, rest_length_, rest_angle_;
};

}  // namespace wl
