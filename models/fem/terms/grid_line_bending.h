// Bending of the grid mesh's lines (docs/models.md §6.5.2): the optional
// alternative to the hinges of hinge_bending.h, [fem] grid_line_bending = true.
// Each run of three vertices along a line of constant v (a warp line) or
// constant u (a weft line) bends as a yarn does (docs/models.md §3.3):
//   V = k_line·θ²/(2l),  θ the turning angle at the middle vertex, l the rest
//   length of either segment (the line spacing along the line),
//   k_line = k_warp·w (lines along u) or k_weft·w (lines along v),
// w the width of cloth the line stands for: the vertex spacing across it, half
// of it on the border lines. The element kernel is the yarn model's
// (BendingTerm::local_evaluate, with the material coordinates fixed at ±l).
// A cylinder of curvature κ about v bends every warp line by κl at each interior
// vertex: the energy per area is ½k_warp κ² as with the hinges; a cylinder along
// a diagonal bends each line by its normal curvature κ/2 only, and twist bends
// no line, as at yarn level (docs/calibration.md §2.1).
// Stencil (9): x0 (middle), x1 (next), x2 (previous). V is linear in k_line:
// each element is tagged with its key (fem.warp_bending_N_m or fem.weft_bending_N_m).
#pragma once
#include <vector>

#include "models/core/term.h"

namespace wl {

class GridLineBendingTerm : public ProportionalParameterTerm<9> {
 public:
  // k_line in N·m² (stiffness per width times the width); l the segment rest length.
  void add(const std::array<int, 9>& stencil, double k_line, double l);
  std::string name() const override { return "fem-line-bending"; }
  std::unique_ptr<Term> clone() const override { return std::make_unique<GridLineBendingTerm>(*this); }
  double energy(int e, const double* q) const override;
  void evaluate(int e, const double* q, const double* v, const ElementOutput& out) const override;

 private:
  std::vector<double> k_, l_;
};

}  // namespace wl
