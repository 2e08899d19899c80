#include "models/yarn/terms/stretch.h"

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace wl {

void StretchTerm::add(const std::array<int, 8>& stencil, double ks) {
  if (!std::isfinite(ks) || ks < 0.0) {
    std::ostringstream msg;
    msg << "StretchTerm::add: stiffness k_s = " << ks << " N, expected a finite value >= 0";
    throw std::invalid_argument(msg.str());
  }
  stencils_.push_back(stencil);
  ks_.push_back(ks);
}

double StretchTerm::local_energy(const double* q, double ks) {
  Eigen::Map<const Vec3> x0(q), x1(q + 3);
  const double du = q[7] - q[6];
  const double wn = (x1 - x0).norm() / du;
  return 0.5 * ks * du * (wn - 1.0) * (wn - 1.0);  // V = ½ k_s Δu (‖w‖−1)², Cirio et al. 2016 eq. (9)
}

void StretchTerm::local_evaluate(const double* q, double ks, double* f_out, double* K_out) {
  Eigen::Map<const Vec3> x0(q), x1(q + 3);
  const double du = q[7] - q[6];
  const Vec3 e = x1 - x0;
  const double l = e.norm();
  const Vec3 d = e / l;   // d_1, Cirio et al. 2016 eq. (4)
  const Vec3 w = e / du;  // w, ‖w‖ = l/Δu
  const double wn = l / du;

  Eigen::Map<Local> f(f_out);
  // F_x1 = −F_x0 = −k_s(‖w‖−1) d_1;  F_u1 = −F_u0 = ½ k_s (‖w‖²−1)   (Cirio et al. 2016 eqs. (10)–(11))
  const Vec3 fx1 = -ks * (wn - 1.0) * d;
  const double fu1 = 0.5 * ks * (wn * wn - 1.0);
  f.segment<3>(0) = -fx1;
  f.segment<3>(3) = fx1;
  f[6] = -fu1;
  f[7] = fu1;
  if (!K_out) return;

  Eigen::Map<LocalMatrix> K(K_out);
  // ∂F_x1/∂x1 = k_s (P_1/l_1 − I/Δu)   (Cirio et al. 2016 eq. (12))
  const Mat3 Kxx = ks * ((Mat3::Identity() - d * d.transpose()) / l - Mat3::Identity() / du);
  // ∂F_x1/∂u1 = k_s w/Δu   (Cirio et al. 2016 eq. (14); docs/models.md §4.5)
  const Vec3 Kxu = ks * w / du;
  // ∂F_u1/∂u1 = −k_s ‖w‖²/Δu   (Cirio et al. 2016 eq. (13))
  const double Kuu = -ks * wn * wn / du;
  K.block<3, 3>(0, 0) = Kxx;
  K.block<3, 3>(3, 3) = Kxx;
  K.block<3, 3>(0, 3) = -Kxx;
  K.block<3, 3>(3, 0) = -Kxx;
  // x–u blocks: the pattern (+,−;−,+) over (x0,x1)×(u0,u1) with ∂F_x1/∂u1 = +Kxu.
  K.block<3, 1>(0, 6) = Kxu;   // ∂F_x0/∂u0
  K.block<3, 1>(0, 7) = -Kxu;  // ∂F_x0/∂u1
  K.block<3, 1>(3, 6) = -Kxu;  // ∂F_x1/∂u0
  K.block<3, 1>(3, 7) = Kxu;   // ∂F_x1/∂u1
  // u–x blocks are the transposes: ∂F_u1/∂x1 = k_s wᵀ/Δu   (Cirio et al. 2016 eq. (15))
  K.block<1, 3>(6, 0) = Kxu.transpose();
  K.block<1, 3>(6, 3) = -Kxu.transpose();
  K.block<1, 3>(7, 0) = -Kxu.transpose();
  K.block<1, 3>(7, 3) = Kxu.transpose();
  K(6, 6) = Kuu;
  K(7, 7) = Kuu;
  K(6, 7) = -Kuu;
  K(7, 6) = -Kuu;
}

StretchTerm::Local StretchTerm::local_force(const Vec3& x0, const Vec3& x1, double u0, double u1, double ks) {
  double q[8] = {x0[0], x0[1], x0[2], x1[0], x1[1], x1[2], u0, u1};
  Local f;
  local_evaluate(q, ks, f.data(), nullptr);
  return f;
}

double StretchTerm::energy(int e, const double* q) const { return local_energy(q, ks_[e]); }

void StretchTerm::evaluate(int e, const double* q, const double*, const ElementOutput& out) const {
  local_evaluate(q, ks_[e], out.force, out.dfdq);
}

}  // namespace wl
