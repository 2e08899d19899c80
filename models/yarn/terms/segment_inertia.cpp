#include "models/yarn/terms/segment_inertia.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace wl {
namespace {

using Mat8 = Eigen::Matrix<double, 8, 8>;
using Vec8 = Eigen::Matrix<double, 8, 1>;

// B(a, σ) of docs/models.md §3.1.1 (linear in a and σ).
Mat8 pattern_b(const Vec3& a, double s) {
  Mat8 b = Mat8::Zero();
  b.block<3, 1>(0, 6) = -2 * a;
  b.block<3, 1>(0, 7) = -a;
  b.block<3, 1>(3, 6) = -a;
  b.block<3, 1>(3, 7) = -2 * a;
  b.block<1, 3>(6, 0) = -2 * a.transpose();
  b.block<1, 3>(6, 3) = -a.transpose();
  b.block<1, 3>(7, 0) = -a.transpose();
  b.block<1, 3>(7, 3) = -2 * a.transpose();
  b(6, 6) = 2 * s;
  b(6, 7) = s;
  b(7, 6) = s;
  b(7, 7) = 2 * s;
  return b;
}

// A0 of docs/models.md §3.1.1: the x–x part [2I I; I 2I].
Mat8 pattern_a0() {
  Mat8 a = Mat8::Zero();
  a.block<3, 3>(0, 0) = 2 * Mat3::Identity();
  a.block<3, 3>(0, 3) = Mat3::Identity();
  a.block<3, 3>(3, 0) = Mat3::Identity();
  a.block<3, 3>(3, 3) = 2 * Mat3::Identity();
  return a;
}

// S: q ↦ (d, D) with d = x1 − x0, D = u1 − u0.
Eigen::Matrix<double, 4, 8> selector() {
  Eigen::Matrix<double, 4, 8> s = Eigen::Matrix<double, 4, 8>::Zero();
  s.block<3, 3>(0, 0) = -Mat3::Identity();
  s.block<3, 3>(0, 3) = Mat3::Identity();
  s(3, 6) = -1;
  s(3, 7) = 1;
  return s;
}

}  // namespace

void SegmentInertiaTerm::add(const std::array<int, 8>& stencil, double rho) {
  if (!(rho > 0.0) || !std::isfinite(rho))
    throw std::invalid_argument("SegmentInertiaTerm::add: linear density rho = " + std::to_string(rho) +
                                " kg/m; expected a finite value > 0");
  stencils_.push_back(stencil);
  rho_.push_back(rho);
}

void SegmentInertiaTerm::mass_block(const double* q, double rho, double* m) {
  Eigen::Map<const Vec3> x0(q), x1(q + 3);
  const Vec3 d = x1 - x0;
  const double D = q[7] - q[6];
  // M = ρ/6 [D A0 + B(d, ‖d‖²/D)], docs/models.md §3.1.1
  Eigen::Map<Mat8> out(m);
  out = rho / 6.0 * (D * pattern_a0() + pattern_b(d, d.squaredNorm() / D));
}

// B is linear in (a, s), so δM = ρ/6 [δD A0 + B(δd, δσ)] with δσ = 2d·δd/D − ‖d‖²δD/D².
void SegmentInertiaTerm::mass_directional_derivative(int e, const double* q, const double* dq, double* dm) const {
  const Vec3 d = Eigen::Map<const Vec3>(q + 3) - Eigen::Map<const Vec3>(q);
  const Vec3 dd = Eigen::Map<const Vec3>(dq + 3) - Eigen::Map<const Vec3>(dq);
  const double D = q[7] - q[6], dD = dq[7] - dq[6];
  const double ds = 2.0 * d.dot(dd) / D - d.squaredNorm() * dD / (D * D);
  Eigen::Map<Mat8>(dm) += rho_[e] / 6.0 * (dD * pattern_a0() + pattern_b(dd, ds));
}

double SegmentInertiaTerm::kinetic_energy(const double* q, const double* v, double rho) {
  Eigen::Map<const Vec3> x0(q), x1(q + 3), xd0(v), xd1(v + 3);
  const Vec3 d = x1 - x0;
  const double D = q[7] - q[6];
  const double ud0 = v[6], ud1 = v[7];
  // T = ρ/6 [D σx − dᵀν + ‖d‖² σu / D], docs/models.md §3.1.2
  const Vec3 nu = (2 * ud0 + ud1) * xd0 + (ud0 + 2 * ud1) * xd1;
  const double sx = xd0.squaredNorm() + xd0.dot(xd1) + xd1.squaredNorm();
  const double su = ud0 * ud0 + ud0 * ud1 + ud1 * ud1;
  return rho / 6.0 * (D * sx - d.dot(nu) + d.squaredNorm() * su / D);
}

