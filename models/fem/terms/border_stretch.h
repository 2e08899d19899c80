// Border strip of the continuum on the crossing mesh (docs/calibration.md §5):
// the yarn level's outermost yarns carry their full cross-section, but the
// mesh through the crossings ends at their centre lines, so the continuum
// lacks half a spacing of cloth along its border. This term adds it back as
// bars on the mesh's border edges, each of the stiffness of a strip of width w:
//   V = ½ K ℓ₀ (ℓ/ℓ₀ − 1)²,  K = k·w  [N],
// ℓ₀ the rest (UV) length, ℓ = ‖x₁ − x₀‖, k the warp stretch stiffness [N/m]
// for edges along u and the weft one for edges along v (w = L/2).
//   f₁ = −K(ℓ/ℓ₀ − 1) n̂ = −f₀,  ∂f₁/∂x₁ = −K/ℓ₀ n̂n̂ᵀ − K(1/ℓ₀ − 1/ℓ)(I − n̂n̂ᵀ).
#pragma once
#include <vector>

#include "models/core/term.h"

namespace wl {

class BorderStretchTerm : public StencilTerm<6> {
 public:
  BorderStretchTerm(double k_warp_N_per_m, double k_weft_N_per_m, double width_m)
      : k_{k_warp_N_per_m, k_weft_N_per_m}, width_(width_m) {}
  std::string name() const override { return "fem-border-stretch"; }
  std::unique_ptr<Term> clone() const override { return std::make_unique<BorderStretchTerm>(*this); }
  // stencil: x of the edge's two vertices; along_u: the edge runs along u (warp stiffness).
  void add(const std::array<int, 6>& stencil, double rest_length_m, bool along_u);
  double energy(int e, const double* q) const override;
  void evaluate(int e, const double* q, const double* v, const ElementOutput& out) const override;
  std::vector<std::string> parameter_keys() const override;
  void parameter_derivative(int e, int k, const double* q, const double* v, double* dfdp) const override;

 private:
  double k_[2], width_;
  std::vector<double> rest_;
  std::vector<int> family_;  // 0 along u (warp), 1 along v (weft)
};

}  // namespace wl
