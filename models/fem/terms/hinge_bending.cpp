#include "models/fem/terms/hinge_bending.h"

#include <cmath>

#include "models/fem/fem_material.h"

namespace wl {
namespace {

using J312 = Eigen::Matrix<double, 3, 12>;
using R12 = Eigen::Matrix<double, 1, 12>;

}  // namespace

void HingeBendingTerm::add(const std::array<int, 12>& stencil, const Vec2& edge_uv, double area_sum, double theta0) {
  stencils_.push_back(stencil);
  const double scale = edge_uv.squaredNorm() / area_sum;
  coeff_.push_back(edge_stiffness(edge_uv) * scale);
  std::array<double, 3> s = stiffness_shares(edge_uv.normalized());
  for (double& x : s) x *= scale;
  shares_.push_back(s);
  theta0_.push_back(theta0);
}

std::array<double, 3> HingeBendingTerm::stiffness_shares(const Vec2& d) const {
  const double uu = d.x() * d.x(), vv = d.y() * d.y();
  if (k_diag_ <= 0.0) return {vv, uu, 0.0};
  const double cross = 4 * uu * vv;  // 1 at 45°, 0 along u and v
  return {vv - 0.5 * cross, uu - 0.5 * cross, cross};
}

double HingeBendingTerm::edge_stiffness(const Vec2& edge_uv) const {
  const Vec2 d = edge_uv.normalized();
  if (k_diag_ <= 0.0) return k_warp_ * d.y() * d.y() + k_weft_ * d.x() * d.x();
  const std::array<double, 3> s = stiffness_shares(d);
  return k_warp_ * s[0] + k_weft_ * s[1] + k_diag_ * s[2];
}

double HingeBendingTerm::dihedral_angle(const double* q) {
  Eigen::Map<const Vec3> x0(q), x1(q + 3), x2(q + 6), x3(q + 9);
  const Vec3 e = x1 - x0;
  const Vec3 n1 = e.cross(x2 - x0), n2 = (x3 - x0).cross(e);
  const double en = e.norm();
  if (en == 0.0) return 0.0;
  return std::atan2(n1.cross(n2).dot(e) / en, n1.dot(n2));
}

double HingeBendingTerm::energy(int e, const double* q) const {
  const double d = dihedral_angle(q) - theta0_[e];
  return 0.5 * coeff_[e] * d * d;
}

bool HingeBendingTerm::dihedral_derivatives(const double* q, double* theta, Vec12* grad, Mat12* hess) {
  Eigen::Map<const Vec3> x0(q), x1(q + 3), x2(q + 6), x3(q + 9);
  const Vec3 e = x1 - x0, a = x2 - x0, b = x3 - x0;
  const Vec3 n1 = e.cross(a), n2 = b.cross(e);
  const double ee = e.squaredNorm(), q1 = n1.squaredNorm(), q2 = n2.squaredNorm();
  const double scale = ee + a.squaredNorm() + b.squaredNorm();
  // A collapsed edge or wing has no defined angle (never met by a sane mesh).
  if (ee <= 1e-24 * scale || q1 <= 1e-24 * scale * scale || q2 <= 1e-24 * scale * scale) return false;
  const double E = std::sqrt(ee);
  *theta = std::atan2(n1.cross(n2).dot(e) / E, n1.dot(n2));
  const double t2 = a.dot(e) / ee, t3 = b.dot(e) / ee;
  const Vec3 g2 = -E / q1 * n1, g3 = -E / q2 * n2;
  *grad << -(1 - t2) * g2 - (1 - t3) * g3, -t2 * g2 - t3 * g3, g2, g3;
  if (!hess) return true;

  // Jacobians (3×12) of the intermediate vectors; rows of scalars (1×12).
  const Mat3 I = Mat3::Identity();
  J312 Je = J312::Zero(), Ja = J312::Zero(), Jb = J312::Zero();
  Je.block<3, 3>(0, 0) = -I;
  Je.block<3, 3>(0, 3) = I;
  Ja.block<3, 3>(0, 0) = -I;
  Ja.block<3, 3>(0, 6) = I;
  Jb.block<3, 3>(0, 0) = -I;
  Jb.block<3, 3>(0, 9) = I;
  const J312 Jn1 = -cross_matrix(a) * Je + cross_matrix(e) * Ja;  // d(e×a)
  const J312 Jn2 = -cross_matrix(e) * Jb + cross_matrix(b) * Je;  // d(b×e)
  const R12 dE = (e / E).transpose() * Je;
  const R12 dq1 = 2.0 * n1.transpose() * Jn1, dq2 = 2.0 * n2.transpose() * Jn2;
  // g = −E n/q:  dg = −(n dE + E dn − E n dq/q)/q
  const J312 Jg2 = -(n1 * dE + E * Jn1 - (E / q1) * n1 * dq1) / q1;
  const J312 Jg3 = -(n2 * dE + E * Jn2 - (E / q2) * n2 * dq2) / q2;
  // t = (a·e)/E²:  dt = (eᵀda + aᵀde)/E² − 2t dE/E
  const R12 dt2 = (e.transpose() * Ja + a.transpose() * Je) / ee - 2.0 * t2 / E * dE;
  const R12 dt3 = (e.transpose() * Jb + b.transpose() * Je) / ee - 2.0 * t3 / E * dE;
  Mat12 H;
  H.middleRows<3>(0) = g2 * dt2 - (1 - t2) * Jg2 + g3 * dt3 - (1 - t3) * Jg3;
  H.middleRows<3>(3) = -g2 * dt2 - t2 * Jg2 - g3 * dt3 - t3 * Jg3;
  H.middleRows<3>(6) = Jg2;
  H.middleRows<3>(9) = Jg3;
  *hess = 0.5 * (H + H.transpose());
  return true;
}

void HingeBendingTerm::evaluate(int el, const double* q, const double*, const ElementOutput& out) const {
  double theta;
  Vec12 grad;
  Mat12 hess;
  if (!dihedral_derivatives(q, &theta, &grad, out.dfdq ? &hess : nullptr)) return;  // no angle: no force
  const double c = coeff_[el], d = theta - theta0_[el];
  VecMap(out.force) = -c * d * grad;
  if (out.dfdq) MatMap(out.dfdq) = -c * (grad * grad.transpose() + d * hess);
}

std::vector<std::string> HingeBendingTerm::parameter_keys() const {
  if (k_diag_ > 0.0) return {kFemWarpBending, kFemWeftBending, kFemDiagonalBending};
  return {kFemWarpBending, kFemWeftBending};
}

void HingeBendingTerm::parameter_derivative(int el, int k, const double* q, const double*, double* dfdp) const {
  // f = −coeff·(θ − θ₀)∇θ with coeff linear in each stiffness: evaluate and scale by ∂coeff/∂k / coeff.
  double f[12] = {};
  const double c = coeff_[el];
  if (c == 0.0) return;
  evaluate(el, q, nullptr, ElementOutput{f});
  const double share = shares_[el][k] / c;
  for (int a = 0; a < 12; ++a) dfdp[a] += share * f[a];
}

}  // namespace wl