// With c = ρ/6, N = [∂M/∂q_j q̇]_j (8×8, column j) the generalized force is
//   ∂T/∂q = ½ Nᵀq̇,  Ṁq̇ = N q̇,  so  f = ½Nᵀq̇ − Nq̇,
//   ∂f/∂q̇ = Nᵀ − N − Ṁ   (∂Ṁ/∂q̇_j = ∂M/∂q_j, docs/models.md §3.1.3).
// ∂M/∂d_k = c B(e_k, 2d_k/D), ∂M/∂D = c[A0 − B(0, ‖d‖²/D²)] (docs/models.md §3.1.2).
// Every second derivative of M is c B(0, Σ) with the (d, D) Hessian of ‖d‖²/D,
//   Σ = [2I/D, −2d/D²; −2dᵀ/D², 2‖d‖²/D³],  Σ_q = SᵀΣS,
// and B(0,1)q̇ = (0, 0, a, b) with a = 2u̇0 + u̇1, b = u̇0 + 2u̇1, so
//   ∂f/∂q = c [σu Σ_q − r (Σ_q q̇)ᵀ],  r = (0,…,0, a, b),  σu = u̇0² + u̇0u̇1 + u̇1².
void SegmentInertiaTerm::evaluate(int e, const double* q, const double* v, const ElementOutput& out) const {
  const double c = rho_[e] / 6.0;
  Eigen::Map<const Vec3> x0(q), x1(q + 3), xd0(v), xd1(v + 3);
  Eigen::Map<const Vec8> qd(v);
  const Vec3 d = x1 - x0;
  const double D = q[7] - q[6];
  const double dd = d.squaredNorm();
  const double ud0 = v[6], ud1 = v[7];
  const double a = 2 * ud0 + ud1, b = ud0 + 2 * ud1;
  const Vec3 p0 = 2 * xd0 + xd1, p1 = xd0 + 2 * xd1;

  // Columns of N for d (∂M/∂d_k q̇) and D (∂M/∂D q̇).
  Eigen::Matrix<double, 8, 3> nd;
  nd.topRows<3>() = -c * a * Mat3::Identity();
  nd.middleRows<3>(3) = -c * b * Mat3::Identity();
  nd.row(6) = c * (-p0 + 2 * a / D * d).transpose();
  nd.row(7) = c * (-p1 + 2 * b / D * d).transpose();
  Vec8 nD;
  nD << c * p0, c * p1, -c * dd / (D * D) * a, -c * dd / (D * D) * b;
  Mat8 n;
  n.leftCols<3>() = -nd;
  n.middleCols<3>(3) = nd;
  n.col(6) = -nD;
  n.col(7) = nD;

  VecMap f(out.force);
  f = 0.5 * n.transpose().lazyProduct(qd) - n.lazyProduct(qd);  // lazy: fixed 8×8 products, no GEMV call

  if (out.dfdv) {
    const Vec3 ddot = xd1 - xd0;
    const double Ddot = ud1 - ud0;
    const double beta = 2 * d.dot(ddot) / D - dd * Ddot / (D * D);
    const Mat8 mdot = c * (Ddot * pattern_a0() + pattern_b(ddot, beta));  // docs/models.md §3.1.3
    MatMap(out.dfdv) = n.transpose() - n - mdot;
  }
  if (out.dfdq) {
    Eigen::Matrix4d sigma;
    sigma.topLeftCorner<3, 3>() = 2 / D * Mat3::Identity();
    sigma.topRightCorner<3, 1>() = -2 / (D * D) * d;
    sigma.bottomLeftCorner<1, 3>() = -2 / (D * D) * d.transpose();
    sigma(3, 3) = 2 * dd / (D * D * D);
    const Eigen::Matrix<double, 4, 8> s = selector();
    const Mat8 sq = (s.transpose() * sigma).lazyProduct(s);  // lazy: a fixed 8×8 product, no GEMM call
    const double su = ud0 * ud0 + ud0 * ud1 + ud1 * ud1;
    Vec8 r = Vec8::Zero();
    r(6) = a;
    r(7) = b;
    MatMap(out.dfdq) = c * (su * sq - r * sq.lazyProduct(qd).transpose());
  }
  if (out.mass) mass_block(q, rho_[e], out.mass);
}

}  // namespace wl
