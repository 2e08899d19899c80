// Deformation gradient of a triangle over warp/weft material coordinates
// (docs/models.md §6.2, the Optitex note): F = [dx1 dx2]·[du1 du2]⁻¹ (3×2), with
// du_k = (u_k − u_0, v_k − v_0) and dx_k = x_k − x_0. The columns
//   w_u = F·(1,0)  (warp direction),  w_v = F·(0,1)  (weft direction)
// are linear in the three positions: w_u = Σ a_k x_k, w_v = Σ b_k x_k, with
// coefficients precomputed once from the rest UVs (the "inverse precomputed").
// ‖w_u‖ = ‖w_v‖ = 1 and w_u ⟂ w_v in the rest state (UVs in metres).
#pragma once
#include <array>
#include <cmath>
#include <stdexcept>
#include <string>

#include <Eigen/Core>

#include "models/core/types.h"

namespace wl {

struct TriangleRest {
  std::array<double, 3> a{};  // w_u = Σ a_k x_k
  std::array<double, 3> b{};  // w_v = Σ b_k x_k
  double area = 0.0;          // rest (UV) area, ½|UV_det| (002 calls UV_det the area; it is twice it, I-11)
};

// Precomputes the rest data of the triangle (uv0, uv1, uv2). Throws
// std::invalid_argument for a degenerate (zero-area) or clockwise triangle:
// UV_det = pu1·pv2 − pu2·pv1 must be > 0.
inline TriangleRest triangle_rest(const Vec2& uv0, const Vec2& uv1, const Vec2& uv2) {
  const double pu1 = uv1.x() - uv0.x(), pv1 = uv1.y() - uv0.y();
  const double pu2 = uv2.x() - uv0.x(), pv2 = uv2.y() - uv0.y();
  const double det = pu1 * pv2 - pu2 * pv1;
  const double scale = (uv1 - uv0).squaredNorm() + (uv2 - uv0).squaredNorm();
  if (!(det > 1e-12 * scale) || !std::isfinite(det))
    throw std::invalid_argument("triangle_rest: degenerate or clockwise UV triangle (UV_det = " + std::to_string(det) +
                                ")");
  TriangleRest r;
  // w_u = (dx1·pv2 − dx2·pv1)/det, w_v = (−dx1·pu2 + dx2·pu1)/det  (the Optitex note)
  r.a = {(pv1 - pv2) / det, pv2 / det, -pv1 / det};
  r.b = {(pu2 - pu1) / det, -pu2 / det, pu1 / det};
  r.area = 0.5 * det;
  return r;
}

// Columns of F from the local positions x0, x1, x2 (9 doubles).
inline Vec3 warp_vector(const TriangleRest& r, const double* q) {
  return r.a[0] * Eigen::Map<const Vec3>(q) + r.a[1] * Eigen::Map<const Vec3>(q + 3) +
         r.a[2] * Eigen::Map<const Vec3>(q + 6);
}
inline Vec3 weft_vector(const TriangleRest& r, const double* q) {
  return r.b[0] * Eigen::Map<const Vec3>(q) + r.b[1] * Eigen::Map<const Vec3>(q + 3) +
         r.b[2] * Eigen::Map<const Vec3>(q + 6);
}

// The 6×9 map C with (w_u; w_v) = C·(x0; x1; x2). An energy ψ(w_u, w_v) with
// gradient G (6) and Hessian H (6×6) has gradient Cᵀ G and Hessian Cᵀ H C in x.
inline Eigen::Matrix<double, 6, 9> column_map(const TriangleRest& r) {
  Eigen::Matrix<double, 6, 9> c = Eigen::Matrix<double, 6, 9>::Zero();
  for (int k = 0; k < 3; ++k) {
    c.block<3, 3>(0, 3 * k).diagonal().setConstant(r.a[k]);
    c.block<3, 3>(3, 3 * k).diagonal().setConstant(r.b[k]);
  }
  return c;
}

// The same without forming C (assembly-speed form): writes s·Cᵀ(g_u; g_v) into
// f (9) and s·Cᵀ[H_uu H_uv; H_uvᵀ H_vv]C into k (9×9, column-major).
inline void add_column_gradient(const TriangleRest& r, const Vec3& gu, const Vec3& gv, double s, double* f) {
  for (int k = 0; k < 3; ++k) Eigen::Map<Vec3>(f + 3 * k) += s * (r.a[k] * gu + r.b[k] * gv);
}
inline void add_column_hessian(const TriangleRest& r, const Mat3& huu, const Mat3& huv, const Mat3& hvv, double s,
                               double* k) {
  Eigen::Map<Eigen::Matrix<double, 9, 9>> K(k);
  for (int m = 0; m < 3; ++m)
    for (int n = m; n < 3; ++n) {
      const Mat3 b = s * (r.a[m] * r.a[n] * huu + r.a[m] * r.b[n] * huv + r.b[m] * r.a[n] * huv.transpose() +
                          r.b[m] * r.b[n] * hvv);
      K.block<3, 3>(3 * m, 3 * n) += b;
      if (n != m) K.block<3, 3>(3 * n, 3 * m) += b.transpose();
    }
}

}  // namespace wl
