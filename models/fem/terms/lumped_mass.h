// Lumped mass of a triangle [not in the sources; standard] (docs/models.md §6.6): the constant diagonal
// block m/3·I₃ per vertex, m = ρ_A·A (areal density × rest area). No force.
// The FEM mass matrix is constant (FemModel::mass_depends_on_q() is false).
#pragma once
#include <vector>

#include "models/core/term.h"

namespace wl {

class LumpedMassTerm : public ProportionalParameterTerm<9> {
 public:
  std::string name() const override { return "fem-mass"; }
  std::unique_ptr<Term> clone() const override { return std::make_unique<LumpedMassTerm>(*this); }
  bool provides_mass() const override { return true; }
  // triangle_mass_kg = ρ_A·A; each vertex receives a third.
  void add(const std::array<int, 9>& stencil, double triangle_mass_kg);
  double energy(int, const double*) const override { return 0.0; }
  void evaluate(int e, const double* q, const double* v, const ElementOutput& out) const override;

 private:
  std::vector<double> mass_;
};

}  // namespace wl
