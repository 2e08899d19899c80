// Warp and weft stretch of a triangle (docs/models.md §6.3; the
// energy is the continuum analogue of the yarn stretch V = ½k_sΔu(‖w‖−1)²,
// docs/models.md §3.2):
//   V = A·½( k_u(‖w_u‖−1)² + k_v(‖w_v‖−1)² ),
// A the rest (UV) area, w_u, w_v the columns of F (deformation_gradient.h),
// k_u, k_v stiffness per unit width [N/m] along warp (u) and weft (v). The rest
// state is the flat UV layout (‖w‖ = 1); a uniform stretch ε along u carries
// the membrane force k_u·ε per unit width. Compression is charged like
// tension (no buckling model); the exact Hessian is indefinite under
// compression (‖w‖ < 1), as for the yarn stretch.
#pragma once
#include <vector>

#include "models/core/term.h"
#include "models/fem/deformation_gradient.h"

namespace wl {

class WarpWeftStretchTerm : public StencilTerm<9> {
 public:
  WarpWeftStretchTerm(double k_u_N_per_m, double k_v_N_per_m) : k_u_(k_u_N_per_m), k_v_(k_v_N_per_m) {}
  std::string name() const override { return "fem-stretch"; }
  std::unique_ptr<Term> clone() const override { return std::make_unique<WarpWeftStretchTerm>(*this); }
  // stencil: x of the triangle's vertices (3 DoFs each), CCW in UV.
  void add(const std::array<int, 9>& stencil, const TriangleRest& rest);
  double energy(int e, const double* q) const override;
  void evaluate(int e, const double* q, const double* v, const ElementOutput& out) const override;
  // k_u, k_v: the force is linear in each, ∂f/∂k_u = f at k_u = 1, k_v = 0.
  std::vector<std::string> parameter_keys() const override;
  void parameter_derivative(int e, int k, const double* q, const double* v, double* dfdp) const override;

 private:
  double k_u_, k_v_;
  std::vector<TriangleRest> rest_;
};

}  // namespace wl
