// Warp and weft stretch of a triangle (docs/models.md §6.3; the
// energy is the continuum analogue of the yarn stretch V = ½k_sΔu(‖w‖−1)²,
// docs/models.md §3.2):
//   V = A·ψ(ε_u, ε_v),  ε_u = ‖w_u‖−1,  ε_v = ‖w_v‖−1,
//   ψ = ½k_u ε_u² + ½k_v ε_v² + k_c ε_u ε_v + ¼q_u ε_u⁴ + ¼q_v ε_v⁴ + ¼q_a (ε_u + ε_v)⁴,
// A the rest (UV) area, w_u, w_v the columns of F (deformation_gradient.h),
// k_u, k_v stiffness per unit width [N/m] along warp (u) and weft (v). The
// warp–weft coupling k_c and the quartic stiffening q_u, q_v, q_a [N/m] are
// optional (0: off, the linear law ½k_u ε_u² + ½k_v ε_v², evaluated as before
// bit for bit); ψ is convex in (ε_u, ε_v) iff k_c² < k_u k_v (docs/models.md
// §6.3.1), which the constructor demands. The rest state is the flat UV layout
// (‖w‖ = 1); a uniform stretch ε along u carries the membrane force
// k_u ε + (q_u + q_a)ε³ per unit width. Compression is charged like tension (no
// buckling model); the exact Hessian is indefinite under compression
// (‖w‖ < 1), as for the yarn stretch.
#pragma once
#include <vector>

#include "models/core/term.h"
#include "models/fem/deformation_gradient.h"

namespace wl {

struct StretchLaw {
  double k_u = 0, k_v = 0;  // warp, weft [N/m]
  double k_c = 0;           // warp–weft coupling [N/m], k_c² < k_u k_v
  double q_u = 0, q_v = 0;  // quartic stiffening [N/m], ≥ 0
  double q_a = 0;           // quartic stiffening of the areal strain ε_u + ε_v [N/m], ≥ 0
  bool linear() const { return k_c == 0 && q_u == 0 && q_v == 0 && q_a == 0; }
  // ∂ψ/∂ε_u, ∂ψ/∂ε_v.
  double stress_u(double eu, double ev) const { return k_u * eu + k_c * ev + q_u * eu * eu * eu + areal(eu + ev); }
  double stress_v(double eu, double ev) const { return k_v * ev + k_c * eu + q_v * ev * ev * ev + areal(eu + ev); }
  double areal(double a) const { return q_a * a * a * a; }
};

class WarpWeftStretchTerm : public StencilTerm<9> {
 public:
  WarpWeftStretchTerm(double k_u_N_per_m, double k_v_N_per_m)
      : WarpWeftStretchTerm(StretchLaw{k_u_N_per_m, k_v_N_per_m}) {}
  // Throws std::invalid_argument unless k_c² < k_u k_v (k_c ≠ 0) and q_u, q_v, q_a ≥ 0.
  explicit WarpWeftStretchTerm(const StretchLaw& law);
  std::string name() const override { return "fem-stretch"; }
  std::unique_ptr<Term> clone() const override { return std::make_unique<WarpWeftStretchTerm>(*this); }
  // stencil: x of the triangle's vertices (3 DoFs each), CCW in UV.
  void add(const std::array<int, 9>& stencil, const TriangleRest& rest);
  double energy(int e, const double* q) const override;
  void evaluate(int e, const double* q, const double* v, const ElementOutput& out) const override;
  // k_u, k_v, then k_c, q_u, q_v, q_a where non-zero: ψ is linear in each, so ∂f/∂p is the force
  // of the law with p = 1 and every other parameter 0.
  std::vector<std::string> parameter_keys() const override { return keys_; }
  void parameter_derivative(int e, int k, const double* q, const double* v, double* dfdp) const override;

 private:
  // The force (and with dfdq its Jacobian) of `law` on element e, added to out.
  void add_law(const StretchLaw& law, int e, const double* q, double* force, double* dfdq) const;
  StretchLaw law_;
  std::vector<std::string> keys_;
  std::vector<StretchLaw> unit_laws_;  // per parameter key: that parameter 1, the others 0
  std::vector<TriangleRest> rest_;
};

}  // namespace wl
