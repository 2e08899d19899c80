#include "models/knit/terms/stitch_roll.h"

#include <Eigen/Geometry>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "models/knit/terms/autodiff_jacobian.h"

namespace wl {
namespace {

// ψ and ∇ψ (12) of a local state, in any scalar type (docs/models.md §11.4).
template <typename T>
T roll_angle_and_gradient(const Eigen::Matrix<T, 12, 1>& q, Eigen::Matrix<T, 12, 1>* grad) {
  using V3 = Eigen::Matrix<T, 3, 1>;
  const V3 x0 = q.template segment<3>(0), x1 = q.template segment<3>(3), x3 = q.template segment<3>(6),
           x5 = q.template segment<3>(9);
  const V3 va = (x5 - x1).cross(x0 - x1), vb = (x0 - x1).cross(x3 - x1);
  const T la = va.norm(), lb = vb.norm();
  const V3 na = va / la, nb = vb / lb, e = (x1 - x0) / (x1 - x0).norm();
  const T psi = atan2(e.dot(na.cross(nb)), na.dot(nb));
  if (!grad) return psi;
  const std::array<V3, 4> xa{x5 - x1, x0 - x5, V3::Zero(), x1 - x0};  // entries for x0, x1, x3, x5
  const std::array<V3, 4> xb{x1 - x3, x3 - x0, x0 - x1, V3::Zero()};
  for (int i = 0; i < 4; ++i) grad->template segment<3>(3 * i) = (e.dot(xb[i]) / lb) * nb - (e.dot(xa[i]) / la) * na;
  return psi;
}

// ψ − ψ̄ taken into (−π, π]: the energy is periodic in the roll (docs/models.md §11.4).
double wrapped(double psi, double rest) { return std::remainder(psi - rest, 2.0 * std::numbers::pi); }

}  // namespace

void StitchRollTerm::add(const std::array<int, 12>& stencil, double kt, double rest_length, double rest_angle) {
  if (!(std::isfinite(kt) && kt >= 0.0 && std::isfinite(rest_length) && rest_length > 0.0 && std::isfinite(rest_angle)))
    throw std::invalid_argument("StitchRollTerm::add: expected k_t ≥ 0, a rest length > 0 and a finite rest angle");
  stencils_.push_back(stencil);
  kt_.push_back(kt);
  rest_length_.push_back(rest_length);
  rest_angle_.push_back(rest_angle);
}

double StitchRollTerm::angle(const double* q) {
  return roll_angle_and_gradient<double>(Eigen::Map<const Eigen::Matrix<double, 12, 1>>(q), nullptr);
}

double StitchRollTerm::energy(int e, const double* q) const {
  const double d = wrapped(angle(q), rest_angle_[e]);
  return 0.5 * kt_[e] * rest_length_[e] * d * d;  // V = ½ k_t L (ψ − ψ̄)²
}

void StitchRollTerm::evaluate(int e, const double* q, const double*, const ElementOutput& out) const {
  const double c = kt_[e] * rest_length_[e];
  Eigen::Map<Eigen::Matrix<double, 12, 1>> f(out.force);
  if (!out.dfdq) {
    Eigen::Matrix<double, 12, 1> g;
    const double psi = roll_angle_and_gradient<double>(Eigen::Map<const Eigen::Matrix<double, 12, 1>>(q), &g);
    f = -c * wrapped(psi, rest_angle_[e]) * g;  // F = −k_t L (ψ − ψ̄) ∇ψ
    return;
  }
  using AD = AutoDiff<12>;
  force_and_jacobian_by_autodiff<12>(
      q,
      [&](const Eigen::Matrix<AD, 12, 1>& x) {
        Eigen::Matrix<AD, 12, 1> g;
        const AD psi = roll_angle_and_gradient<AD>(x, &g);
        const AD d = psi - (psi.value() - wrapped(psi.value(), rest_angle_[e]));  // ψ − ψ̄ wrapped, ∂d/∂q = ∇ψ
        return Eigen::Matrix<AD, 12, 1>(-c * d * g);
      },
      out.force, out.dfdq);
}

}  // namespace wl
