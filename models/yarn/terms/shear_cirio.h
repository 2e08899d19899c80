// Cirio's shear between a warp and a weft segment at a crossing (one quadrant):
//   V = ½ k_x L (φ − π/2)²,  φ = arccos(d1·d3)
// docs/models.md §3.4.2, Cirio et al. 2016 eqs. (41)–(51). Local stencil (x0, x1, x3): x0 the
// crossing, x1 a warp neighbour, x3 a weft neighbour; the model adds all four
// quadrants of a crossing. No force on the Eulerian coordinates.
#pragma once
#include <array>
#include <vector>

#include "models/core/term.h"

namespace wl {

class CirioShearTerm : public ProportionalParameterTerm<9> {
 public:
  // kx_L = k_x L (N·m per rad²), the stiffness of this quadrant.
  void add(const std::array<int, 9>& stencil, double kx_L);

  std::string name() const override { return "shear"; }
  std::unique_ptr<Term> clone() const override { return std::make_unique<CirioShearTerm>(*this); }
  double energy(int e, const double* q) const override;
  void evaluate(int e, const double* q, const double* v, const ElementOutput& out) const override;

 private:
  std::vector<double> kx_L_;
};

}  // namespace wl
