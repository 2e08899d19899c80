// In-plane shear of a triangle with optional shear locking [not in the sources: the
// continuum counterpart of the yarn shear, docs/models.md §3.4; here §6.4]:
//   s = w_u·w_v / (‖w_u‖‖w_v‖)        cosine of the warp/weft angle φ;
//                                      s = cos φ = sin γ, γ = π/2 − φ the shear angle
//   V = A·½ k_sh ψ(s),  ψ(s) = s² + s_l²·r^{m+1}/(m+1),  r = s²/s_l²,
// so that ψ'(s) = 2s·(1 + (s/s_l)^{2m}): the effective shear stiffness is
// k_sh·(1 + (s/s_l)^{2m}) — equal to k_sh for |γ| ≪ γ_lock, doubled at the lock
// angle (s_l = sin γ_lock) and growing like (s/s_l)^{2m} beyond it (shear lock).
// For small γ, V ≈ A·½k_sh γ², matching the yarn V = ½k_sh,yarn L(φ−π/2)² per
// crossing with k_sh = k_sh,yarn/L. m ≤ 0 (or s_l ≥ 1) switches locking off.
// k_sh in N/m (per unit width); A the rest area.
#pragma once
#include <vector>

#include "models/core/term.h"
#include "models/fem/deformation_gradient.h"

namespace wl {

class InPlaneShearTerm : public StencilTerm<9> {
 public:
  // lock_angle_rad: shear angle γ_lock where stiffening starts (0 < γ_lock < π/2);
  // lock_exponent m > 0, or ≤ 0 for no locking.
  InPlaneShearTerm(double k_sh_N_per_m, double lock_angle_rad = 0.0, double lock_exponent = 0.0);
  std::string name() const override { return "fem-shear"; }
  std::unique_ptr<Term> clone() const override { return std::make_unique<InPlaneShearTerm>(*this); }
  void add(const std::array<int, 9>& stencil, const TriangleRest& rest);
  double energy(int e, const double* q) const override;
  void evaluate(int e, const double* q, const double* v, const ElementOutput& out) const override;

  // k_sh, and with locking γ_lock and m (docs/calibration.md §3).
  std::vector<std::string> parameter_keys() const override;
  void parameter_derivative(int e, int k, const double* q, const double* v, double* dfdp) const override;

  // ψ(s) and its first two derivatives (exposed for tests).
  void psi(double s, double* p, double* dp, double* ddp) const;
  bool locking() const { return locking_; }

 private:
  double k_;
  bool locking_;
  double lock_angle_, s_lock_, m_;
  std::vector<TriangleRest> rest_;
};

}  // namespace wl
