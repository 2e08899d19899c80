#include "models/fem/terms/in_plane_shear.h"

#include <cmath>

#include "models/fem/fem_material.h"

namespace wl {

InPlaneShearTerm::InPlaneShearTerm(double k, double lock_angle, double lock_exponent)
    : k_(k),
      locking_(lock_exponent > 0.0 && lock_angle > 0.0 && lock_angle < M_PI / 2),
      lock_angle_(lock_angle),
      s_lock_(std::sin(lock_angle)),
      m_(lock_exponent) {}

void InPlaneShearTerm::add(const std::array<int, 9>& stencil, const TriangleRest& rest) {
  stencils_.push_back(stencil);
  rest_.push_back(rest);
}

void InPlaneShearTerm::psi(double s, double* p, double* dp, double* ddp) const {
  *p = s * s;
  *dp = 2.0 * s;
  *ddp = 2.0;
  if (!locking_) return;
  // r^m with r = s²/s_l²; r^{m−1} never appears (ψ'' = 2 + (2+4m) r^m), so m < 1 is safe at s = 0.
  const double r = s * s / (s_lock_ * s_lock_);
  const double rm = std::pow(r, m_);
  *p += s_lock_ * s_lock_ * rm * r / (m_ + 1.0);
  *dp += 2.0 * s * rm;
  *ddp += (2.0 + 4.0 * m_) * rm;
}

double InPlaneShearTerm::energy(int e, const double* q) const {
  const TriangleRest& r = rest_[e];
  const Vec3 wu = warp_vector(r, q), wv = weft_vector(r, q);
  const double lu = wu.norm(), lv = wv.norm();
  if (lu < 1e-300 || lv < 1e-300) return 0.0;
  double p, dp, ddp;
  psi(wu.dot(wv) / (lu * lv), &p, &dp, &ddp);
  return r.area * 0.5 * k_ * p;
}

void InPlaneShearTerm::evaluate(int e, const double* q, const double*, const ElementOutput& out) const {
  const TriangleRest& r = rest_[e];
  const Vec3 wu = warp_vector(r, q), wv = weft_vector(r, q);
  const double lu = wu.norm(), lv = wv.norm();
  if (lu < 1e-300 || lv < 1e-300) return;  // collapsed: angle undefined, no force
  const Vec3 p = wu / lu, n = wv / lv;
  const double s = p.dot(n);
  // ∂s/∂w_u = (n − s p)/l_u, ∂s/∂w_v = (p − s n)/l_v
  const Vec3 gu = (n - s * p) / lu, gv = (p - s * n) / lv;
  const Mat3 I = Mat3::Identity();
  const Mat3 Pu = I - p * p.transpose(), Pv = I - n * n.transpose();
  // ∂²s: H_uu = −(p g_uᵀ + g_u pᵀ)/l_u − s P_u/l_u², H_uv = (P_v/l_v − p g_vᵀ)/l_u, H_vv likewise.
  const Mat3 huu = -(p * gu.transpose() + gu * p.transpose()) / lu - s * Pu / (lu * lu);
  const Mat3 hvv = -(n * gv.transpose() + gv * n.transpose()) / lv - s * Pv / (lv * lv);
  const Mat3 huv = (Pv / lv - p * gv.transpose()) / lu;
  double ps, dps, ddps;
  psi(s, &ps, &dps, &ddps);
  const double c = r.area * 0.5 * k_;
  // V = c ψ(s): ∇V = c ψ' ∇s, ∇²V = c (ψ'' ∇s∇sᵀ + ψ' ∇²s), mapped to x by C (deformation_gradient.h).
  add_column_gradient(r, gu, gv, -c * dps, out.force);
  if (out.dfdq)
    add_column_hessian(r, ddps * gu * gu.transpose() + dps * huu, ddps * gu * gv.transpose() + dps * huv,
                       ddps * gv * gv.transpose() + dps * hvv, -c, out.dfdq);
}

std::vector<std::string> InPlaneShearTerm::parameter_keys() const {
  if (!locking_) return {kFemShear};
  return {kFemShear, kFemShearLockAngle, kFemShearLockExponent};
}

void InPlaneShearTerm::parameter_derivative(int e, int k, const double* q, const double*, double* dfdp) const {
  const TriangleRest& r = rest_[e];
  const Vec3 wu = warp_vector(r, q), wv = weft_vector(r, q);
  const double lu = wu.norm(), lv = wv.norm();
  if (lu < 1e-300 || lv < 1e-300) return;
  const Vec3 p = wu / lu, n = wv / lv;
  const double s = p.dot(n);
  const Vec3 gu = (n - s * p) / lu, gv = (p - s * n) / lv;
  // f = −(A/2) k ψ'(s) ∇s; differentiate the factor k ψ'(s) only.
  double dpsi_dp = 0.0;
  if (k == 0) {
    double ps, dps, ddps;
    psi(s, &ps, &dps, &ddps);
    dpsi_dp = dps;
  } else {
    // ψ' = 2s(1 + r^m), r = s²/s_l², s_l = sin γ_lock.
    const double rr = s * s / (s_lock_ * s_lock_);
    const double rm = rr > 0 ? std::pow(rr, m_) : 0.0;
    if (k == 1) dpsi_dp = k_ * (-4.0 * m_ * s * rm / s_lock_) * std::cos(lock_angle_);
    else dpsi_dp = rr > 0 ? k_ * 2.0 * s * rm * std::log(rr) : 0.0;
  }
  add_column_gradient(r, gu, gv, -r.area * 0.5 * dpsi_dp, dfdp);
}

}  // namespace wl
