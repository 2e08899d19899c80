#include "models/fem/terms/in_plane_shear.h"

#include <cmath>
#include <stdexcept>

#include "models/fem/fem_material.h"

namespace wl {

InPlaneShearTerm::InPlaneShearTerm(double k, double lock_angle, double lock_exponent)
    : k_(k),
      locking_(lock_exponent > 0.0 && lock_angle > 0.0 && lock_angle < M_PI / 2),
      lock_angle_(lock_angle),
      s_lock_(std::sin(lock_angle)),
      m_(lock_exponent) {}

InPlaneShearTerm::InPlaneShearTerm(double k, double lock_angle, double lock_exponent,
                                   const std::vector<double>& knots_rad, const std::vector<double>& knot_N_per_m)
    : InPlaneShearTerm(k, lock_angle, lock_exponent) {
  if (knots_rad.size() != knot_N_per_m.size())
    throw std::invalid_argument("shear spline: one knot value per knot angle");
  std::vector<double> s;
  for (double g : knots_rad) {
    if (!(g > 0.0 && g < M_PI / 2)) throw std::invalid_argument("shear spline: knot angles must lie in (0, π/2)");
    s.push_back(std::sin(g));
  }
  spline_ = true;
  curve_ = ShearStiffnessSpline(s);
  knots_ = {k};
  knots_.insert(knots_.end(), knot_N_per_m.begin(), knot_N_per_m.end());
}

void InPlaneShearTerm::add(const std::array<int, 9>& stencil, const TriangleRest& rest) {
  stencils_.push_back(stencil);
  rest_.push_back(rest);
}

void InPlaneShearTerm::lock(double s, double* p, double* dp, double* ddp) const {
  *p = *dp = *ddp = 0.0;
  if (!locking_) return;
  // r^m with r = s²/s_l²; r^{m−1} never appears (ψ'' = 2 + (2+4m) r^m), so m < 1 is safe at s = 0.
  const double r = s * s / (s_lock_ * s_lock_);
  const double rm = std::pow(r, m_);
  *p = s_lock_ * s_lock_ * rm * r / (m_ + 1.0);
  *dp = 2.0 * s * rm;
  *ddp = (2.0 + 4.0 * m_) * rm;
}

void InPlaneShearTerm::psi(double s, double* p, double* dp, double* ddp) const {
  double lp, ldp, lddp;
  lock(s, &lp, &ldp, &lddp);
  *p = s * s + lp;
  *dp = 2.0 * s + ldp;
  *ddp = 2.0 + lddp;
}

// e = ½k_sh ψ(s), or with the spline law E(|s|) + ½k_sh ψ_lock(s) (docs/models.md §6.4.1).
void InPlaneShearTerm::density(double s, double* e, double* de, double* dde) const {
  if (!spline_) {
    psi(s, e, de, dde);
    *e *= 0.5 * k_;
    *de *= 0.5 * k_;
    *dde *= 0.5 * k_;
    return;
  }
  double lp, ldp, lddp;
  lock(s, &lp, &ldp, &lddp);
  curve_.evaluate(s, knots_.data(), e, de, dde);
  *e += 0.5 * k_ * lp;
  *de += 0.5 * k_ * ldp;
  *dde += 0.5 * k_ * lddp;
}

double InPlaneShearTerm::energy(int e, const double* q) const {
  const TriangleRest& r = rest_[e];
  const Vec3 wu = warp_vector(r, q), wv = weft_vector(r, q);
  const double lu = wu.norm(), lv = wv.norm();
  if (lu < 1e-300 || lv < 1e-300) return 0.0;
  const double s = wu.dot(wv) / (lu * lv);
  double p, dp, ddp;
  if (spline_) {
    density(s, &p, &dp, &ddp);
    return r.area * p;
  }
  psi(s, &p, &dp, &ddp);
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
  // V = c ψ(s) (linear law, c = A·½k_sh) or c e(s) (spline law, c = A): ∇V = c ψ' ∇s,
  // ∇²V = c (ψ'' ∇s∇sᵀ + ψ' ∇²s), mapped to x by C (deformation_gradient.h).
  double ps, dps, ddps;
  if (spline_) density(s, &ps, &dps, &ddps);
  else psi(s, &ps, &dps, &ddps);
  const double c = spline_ ? r.area : r.area * 0.5 * k_;
  add_column_gradient(r, gu, gv, -c * dps, out.force);
  if (out.dfdq)
    add_column_hessian(r, ddps * gu * gu.transpose() + dps * huu, ddps * gu * gv.transpose() + dps * huv,
                       ddps * gv * gv.transpose() + dps * hvv, -c, out.dfdq);
}

std::vector<std::string> InPlaneShearTerm::parameter_keys() const {
  std::vector<std::string> keys{kFemShear};
  if (locking_) keys.insert(keys.end(), {kFemShearLockAngle, kFemShearLockExponent});
  for (size_t i = 1; i < knots_.size(); ++i) keys.push_back(std::string("fem.") + shear_knot_key(int(i) - 1));
  return keys;
}

void InPlaneShearTerm::parameter_derivative(int e, int k, const double* q, const double*, double* dfdp) const {
  const TriangleRest& r = rest_[e];
  const Vec3 wu = warp_vector(r, q), wv = weft_vector(r, q);
  const double lu = wu.norm(), lv = wv.norm();
  if (lu < 1e-300 || lv < 1e-300) return;
  const Vec3 p = wu / lu, n = wv / lv;
  const double s = p.dot(n);
  const Vec3 gu = (n - s * p) / lu, gv = (p - s * n) / lv;
  // f = −A e'(s) ∇s, e' = ½k ψ'(s) (linear) or σ(s) + ½k ψ_lock'(s) (spline); differentiate e' only.
  // Parameters: k_sh, then γ_lock and m with locking, then the knot values k_1 … k_n.
  const int lock_params = locking_ ? 2 : 0;
  double dpsi_dp = 0.0;  // 2∂e'/∂p (the linear law's ∂(kψ')/∂p): ∂f/∂p = −(A/2)·dpsi_dp·∇s
  if (k == 0) {
    double ps, dps, ddps;
    if (spline_) {
      // e' is linear in k_sh: k_0 of the spline and the lock's ½k_sh ψ_lock'
      std::vector<double> unit(knots_.size(), 0.0);
      unit[0] = 1.0;
      double le, lde, ldde;
      curve_.evaluate(s, unit.data(), &ps, &dps, &ddps);
      lock(s, &le, &lde, &ldde);
      dpsi_dp = 2.0 * dps + lde;
    } else {
      psi(s, &ps, &dps, &ddps);
      dpsi_dp = dps;
    }
  } else if (k <= lock_params) {
    // ψ_lock' = 2s r^m, r = s²/s_l², s_l = sin γ_lock.
    const double rr = s * s / (s_lock_ * s_lock_);
    const double rm = rr > 0 ? std::pow(rr, m_) : 0.0;
    if (k == 1) dpsi_dp = k_ * (-4.0 * m_ * s * rm / s_lock_) * std::cos(lock_angle_);
    else dpsi_dp = rr > 0 ? k_ * 2.0 * s * rm * std::log(rr) : 0.0;
  } else {
    std::vector<double> unit(knots_.size(), 0.0);
    unit[k - lock_params] = 1.0;
    double ps, dps, ddps;
    curve_.evaluate(s, unit.data(), &ps, &dps, &ddps);
    dpsi_dp = 2.0 * dps;
  }
  add_column_gradient(r, gu, gv, -r.area * 0.5 * dpsi_dp, dfdp);
}

}  // namespace wl
