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
// Spline law (§6.4.1): the linear part ½k_sh s² is replaced by E(|s|), whose tangent
// stiffness κ interpolates k_0 = k_sh, k_1, …, k_n at knots sin γ_1 < … < sin γ_n
// (shear_stiffness_spline.h); the lock ½k_sh ψ_lock stays:
//   V = A·(E(|s|) + ½k_sh s_l² r^{m+1}/(m+1)).
#pragma once
#include <vector>

#include "models/core/term.h"
#include "models/fem/deformation_gradient.h"
#include "models/fem/terms/shear_stiffness_spline.h"

namespace wl {

class InPlaneShearTerm : public StencilTerm<9> {
 public:
  // lock_angle_rad: shear angle γ_lock where stiffening starts (0 < γ_lock < π/2);
  // lock_exponent m > 0, or ≤ 0 for no locking.
  InPlaneShearTerm(double k_sh_N_per_m, double lock_angle_rad = 0.0, double lock_exponent = 0.0);
  // The spline law: knot angles γ_1 < … < γ_n (rad, below π/2) and the tangent stiffness k_1 … k_n there.
  InPlaneShearTerm(double k_sh_N_per_m, double lock_angle_rad, double lock_exponent,
                   const std::vector<double>& knots_rad, const std::vector<double>& knot_N_per_m);
  std::string name() const override { return "fem-shear"; }
  std::unique_ptr<Term> clone() const override { return std::make_unique<InPlaneShearTerm>(*this); }
  void add(const std::array<int, 9>& stencil, const TriangleRest& rest);
  double energy(int e, const double* q) const override;
  void evaluate(int e, const double* q, const double* v, const ElementOutput& out) const override;

  // k_sh, with locking γ_lock and m, then the spline law's knot values (docs/calibration.md §3).
  std::vector<std::string> parameter_keys() const override;
  void parameter_derivative(int e, int k, const double* q, const double* v, double* dfdp) const override;

  // ψ(s) and its first two derivatives (exposed for tests).
  void psi(double s, double* p, double* dp, double* ddp) const;
  // The energy per rest area e(s) = V/A and its first two derivatives in s, either law.
  void density(double s, double* e, double* de, double* dde) const;
  bool locking() const { return locking_; }

 private:
  void lock(double s, double* p, double* dp, double* ddp) const;  // ψ − s² (0 without locking)
  double k_;
  bool locking_;
  double lock_angle_, s_lock_, m_;
  bool spline_ = false;
  ShearStiffnessSpline curve_;
  std::vector<double> knots_;  // k_0 = k_sh, k_1, …, k_n
  std::vector<TriangleRest> rest_;
};

}  // namespace wl
