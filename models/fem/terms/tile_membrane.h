// The membrane of the tile law on a triangle (docs/models.md §6.9): the energy
// density sampled from the woven fabric's periodic tile and fitted by
// `weavelab tiles` (docs/calibration.md §9), at zero curvature:
//   V = A·W_m(ε_u, ε_v, γ),  ε_u = ‖w_u‖ − 1,  ε_v = ‖w_v‖ − 1,  γ = asin s,
//   s = w_u·w_v/(‖w_u‖‖w_v‖),
// A the rest area, w_u, w_v the columns of F (deformation_gradient.h), W_m the
// law's membrane restriction (tile_law_file.h), extended beyond the sampled box.
// γ is the tile's shear angle: its map's columns meet at π/2 − γ (the same s as
// the shear term's, docs/models.md §6.4). It replaces the stretch and shear
// terms; bending stays with the mesh's bending term.
// Derivatives: ∇_w V = A Σ_k ∂W_m/∂m_k ∇m_k, ∇²_w V = A(Σ_kl ∂²W_m/∂m_k∂m_l ∇m_k∇m_lᵀ
// + Σ_k ∂W_m/∂m_k ∇²m_k), with ∇ε_u = (n_u, 0), ∇²ε_u = (I − n_u n_uᵀ)/‖w_u‖ in the
// u block, ∇γ = ∇s/c, ∇²γ = ∇²s/c + (s/c³)∇s∇sᵀ, c = √(1 − s²), ∇s and ∇²s as in
// in_plane_shear.h.
// Parameters: the law's membrane coefficients c_i, keys "fem.tile_law." + the
// monomial's name; V is linear in each, ∂f/∂c_i the force of the law with c_i = 1
// and every other 0. They are the tile fit's; no scene key sets them.
#pragma once
#include <memory>
#include <string>
#include <vector>

#include "models/core/term.h"
#include "models/fem/deformation_gradient.h"
#include "models/fem/tile_law_file.h"

namespace wl {

class TileMembraneTerm : public StencilTerm<9> {
 public:
  explicit TileMembraneTerm(std::shared_ptr<const TileMembraneLaw> law);
  std::string name() const override { return "fem-tile-membrane"; }
  std::unique_ptr<Term> clone() const override { return std::make_unique<TileMembraneTerm>(*this); }
  void add(const std::array<int, 9>& stencil, const TriangleRest& rest);
  double energy(int e, const double* q) const override;
  void evaluate(int e, const double* q, const double* v, const ElementOutput& out) const override;
  std::vector<std::string> parameter_keys() const override;
  void parameter_derivative(int e, int k, const double* q, const double* v, double* dfdp) const override;
  const TileMembraneLaw& law() const { return *law_; }
  // The same triangles under another law.
  std::unique_ptr<TileMembraneTerm> with_law(std::shared_ptr<const TileMembraneLaw> law) const;

 private:
  std::shared_ptr<const TileMembraneLaw> law_;
  std::vector<TriangleRest> rest_;
};

}  // namespace wl
