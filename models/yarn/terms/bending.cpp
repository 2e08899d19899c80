#include "models/yarn/terms/bending.h"

#include <cmath>
#include <sstream>
#include <stdexcept>

#include <Eigen/Geometry>

namespace wl {
namespace {

// Below this angle α(θ) and β(θ) use their Taylor series: the truncation error
// is O(θ⁸) ≈ 1e-13, while the closed form of β loses ≈ ε/θ² ≈ 1e-13 here.
constexpr double kSmallAngle = 0.05;

// α = θ/sin θ = 1 + θ²/6 + 7θ⁴/360 + 31θ⁶/15120 + …
double alpha(double t) {
  if (t < kSmallAngle) {
    const double t2 = t * t;
    return 1.0 + t2 * (1.0 / 6.0 + t2 * (7.0 / 360.0 + t2 * (31.0 / 15120.0)));
  }
  return t / std::sin(t);
}

// β = (1 − θ cot θ)/sin²θ = 1/3 + 2θ²/15 + 2θ⁴/63 + 4θ⁶/675 + …
double beta(double t) {
  if (t < kSmallAngle) {
    const double t2 = t * t;
    return 1.0 / 3.0 + t2 * (2.0 / 15.0 + t2 * (2.0 / 63.0 + t2 * (4.0 / 675.0)));
  }
  const double s = std::sin(t);
  return (1.0 - t * std::cos(t) / s) / (s * s);
}

struct Geometry {
  Vec3 e1, e2;    // unit directions of x1−x0 and x0−x2 (both along +u)
  double l1, l2;  // segment lengths
  Vec3 cross;     // e1 × e2, ‖·‖ = sin θ
  double c;       // cos θ = e1·e2
  double theta;
};

Geometry geometry(const double* q) {
  Eigen::Map<const Vec3> x0(q), x1(q + 3), x2(q + 6);
  Geometry g;
  const Vec3 r1 = x1 - x0, r2 = x0 - x2;
  g.l1 = r1.norm();
  g.l2 = r2.norm();
  g.e1 = r1 / g.l1;
  g.e2 = r2 / g.l2;
  g.cross = g.e1.cross(g.e2);
  g.c = g.e1.dot(g.e2);
  g.theta = std::atan2(g.cross.norm(), g.c);  // = arccos(−d_1·d_2), Cirio et al. 2016 eq. (16)
  return g;
}

}  // namespace

void BendingTerm::add(const std::array<int, 11>& stencil, double kb) {
  if (!std::isfinite(kb) || kb < 0.0) {
    std::ostringstream msg;
    msg << "BendingTerm::add: stiffness k_b = " << kb << " N*m^2, expected a finite value >= 0";
    throw std::invalid_argument(msg.str());
  }
  stencils_.push_back(stencil);
  kb_.push_back(kb);
}

double BendingTerm::angle(const Vec3& x0, const Vec3& x1, const Vec3& x2) {
  const double q[9] = {x0[0], x0[1], x0[2], x1[0], x1[1], x1[2], x2[0], x2[1], x2[2]};
  return geometry(q).theta;
}

double BendingTerm::local_energy(const double* q, double kb) {
  const Geometry g = geometry(q);
  return kb * g.theta * g.theta / (q[9] - q[10]);  // V = k_b θ²/(u1−u2), Cirio et al. 2016 eq. (18)
}

void BendingTerm::local_evaluate(const double* q, double kb, double* f_out, double* K_out) {
  const Geometry g = geometry(q);
  const double U = q[9] - q[10];
  const double th = g.theta;
  const double a = alpha(th);

  // ∇c over (x1, x2): ∂c/∂x1 = P_1 e2 / l_1, ∂c/∂x2 = −P_2 e1 / l_2; ∂c/∂x0 = −(sum).
  const Vec3 P1e2 = g.cross.cross(g.e1);  // = e2 − c e1, accurate for small θ
  const Vec3 P2e1 = g.e2.cross(g.cross);  // = e1 − c e2
  const Vec3 gc1 = P1e2 / g.l1;
  const Vec3 gc2 = -P2e1 / g.l2;

  // ∇Φ = Φ'(c)∇c = −2α ∇c;  F_x = −(k_b/U)∇Φ   (Cirio et al. 2016 eqs. (21)–(23))
  const Vec3 gp1 = -2.0 * a * gc1, gp2 = -2.0 * a * gc2, gp0 = -(gp1 + gp2);
  Eigen::Map<Local> f(f_out);
  f.segment<3>(0) = -(kb / U) * gp0;
  f.segment<3>(3) = -(kb / U) * gp1;
  f.segment<3>(6) = -(kb / U) * gp2;
  // F_u1 = −F_u2 = k_b θ²/U²   (Cirio et al. 2016 eqs. (24)–(25); docs/models.md §4.7)
  const double fu1 = kb * th * th / (U * U);
  f[9] = fu1;
  f[10] = -fu1;
  if (!K_out) return;

  // Hessian of c (blocks over x1, x2):
  //   ∇²_11 c = −(c P_1 + P_1e2 e1ᵀ + e1 e2ᵀP_1)/l_1²,  ∇²_22 c likewise (1↔2),
  //   ∇²_12 c = −P_1 P_2 /(l_1 l_2).
  const Mat3 I = Mat3::Identity();
  const Mat3 P1 = I - g.e1 * g.e1.transpose();
  const Mat3 P2 = I - g.e2 * g.e2.transpose();
  const Mat3 Hc11 = -(g.c * P1 + P1e2 * g.e1.transpose() + g.e1 * P1e2.transpose()) / (g.l1 * g.l1);
  const Mat3 Hc22 = -(g.c * P2 + P2e1 * g.e2.transpose() + g.e2 * P2e1.transpose()) / (g.l2 * g.l2);
  const Mat3 Hc12 = -P1 * P2 / (g.l1 * g.l2);

  // ∂F/∂x = −(k_b/U)(Φ''∇c∇cᵀ + Φ'∇²c) = −(k_b/U)(2β ∇c∇cᵀ − 2α ∇²c)   (Cirio et al. 2016 eqs. (28)–(31))
  const double b = beta(th);
  const double s = -kb / U;
  const Mat3 K11 = s * (2.0 * b * gc1 * gc1.transpose() - 2.0 * a * Hc11);
  const Mat3 K22 = s * (2.0 * b * gc2 * gc2.transpose() - 2.0 * a * Hc22);
  const Mat3 K12 = s * (2.0 * b * gc1 * gc2.transpose() - 2.0 * a * Hc12);
  const Mat3 K21 = K12.transpose();
  // Translation invariance (Cirio et al. 2016 eqs. (32)–(33)): x0 rows/columns are minus the sums.
  const Mat3 K10 = -(K11 + K12), K20 = -(K21 + K22);
  const Mat3 K01 = K10.transpose(), K02 = K20.transpose();
  const Mat3 K00 = -(K01 + K02);

  Eigen::Map<LocalMatrix> K(K_out);
  K.block<3, 3>(0, 0) = K00;
  K.block<3, 3>(0, 3) = K01;
  K.block<3, 3>(0, 6) = K02;
  K.block<3, 3>(3, 0) = K10;
  K.block<3, 3>(3, 3) = K11;
  K.block<3, 3>(3, 6) = K12;
  K.block<3, 3>(6, 0) = K20;
  K.block<3, 3>(6, 3) = K21;
  K.block<3, 3>(6, 6) = K22;
  // x–u coupling: ∂F_x/∂u1 = −∂F_x/∂u2 = (k_b/U²)∇Φ, ∂F_u1/∂x = (k_b/U²)∇Φᵀ (Cirio et al. 2016 eqs. (35)–(40))
  const double r = kb / (U * U);
  const Vec3* gp[3] = {&gp0, &gp1, &gp2};
  for (int n = 0; n < 3; ++n) {
    K.block<3, 1>(3 * n, 9) = r * *gp[n];
    K.block<3, 1>(3 * n, 10) = -r * *gp[n];
    K.block<1, 3>(9, 3 * n) = r * gp[n]->transpose();
    K.block<1, 3>(10, 3 * n) = -r * gp[n]->transpose();
  }
  // ∂F_u1/∂u1 = ∂F_u2/∂u2 = −∂F_u1/∂u2 = −2 k_b θ²/U³   (Cirio et al. 2016 eq. (34); docs/models.md §4.9)
  const double kuu = -2.0 * kb * th * th / (U * U * U);
  K(9, 9) = kuu;
  K(10, 10) = kuu;
  K(9, 10) = -kuu;
  K(10, 9) = -kuu;
}

BendingTerm::Local BendingTerm::local_force(const Vec3& x0, const Vec3& x1, const Vec3& x2, double u1, double u2,
                                            double kb) {
  const double q[11] = {x0[0], x0[1], x0[2], x1[0], x1[1], x1[2], x2[0], x2[1], x2[2], u1, u2};
  Local f;
  local_evaluate(q, kb, f.data(), nullptr);
  return f;
}

double BendingTerm::energy(int e, const double* q) const { return local_energy(q, kb_[e]); }

// The published sliding force F_u1 = −F_u2 = k_b θ/U² (docs/published_code.md row 6) replaces rows
// u1, u2: with ∇θ = −∇c/sin θ (zero at θ = 0, where θ has no derivative),
//   ∂F_u1/∂x = (k_b/U²)∇θ,  ∂F_u1/∂u1 = −∂F_u1/∂u2 = −2k_b θ/U³,  F_u2 = −F_u1.
void BendingTerm::evaluate(int e, const double* q, const double*, const ElementOutput& out) const {
  local_evaluate(q, kb_[e], out.force, out.dfdq);
  if (!sliding_theta_) return;
  const Geometry g = geometry(q);
  const double U = q[9] - q[10], kb = kb_[e];
  const double fu1 = kb * g.theta / (U * U);
  out.force[9] = fu1;
  out.force[10] = -fu1;
  if (!out.dfdq) return;
  const double sin_theta = g.cross.norm();
  Eigen::Matrix<double, 9, 1> grad_theta = Eigen::Matrix<double, 9, 1>::Zero();
  if (sin_theta > 0.0) {
    const Vec3 gc1 = g.cross.cross(g.e1) / g.l1, gc2 = -g.e2.cross(g.cross) / g.l2;  // ∇c over x1, x2
    grad_theta.segment<3>(3) = -gc1 / sin_theta;
    grad_theta.segment<3>(6) = -gc2 / sin_theta;
    grad_theta.head<3>() = -(grad_theta.segment<3>(3) + grad_theta.segment<3>(6));
  }
  Eigen::Map<LocalMatrix> K(out.dfdq);
  const double r = kb / (U * U), kuu = -2.0 * kb * g.theta / (U * U * U);
  K.block<1, 9>(9, 0) = r * grad_theta.transpose();
  K.block<1, 9>(10, 0) = -r * grad_theta.transpose();
  K(9, 9) = kuu;
  K(10, 10) = kuu;
  K(9, 10) = -kuu;
  K(10, 9) = -kuu;
}

}  // namespace wl
