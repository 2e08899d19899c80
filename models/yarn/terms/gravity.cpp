#include "models/yarn/terms/gravity.h"

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace wl {

GravityTerm::GravityTerm(const Vec3& g_m_per_s2) : g_(g_m_per_s2) {
  if (!g_.allFinite()) {
    std::ostringstream msg;
    msg << "GravityTerm: gravity = (" << g_.transpose() << ") m/s^2; expected finite components";
    throw std::invalid_argument(msg.str());
  }
}

void GravityTerm::add(const std::array<int, 8>& stencil, double rho) {
  if (!(rho > 0.0) || !std::isfinite(rho))
    throw std::invalid_argument("GravityTerm::add: linear density rho = " + std::to_string(rho) +
                                " kg/m; expected a finite value > 0");
  stencils_.push_back(stencil);
  rho_.push_back(rho);
}

// V = −ρ Δu gᵀ(x0 + x1)/2, docs/models.md §3.8 with g the (downward) acceleration
double GravityTerm::energy(int e, const double* q) const {
  Eigen::Map<const Vec3> x0(q), x1(q + 3);
  return -rho_[e] * (q[7] - q[6]) * g_.dot(x0 + x1) / 2;
}

// F_x0 = F_x1 = ½ρΔu g,  F_u1 = −F_u0 = ½ρ gᵀ(x0 + x1);
// ∂F_x/∂u1 = −∂F_x/∂u0 = ½ρg, ∂F_u1/∂x = −∂F_u0/∂x = ½ρgᵀ (symmetric Jacobian).
void GravityTerm::evaluate(int e, const double* q, const double*, const ElementOutput& out) const {
  Eigen::Map<const Vec3> x0(q), x1(q + 3);
  const double rho = rho_[e];
  const double du = q[7] - q[6];
  VecMap f(out.force);
  f.segment<3>(0) = 0.5 * rho * du * g_;
  f.segment<3>(3) = 0.5 * rho * du * g_;
  const double fu = 0.5 * rho * g_.dot(x0 + x1);
  f(6) = -fu;
  f(7) = fu;
  if (out.dfdq) {
    MatMap k(out.dfdq);
    k.setZero();
    const Vec3 hg = 0.5 * rho * g_;
    for (int b : {0, 3}) {
      k.block<3, 1>(b, 6) = -hg;              // ∂F_x/∂u0
      k.block<3, 1>(b, 7) = hg;               // ∂F_x/∂u1
      k.block<1, 3>(6, b) = -hg.transpose();  // ∂F_u0/∂x
      k.block<1, 3>(7, b) = hg.transpose();   // ∂F_u1/∂x
    }
  }
}

}  // namespace wl
