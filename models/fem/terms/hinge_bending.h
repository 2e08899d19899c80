// Bending across an interior edge of the triangle mesh (dihedral-angle hinge,
// discrete shells, Grinspun et al. 2003) [not in the sources] (docs/models.md §6.5):
//   V = ½ k_e · ‖ē‖²/(Ā₁+Ā₂) · (θ − θ₀)²,
// ē the rest (UV) edge, Ā₁, Ā₂ the rest areas of the two triangles, θ the
// signed dihedral angle (0 when flat, robust there: atan2 form, no 1/sin θ),
// θ₀ = 0 (the cloth is flat at rest: the material rest state is the UV layout).
// Stiffness per edge, from its direction d = (d_u, d_v) in UV space:
//   k_e = k_warp·d_v² + k_weft·d_u²,
// so an edge along v (crossed by the warp yarns) bends with the warp stiffness,
// an edge along u with the weft stiffness, and a 45° diagonal with the mean.
// With the optional diagonal stiffness k_diag > 0 (docs/models.md §6.5.1) the
// 45° edges bend with k_diag instead:
//   k_e = k_warp·d_v² + k_weft·d_u² + (k_diag − ½(k_warp + k_weft))·4d_u²d_v²,
// still linear in each stiffness, equal to the above on edges along u and v.
// k in N·m (bending stiffness per unit width). Normalisation: on the grid mesh
// (right triangles, diagonal (i,j)-(i+1,j+1)), a cylinder of curvature κ about
// the v axis bends only the edges along v, each by θ = κL, so V per area is
// exactly ½k_warp κ² (likewise about u with k_weft); diagonals see only twist.
// On other meshes the effective stiffness differs by a mesh-dependent factor
// (½ for an equilateral mesh), which calibration absorbs.
//
// Stencil: (x0, x1) the edge, x2 the opposite vertex of the triangle that
// holds the edge as x0→x1 in its CCW order, x3 that of the other triangle.
// Gradient (Bridson et al. 2003): ∇_{x2}θ = −‖e‖N₁/‖N₁‖², ∇_{x3}θ = −‖e‖N₂/‖N₂‖²,
// ∇_{x0}θ = −(1−t₂)∇_{x2}θ − (1−t₃)∇_{x3}θ, ∇_{x1}θ = −t₂∇_{x2}θ − t₃∇_{x3}θ with
// N₁ = e×(x2−x0), N₂ = (x3−x0)×e, e = x1−x0, t_k = (x_k−x0)·e/‖e‖². The Hessian
// is the exact derivative of these expressions (product rule, carried as 3×12
// Jacobians of every intermediate vector).
#pragma once
#include <array>
#include <vector>

#include <Eigen/Geometry>

#include "models/core/term.h"

namespace wl {

class HingeBendingTerm : public StencilTerm<12> {
 public:
  // k_diag_N_m ≤ 0: no diagonal stiffness of its own (the 45° edges take the mean).
  HingeBendingTerm(double k_warp_N_m, double k_weft_N_m, double k_diag_N_m = 0.0)
      : k_warp_(k_warp_N_m), k_weft_(k_weft_N_m), k_diag_(k_diag_N_m) {}
  std::string name() const override { return "fem-bending"; }
  std::unique_ptr<Term> clone() const override { return std::make_unique<HingeBendingTerm>(*this); }
  // edge_uv = rest UV of x1 − rest UV of x0; area_sum = Ā₁ + Ā₂ (rest).
  void add(const std::array<int, 12>& stencil, const Vec2& edge_uv, double area_sum, double theta0 = 0.0);
  double energy(int e, const double* q) const override;
  void evaluate(int e, const double* q, const double* v, const ElementOutput& out) const override;
  // k_warp, k_weft (and k_diag when set): V is linear in each through k_e.
  std::vector<std::string> parameter_keys() const override;
  void parameter_derivative(int e, int k, const double* q, const double* v, double* dfdp) const override;

  // k_e for an edge of UV direction edge_uv (see above).
  double edge_stiffness(const Vec2& edge_uv) const;
  // Signed dihedral angle of the hinge at local positions q (12 doubles).
  static double dihedral_angle(const double* q);
  using Vec12 = Eigen::Matrix<double, 12, 1>;
  using Mat12 = Eigen::Matrix<double, 12, 12>;
  // θ, ∇θ and (hess non-null) the symmetric ∇²θ at q; false where the edge or a wing
  // has collapsed (no angle).
  static bool dihedral_derivatives(const double* q, double* theta, Vec12* grad, Mat12* hess);

 private:
  // ∂k_e/∂k for k = warp, weft, diagonal at edge direction d (unit).
  std::array<double, 3> stiffness_shares(const Vec2& d) const;

  double k_warp_, k_weft_, k_diag_;
  std::vector<double> coeff_;                  // k_e ‖ē‖²/(Ā₁+Ā₂)
  std::vector<std::array<double, 3>> shares_;  // ∂coeff/∂(k_warp, k_weft, k_diag)
  std::vector<double> theta0_;
};

}  // namespace wl
