// The curvature part of the tile law on a triangle (docs/models.md §6.9.1):
//   V = A·W_b(ε_u, ε_v, γ, κ_u, κ_v, κ_uv),
// A the rest area, the membrane strains of membrane_strains.h, W_b the law's
// monomials with a curvature (tile_bending_law.h), and the curvature per triangle
// from the dihedral angles θ_k of its three edges (a discrete shape operator,
// Grinspun et al. 2003 [not in the sources]):
//   B = [κ_u κ_uv; κ_uv κ_v] = −Σ_k θ_k ‖ē_k‖/(2A) t_k t_kᵀ,
// ē_k the rest (UV) edge, t_k its unit normal in UV. On the grid mesh B is exact
// for every constant curvature of the flat cloth (to first order): a cylinder
// about v bends each edge along v by θ = −κ_u L. A border edge has no angle and
// adds nothing, as the hinges have none there. The sign puts κ > 0 where the cloth
// curves towards w_u × w_v, the tile's convention (docs/calibration.md §9.1).
// Stencil: the triangle's vertices x0, x1, x2 (CCW in UV), then o0, o1, o2, o_k
// the apex across edge (x_k, x_{k+1}) (x_{k+2} again on a border edge).
// Derivatives: with θ6 = (m, κ), ∇V = A Σ_j ∂_j W_b ∇θ6_j and
// ∇²V = A(Σ_jl ∂_jl W_b ∇θ6_j ∇θ6_lᵀ + Σ_j ∂_j W_b ∇²θ6_j), ∇κ = Σ_k a_k ∇θ_k,
// ∇²κ = Σ_k a_k ∇²θ_k (a_k the coefficients above; ∇θ_k, ∇²θ_k of hinge_bending.h).
// Parameters: the law's curvature coefficients, keys "fem.tile_law." + the
// monomial's name; ∂f/∂c_i the force of the unit law (tile_bending_law.h).
#pragma once
#include <memory>
#include <string>
#include <vector>

#include "models/core/term.h"
#include "models/fem/deformation_gradient.h"
#include "models/fem/tile_bending_law.h"

namespace wl {

class TileBendingTerm : public StencilTerm<18> {
 public:
  explicit TileBendingTerm(std::shared_ptr<const TileBendingLaw> law);
  std::string name() const override { return "fem-tile-bending"; }
  std::unique_ptr<Term> clone() const override { return std::make_unique<TileBendingTerm>(*this); }
  // vertices: x0, x1, x2 (CCW in UV) and the apexes o0, o1, o2 (−1: a border edge);
  // uv: the rest UVs of x0, x1, x2.
  void add(const std::array<int, 6>& vertices, const std::array<Vec2, 3>& uv);
  double energy(int e, const double* q) const override;
  void evaluate(int e, const double* q, const double* v, const ElementOutput& out) const override;
  std::vector<std::string> parameter_keys() const override;
  void parameter_derivative(int e, int k, const double* q, const double* v, double* dfdp) const override;
  const TileBendingLaw& law() const { return *law_; }
  // The same triangles under another law.
  std::unique_ptr<TileBendingTerm> with_law(std::shared_ptr<const TileBendingLaw> law) const;
  // (κ_u, κ_v, κ_uv) of element e at local positions q (18 doubles).
  std::array<double, 3> curvature(int e, const double* q) const;

 private:
  struct Rest {
    TriangleRest triangle;
    std::array<std::array<double, 3>, 3> a{};  // ∂(κ_u, κ_v, κ_uv)/∂θ_k
    std::array<bool, 3> hinge{};               // edge k has a neighbour
  };
  // The strains θ6 with their gradients (18) and, when `second`, their Hessians (18×18).
  struct Strains;
  bool strains(int e, const double* q, bool second, Strains& s) const;
  std::shared_ptr<const TileBendingLaw> law_;
  std::vector<Rest> rest_;
};

}  // namespace wl
