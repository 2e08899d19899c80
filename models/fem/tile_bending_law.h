// The curvature part of the tile law (docs/models.md §6.9): the monomials of
// W(θ) (tile_law_file.h) that hold a curvature, θ = (ε_u, ε_v, γ, κ_u, κ_v, κ_uv),
//   W_b(θ) = W(θ) − W(ε_u, ε_v, γ, 0, 0, 0),
// so that W = W_m + W_b with the membrane part W_m of TileMembraneLaw. It holds the
// sampled bending response and its couplings with stretch and shear (a tile bent
// under tension is softer). Beyond the sampled box, with p the nearest point of the
// box and d = θ − p,
//   W_b = P_b(p) + ∇P_b(p)·d + ½ Σ_{k curvature} h_k d_k²,   h_k = ∂²P_b/∂θ_k²(0),
// which is the curvature part of the whole law's continuation (the membrane part
// carries ½ h_k d_k² of the membrane strains); C¹ across the box's faces.
#pragma once
#include <array>
#include <string>
#include <vector>

#include "models/fem/tile_law_file.h"

namespace wl {

class TileBendingLaw {
 public:
  TileBendingLaw() = default;
  // Throws FemParameterError, located at the row, for a curvature squared with a negative
  // coefficient (h_k < 0; κ_u² and κ_v² > 0 are the file reader's check).
  explicit TileBendingLaw(const TileLawFile& law);
  // W_b, its gradient and its Hessian (6×6, row-major) in θ; g, h may be null.
  void evaluate(const std::array<double, 6>& theta, double* w, std::array<double, 6>* g,
                std::array<double, 36>* h) const;
  // The same for the law with the coefficient of curvature monomial i set to 1 and
  // every other to 0: ∂W_b/∂c_i (h_k = 2c[θ_k²] is linear in c too).
  void evaluate_unit(int i, const std::array<double, 6>& theta, double* w, std::array<double, 6>* g) const;
  int size() const { return static_cast<int>(exponent_.size()); }
  // The law of the monomials whose strains all lie in `strains` (indexed as kTileLawStrainNames),
  // every other coefficient 0; linear in the coefficients as TileMembraneLaw::restricted.
  TileBendingLaw restricted(const std::array<bool, 6>& strains) const;
  // "curvature_warp^2*stretch_warp" for curvature monomial i.
  std::string name(int i) const;

 private:
  struct Monomial {
    std::array<int, 6> exponent{};
    std::array<int, 6> active{};  // the strains with a positive exponent
    int num_active = 0;
  };
  // Σ c_i t^{e_i} at the normalized strains t: value, gradient (6), Hessian (36), third derivatives (216).
  void polynomial(const double* c, const std::array<double, 6>& t, double* p, double* g, double* h,
                  double* third) const;
  // The law of coefficients c continued beyond the box with face curvatures h_k (tile_law_continuation.h).
  void extend(const double* c, const std::array<double, 6>& rest, const std::array<double, 6>& theta, double* w,
              std::array<double, 6>* g, std::array<double, 36>* h) const;
  TileLawBox<6> box_;
  std::array<double, 6> rest_curvature_{};  // h_k in t (0 for the membrane strains)
  std::vector<Monomial> exponent_;
  std::vector<double> coefficient_;
};

}  // namespace wl
