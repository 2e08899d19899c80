// Inertia of a yarn segment with sliding (Eulerian) end coordinates
// (docs/models.md §3.1; Gong et al. 2022 §B.2–§B.4 with the corrections of §4.1, §4.3, §4.4).
// Local stencil (x0[3], x1[3], u0, u1), u1 > u0. With d = x1 − x0, D = u1 − u0:
//   mass block   M = ρ/6 [D A0 + B(d, ‖d‖²/D)]            (docs/models.md §3.1.1)
//   force        f = ∂T/∂q − Ṁq̇, T = ½ q̇ᵀ M q̇           (docs/models.md §3.1.2, §4.4)
// The force is velocity dependent and has no potential (conservative() = false).
#pragma once
#include <array>
#include <string>
#include <vector>

#include "models/core/term.h"

namespace wl {

class SegmentInertiaTerm : public ProportionalParameterTerm<8>, public PositionDependentMass {
 public:
  // One segment; rho is the linear density in kg/m (> 0).
  void add(const std::array<int, 8>& stencil, double rho);

  std::string name() const override { return "inertia"; }
  std::unique_ptr<Term> clone() const override { return std::make_unique<SegmentInertiaTerm>(*this); }
  bool conservative() const override { return false; }
  bool has_velocity_jacobian() const override { return true; }
  bool provides_mass() const override { return true; }

  double energy(int, const double*) const override { return 0.0; }
  void evaluate(int e, const double* q, const double* v, const ElementOutput& out) const override;

  // Kinetic energy T = ½ρ∫‖ẋ(u)‖²du of one segment in closed form
  // (docs/models.md §3.1.2): local q and v in stencil order, rho in kg/m.
  static double kinetic_energy(const double* q, const double* v, double rho);
  double kinetic_energy(int e, const double* q, const double* v) const override {
    return kinetic_energy(q, v, rho_[e]);
  }
  // The 8×8 mass block M(q) of one segment (column-major into m).
  static void mass_block(const double* q, double rho, double* m);
  // δM = ρ/6 [δD A0 + B(δd, δσ)], σ = ‖d‖²/D, along dq (docs/models.md §9.2).
  void mass_directional_derivative(int e, const double* q, const double* dq, double* dm) const override;

 private:
  std::vector<double> rho_;
};

}  // namespace wl
