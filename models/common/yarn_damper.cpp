#include "models/common/yarn_damper.h"

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

namespace wl {

void YarnDamperTerm::add(const std::array<int, 6>& stencil, double c) {
  if (!(std::isfinite(c) && c >= 0.0))
    throw std::invalid_argument("YarnDamperTerm::add: c = " + std::to_string(c) +
                                " N·s/m; expected a finite value >= 0");
  stencils_.push_back(stencil);
  c_.push_back(c);
}

double yarn_damper_coefficient(double viscosity_Pa_s, double radius_m, double spacing_m) {
  return viscosity_Pa_s * std::numbers::pi * radius_m * radius_m / spacing_m;
}

void YarnDamperTerm::evaluate(int e, const double* q, const double* v, const ElementOutput& out) const {
  const Eigen::Map<const Vec3> xa(q), xb(q + 3), va(v), vb(v + 3);
  const Vec3 dx = xb - xa;
  const double len = dx.norm();
  VecMap f(out.force);
  if (len <= 0.0) {
    f.setZero();
    return;
  }
  const double c = c_[e];
  const Vec3 d = dx / len, dv = vb - va;
  const double rate = d.dot(dv);
  const Vec3 fb = -c * rate * d;
  f.head<3>() = -fb;
  f.tail<3>() = fb;
  // Blocks of ∂F/∂(x_a, x_b) and ∂F/∂(ẋ_a, ẋ_b): ±B with B = ∂F_b/∂(·)_b.
  auto fill = [](double* out6, const Mat3& b) {
    MatMap m(out6);
    m.block<3, 3>(0, 0) = b;
    m.block<3, 3>(0, 3) = -b;
    m.block<3, 3>(3, 0) = -b;
    m.block<3, 3>(3, 3) = b;
  };
  if (out.dfdv) fill(out.dfdv, -c * d * d.transpose());
  if (out.dfdq) {
    const Mat3 p = Mat3::Identity() - d * d.transpose();
    fill(out.dfdq, -(c / len) * (rate * p + d * (p * dv).transpose()));
  }
}

}  // namespace wl
