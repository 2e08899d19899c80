// The mass an interface crossing of a mixed cloth lacks or carries in excess
// because the continuum's triangles lump a cell unevenly (docs/models.md §12.4):
// a constant diagonal block δ·I₃ at the crossing, δ = Σ_c M_c/4 − (what the
// continuum cells c around it give it), so that at an interface crossing every
// cell gives a quarter of its mass, as the yarn level's cells do. δ is ±1/12 of
// a cell's mass at a rectangle's corners and 0 on its straight sides; it is
// proportional to ρ_A. Gravity on δ is a NodalGravityTerm beside it. No force.
#pragma once
#include <array>
#include <vector>

#include "models/core/term.h"

namespace wl {

class InterfaceMassTerm : public ProportionalParameterTerm<3> {
 public:
  std::string name() const override { return "mixed-interface-mass"; }
  std::unique_ptr<Term> clone() const override { return std::make_unique<InterfaceMassTerm>(*this); }
  bool provides_mass() const override { return true; }
  void add(const std::array<int, 3>& stencil, double mass_kg);
  double energy(int, const double*) const override { return 0.0; }
  void evaluate(int e, const double* q, const double* v, const ElementOutput& out) const override;

 private:
  std::vector<double> mass_;
};

}  // namespace wl
