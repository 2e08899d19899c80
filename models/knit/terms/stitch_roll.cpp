#include "models/knit/terms/stitch_roll.h"

#include <Eigen/Geometry>
#include <cmath>
#include <stdexcept>

#include "models/knit/terms/autodiff_jacobian.h"

namespace wl {
namespace {

template <typename T>
using V3 = Eigen::Matrix<T, 3, 1>;
template <typename T>
using V12 = Eigen::Matrix<T, 12, 1>;

// ψ and ∇ψ (12) of a local state, in any scalar type (docs/models.md §11.4).
template <typename T>
T roll_angle_and_gradient(const V12<T>& q, V12<T>* grad) {
  const V3<T> x0 = q.template segment<3>(0), x1 = q.template segment<3>(3), x3 = q.template segment<3>(6),
              x5 = q.template segment<3>(9);
  const V3<T> va = (x5 - x1).cross(x0 - x1), vb = (x0 - x1).cross(x3 - x1);
  const T la = va.norm(), lb = vb.norm();
  const V3<T> na = va / la, nb = vb / lb, e = (x1 - x0) / (x1 - x0).norm();
  const T psi = atan2(e.dot(na.cross(nb)), na.dot(nb));
  if (!grad) return psi;
  const std::array<V3<T>, 4> xa{x5 - x1, x0 - x5, V3<T>::Zero(), x1 - x0};  // entries for x0, x1, x3, x5
  const std::array<V3<T>, 4> xb{x1 - x3, x3 - x0, x0 - x1, V3<T>::Zero()};
  for (int i = 0; i < 4; ++i) grad->template segment<3>(3 * i) = (e.dot(xb[i]) / lb) * nb - (e.dot(xa[i]) / la) * na;
  return psi;
}

// sin²α of the angle α at x1 between p = x_p − x1 and r = x0 − x1, and its
// gradient with respect to x_p and x0 (x1's is minus their sum):
// sin²α = ‖p̂ × r̂‖² (not 1 − c², which loses it to rounding where the triangle
// degenerates and ∇ψ grows as 1/‖v‖), c = p̂·r̂, ∂sin²α/∂p = −2c(r̂ − c p̂)/‖p‖.
template <typename T>
T sine_squared(const V3<T>& p, const V3<T>& r, V3<T>& dp, V3<T>& dr) {
  const T lp = p.norm(), lr = r.norm();
  const V3<T> ph = p / lp, rh = r / lr;
  const T c = ph.dot(rh);
  dp = T(-2.0) * c * (rh - c * ph) / lp;
  dr = T(-2.0) * c * (ph - c * rh) / lr;
  return ph.cross(rh).squaredNorm();
}

// S = sin²α_a sin²α_b and ∇S (12) (docs/models.md §11.4.1).
template <typename T>
T opening_and_gradient(const V12<T>& q, V12<T>* grad) {
  const V3<T> x0 = q.template segment<3>(0), x1 = q.template segment<3>(3), x3 = q.template segment<3>(6),
              x5 = q.template segment<3>(9);
  V3<T> da5, da0, db3, db0;
  const T sa = sine_squared<T>(x5 - x1, x0 - x1, da5, da0), sb = sine_squared<T>(x3 - x1, x0 - x1, db3, db0);
  if (grad) {
    grad->template segment<3>(0) = sb * da0 + sa * db0;
    grad->template segment<3>(3) = -sb * (da5 + da0) - sa * (db3 + db0);
    grad->template segment<3>(6) = sa * db3;
    grad->template segment<3>(9) = sb * da5;
  }
  return sa * sb;
}

}  // namespace

void StitchRollTerm::add(const std::array<int, 12>& stencil, double kt, double rest_length, double rest_angle,
                         double rest_opening) {
  if (!(std::isfinite(kt) && kt >= 0.0 && std::isfinite(rest_length) && rest_length > 0.0 &&
        std::isfinite(rest_angle) && rest_opening > 0.0 && rest_opening <= 1.0))
    throw std::invalid_argument(
        "StitchRollTerm::add: expected k_t ≥ 0, a rest length > 0, a finite rest angle and a rest opening in (0, 1] "
        "(a rest triangle degenerates)");
  stencils_.push_back(stencil);
  kt_.push_back(kt);
  rest_length_.push_back(rest_length);
  rest_angle_.push_back(rest_angle);
  rest_opening_.push_back(rest_opening);
}

double StitchRollTerm::angle(const double* q) { return roll_angle_and_gradient<double>(V12<double>::Map(q), nullptr); }

double StitchRollTerm::opening(const double* q) { return opening_and_gradient<double>(V12<double>::Map(q), nullptr); }

double StitchRollTerm::energy(int e, const double* q) const {
  const double s = opening(q);
  if (!(s > 0.0)) return 0.0;  // a degenerate triangle: V → 0
  // V = k_t L (S/S̄)(1 − cos(ψ − ψ̄))
  return kt_[e] * rest_length_[e] * (s / rest_opening_[e]) * (1.0 - std::cos(angle(q) - rest_angle_[e]));
}

void StitchRollTerm::evaluate(int e, const double* q, const double*, const ElementOutput& out) const {
  if (!(opening(q) > 0.0)) return;  // a degenerate triangle: F → 0 (and ψ undefined)
  const double c = kt_[e] * rest_length_[e] / rest_opening_[e], rest = rest_angle_[e];
  // F = −k_t L/S̄ ((1 − cos(ψ − ψ̄)) ∇S + S sin(ψ − ψ̄) ∇ψ)
  auto force = [&]<typename T>(const V12<T>& x) {
    using std::cos, std::sin;
    V12<T> gpsi, gs;
    const T psi = roll_angle_and_gradient<T>(x, &gpsi);
    const T s = opening_and_gradient<T>(x, &gs);
    return V12<T>(-c * ((T(1.0) - cos(psi - rest)) * gs + s * sin(psi - rest) * gpsi));
  };
  if (!out.dfdq) {
    V12<double>::Map(out.force) = force(V12<double>(V12<double>::Map(q)));
    return;
  }
  force_and_jacobian_by_autodiff<12>(q, force, out.force, out.dfdq);
}

}  // namespace wl
