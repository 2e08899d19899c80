// The angle φ = arccos(d1·d3) between a warp and a weft segment at a crossing,
// with its gradient and Hessian over the local stencil (x0, x1, x3), and the
// element outputs of any energy V(φ) (docs/models.md §3.4.1; Cirio et al. 2016
// eqs. (41)–(51)). Shared by the shear terms.
//
// With t1 = P1 d3 / sin φ, t3 = P3 d1 / sin φ (unit, in the plane of d1, d3) and
// b = d1 × d3 / sin φ (unit normal of that plane):
//   ∇_{x1}φ = −t1 / l1,  ∇_{x3}φ = −t3 / l3,  ∇_{x0}φ = −(∇_{x1}φ + ∇_{x3}φ)
//   H11 = (t1 d1ᵀ + d1 t1ᵀ + cot φ b bᵀ) / l1²,  H33 = (1 ↔ 3),
//   H13 = H31 = −b bᵀ / (l1 l3 sin φ),  H0j = −(H1j + H3j).
// These equal the angle Hessian of Cirio et al. 2016 eqs. (46)–(49) (P1 P3 = b bᵀ − cos φ t1 t3ᵀ, t1·t3 = −cos φ)
// but avoid cos φ / sin² φ cancellations: only the out-of-plane b bᵀ parts
// carry 1/sin φ, which is the genuine cone singularity of arccos at φ → 0, π.
#pragma once
#include <cmath>

#include <Eigen/Geometry>

#include "models/core/term.h"
#include "models/core/types.h"

namespace wl {

struct CrossingAngle {
  using Vec9 = Eigen::Matrix<double, 9, 1>;
  using Mat9 = Eigen::Matrix<double, 9, 9>;

  // Below this sin φ (or for a zero-length segment) the crossing is degenerate:
  // the direction of ∇φ is undefined and terms write zero force and Jacobian.
  static constexpr double kMinSin = 1e-9;

  double phi = 0.0;
  bool degenerate = true;
  Vec9 grad = Vec9::Zero();  // ∇φ over (x0, x1, x3)

  // Computes φ and ∇φ from local q = (x0, x1, x3); the Hessian only on demand.
  explicit CrossingAngle(const double* q) {
    Eigen::Map<const Vec3> x0(q), x1(q + 3), x3(q + 6);
    const Vec3 e1 = x1 - x0, e3 = x3 - x0;
    l1 = e1.norm();
    l3 = e3.norm();
    if (!(l1 > 0.0) || !(l3 > 0.0)) return;
    d1 = e1 / l1;
    d3 = e3 / l3;
    const Vec3 n = d1.cross(d3);
    sin_phi = n.norm();
    cos_phi = d1.dot(d3);
    phi = std::atan2(sin_phi, cos_phi);  // = arccos(d1·d3), accurate near 0 and π
    if (!(sin_phi > kMinSin)) return;
    degenerate = false;
    b = n / sin_phi;
    t1 = (d3 - cos_phi * d1) / sin_phi;
    t3 = (d1 - cos_phi * d3) / sin_phi;
    grad.segment<3>(3) = -t1 / l1;
    grad.segment<3>(6) = -t3 / l3;
    grad.head<3>() = -(grad.segment<3>(3) + grad.segment<3>(6));
  }

  Mat9 hessian() const {
    Mat9 H = Mat9::Zero();
    if (degenerate) return H;
    const double cot = cos_phi / sin_phi;
    const Mat3 bb = b * b.transpose();
    const Mat3 H11 = (t1 * d1.transpose() + d1 * t1.transpose() + cot * bb) / (l1 * l1);
    const Mat3 H33 = (t3 * d3.transpose() + d3 * t3.transpose() + cot * bb) / (l3 * l3);
    const Mat3 H13 = -bb / (l1 * l3 * sin_phi);
    H.block<3, 3>(3, 3) = H11;
    H.block<3, 3>(6, 6) = H33;
    H.block<3, 3>(3, 6) = H13;
    H.block<3, 3>(6, 3) = H13.transpose();
    // Translation invariance: rows/columns of x0 are minus the sums of the others.
    H.block<3, 3>(0, 3) = -(H11 + H13.transpose());
    H.block<3, 3>(0, 6) = -(H13 + H33);
    H.block<3, 3>(3, 0) = H.block<3, 3>(0, 3).transpose();
    H.block<3, 3>(6, 0) = H.block<3, 3>(0, 6).transpose();
    H.block<3, 3>(0, 0) = H11 + H13 + H13.transpose() + H33;
    return H;
  }

  // For any V(φ): F = −V′ ∇φ, ∂F/∂x = −(V″ ∇φ ∇φᵀ + V′ H) (docs/models.md §3.4.1).
  void write(double dV, double d2V, const ElementOutput& out) const {
    if (degenerate) return;  // outputs arrive zero-filled
    Eigen::Map<Vec9> f(out.force);
    f = -dV * grad;
    if (out.dfdq) {
      Eigen::Map<Mat9> K(out.dfdq);
      K = -(d2V * grad * grad.transpose() + dV * hessian());
    }
  }

  double l1 = 0.0, l3 = 0.0, sin_phi = 0.0, cos_phi = 1.0;
  Vec3 d1 = Vec3::Zero(), d3 = Vec3::Zero(), b = Vec3::Zero(), t1 = Vec3::Zero(), t3 = Vec3::Zero();
};

}  // namespace wl
