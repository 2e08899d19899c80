// Yarn-internal stretch damping, a Kelvin–Voigt viscosity η of the yarn
// material acting along each yarn segment (docs/models.md §3.12). Model
// agnostic: local stencil (x_a, x_b) of two points on one yarn, or on one warp
// or weft edge of the continuum mesh.
//   d = (x_b − x_a)/‖x_b − x_a‖,   ṡ = d·(ẋ_b − ẋ_a),   F_b = −c ṡ d = −F_a,
//   c = η πR² / L  (the yarn's cross-section over the rest yarn spacing).
// Non-conservative (energy 0); it removes energy at the rate c ṡ² per segment.
// ∂F_b/∂ẋ_b = −c d dᵀ;  ∂F_b/∂x_b = −(c/ℓ)[ṡ (I − d dᵀ) + d Δẋᵀ(I − d dᵀ)],
// ℓ = ‖x_b − x_a‖, Δẋ = ẋ_b − ẋ_a. A degenerate segment (ℓ = 0) gets no force.
#pragma once
#include <array>
#include <vector>

#include "models/core/term.h"

namespace wl {

class YarnDamperTerm : public StencilTerm<6> {
 public:
  // One segment with its dashpot coefficient c (N·s/m, finite, ≥ 0).
  void add(const std::array<int, 6>& stencil, double c);

  std::string name() const override { return "yarn_damping"; }
  std::unique_ptr<Term> clone() const override { return std::make_unique<YarnDamperTerm>(*this); }
  bool conservative() const override { return false; }
  bool has_velocity_jacobian() const override { return true; }
  double energy(int, const double*) const override { return 0.0; }
  void evaluate(int e, const double* q, const double* v, const ElementOutput& out) const override;

 private:
  std::vector<double> c_;
};

// c = η πR² / L for a yarn viscosity η [Pa·s], radius R and spacing L [m].
double yarn_damper_coefficient(double viscosity_Pa_s, double radius_m, double spacing_m);

}  // namespace wl
