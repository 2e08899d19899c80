// Gravity on a lumped vertex mass [not in the sources; the nodal form of
// docs/models.md §3.8, §6.6]: V = −m g·x, F = m g, ∂F/∂x = 0. g is the scene's gravity
// acceleration vector (default (0, 0, −9.81) m/s²); m the vertex's lumped mass
// (sum of ρ_A·A/3 over its triangles), so gravity and inertia use one mass.
#pragma once
#include <vector>

#include "models/core/term.h"

namespace wl {

class NodalGravityTerm : public ProportionalParameterTerm<3> {
 public:
  explicit NodalGravityTerm(const Vec3& g_m_per_s2) : g_(g_m_per_s2) {}
  std::string name() const override { return "fem-gravity"; }
  std::unique_ptr<Term> clone() const override { return std::make_unique<NodalGravityTerm>(*this); }
  bool imex_explicit() const override { return true; }  // non-stiff external load
  void add(const std::array<int, 3>& stencil, double mass_kg);
  double energy(int e, const double* q) const override;
  void evaluate(int e, const double* q, const double* v, const ElementOutput& out) const override;

 private:
  Vec3 g_;
  std::vector<double> mass_;
};

}  // namespace wl
