// Lumped mass of a triangle [not in the sources; standard] (docs/models.md §6.6): a constant diagonal
// block m_k·I₃ per vertex k. By default m_k = ρ_A·A/3 (areal density × rest area, a third each);
// with [fem] yarn_node_mass each vertex's share follows the yarn level's node masses. No force.
// The FEM mass matrix is constant (FemModel::mass_depends_on_q() is false).
#pragma once
#include <array>
#include <vector>

#include "models/core/term.h"

namespace wl {

class LumpedMassTerm : public ProportionalParameterTerm<9> {
 public:
  std::string name() const override { return "fem-mass"; }
  std::unique_ptr<Term> clone() const override { return std::make_unique<LumpedMassTerm>(*this); }
  bool provides_mass() const override { return true; }
  // The mass each of the triangle's three vertices receives from it [kg] (all ∝ ρ_A).
  void add(const std::array<int, 9>& stencil, const std::array<double, 3>& vertex_mass_kg);
  double energy(int, const double*) const override { return 0.0; }
  void evaluate(int e, const double* q, const double* v, const ElementOutput& out) const override;
  // ½ Σ_k m_k |v_k|² (closed form: run.cpp's metrics ask for it every step).
  double kinetic_energy(int e, const double* q, const double* v) const override;

 private:
  std::vector<std::array<double, 3>> mass_;
};

}  // namespace wl
