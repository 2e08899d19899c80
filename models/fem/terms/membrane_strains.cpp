#include "models/fem/terms/membrane_strains.h"

#include <cmath>

namespace wl {

MembraneStrains membrane_strains(const Vec3& wu, const Vec3& wv, bool second) {
  MembraneStrains r;
  const double lu = wu.norm(), lv = wv.norm();
  if (lu < 1e-300 || lv < 1e-300) return r;
  const Vec3 p = wu / lu, n = wv / lv;
  const double s = p.dot(n), c2 = 1.0 - s * s;
  if (!(c2 > 1e-24)) return r;
  const double c = std::sqrt(c2);
  r.valid = true;
  r.m = {lu - 1.0, lv - 1.0, std::asin(s)};
  const Vec3 dsu = (n - s * p) / lu, dsv = (p - s * n) / lv;  // ∂s/∂w_u, ∂s/∂w_v
  r.gu = {p, Vec3::Zero(), Vec3(dsu / c)};
  r.gv = {Vec3::Zero(), n, Vec3(dsv / c)};
  if (!second) return r;
  const Mat3 I = Mat3::Identity(), Pu = I - p * p.transpose(), Pv = I - n * n.transpose();
  // ∂²s (in_plane_shear.cpp): H_uu = −(p g_uᵀ + g_u pᵀ)/l_u − s P_u/l_u², H_uv = (P_v/l_v − p g_vᵀ)/l_u.
  const Mat3 suu = -(p * dsu.transpose() + dsu * p.transpose()) / lu - s * Pu / (lu * lu);
  const Mat3 svv = -(n * dsv.transpose() + dsv * n.transpose()) / lv - s * Pv / (lv * lv);
  const Mat3 suv = (Pv / lv - p * dsv.transpose()) / lu;
  const double k3 = s / (c2 * c);  // ∇²γ = ∇²s/c + (s/c³)∇s∇sᵀ
  r.huu = {Pu / lu, Mat3::Zero(), Mat3(suu / c + k3 * dsu * dsu.transpose())};
  r.huv = {Mat3::Zero(), Mat3::Zero(), Mat3(suv / c + k3 * dsu * dsv.transpose())};
  r.hvv = {Mat3::Zero(), Pv / lv, Mat3(svv / c + k3 * dsv * dsv.transpose())};
  return r;
}

}  // namespace wl
