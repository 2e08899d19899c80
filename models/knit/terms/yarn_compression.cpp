#include "models/knit/terms/yarn_compression.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "models/knit/terms/autodiff_jacobian.h"

namespace wl {
namespace {

template <typename T>
T clamp01(const T& x) {
  if (x < T(0.0)) return T(0.0);
  if (x > T(1.0)) return T(1.0);
  return x;
}

// d and, when `grad` is set, ∇d (12) of a local state in any scalar type
// (docs/models.md §11.6): the closest points of two segments, clamped to the
// segments (the parallel case takes s = 0).
template <typename T>
T segment_distance(const Eigen::Matrix<T, 12, 1>& q, Eigen::Matrix<T, 12, 1>* grad) {
  using V3 = Eigen::Matrix<T, 3, 1>;
  const V3 x0 = q.template segment<3>(0), y0 = q.template segment<3>(6);
  const V3 a = q.template segment<3>(3) - x0, b = q.template segment<3>(9) - y0, r = x0 - y0;
  const T aa = a.dot(a), ab = a.dot(b), bb = b.dot(b), ar = a.dot(r), br = b.dot(r);
  const T den = aa * bb - ab * ab;
  T s = den > T(1e-12) * aa * bb ? clamp01(T((ab * br - bb * ar) / den)) : T(0.0);
  T t = (ab * s + br) / bb;
  if (t < T(0.0)) {
    t = T(0.0);
    s = clamp01(T(-ar / aa));
  } else if (t > T(1.0)) {
    t = T(1.0);
    s = clamp01(T((ab - ar) / aa));
  }
  const V3 gap = r + s * a - t * b;
  const T d = gap.norm();
  if (grad && d > T(0.0)) {
    const V3 n = gap / d;
    grad->template segment<3>(0) = (T(1.0) - s) * n;
    grad->template segment<3>(3) = s * n;
    grad->template segment<3>(6) = -(T(1.0) - t) * n;
    grad->template segment<3>(9) = -t * n;
  } else if (grad) grad->setZero();
  return d;
}

}  // namespace

void YarnCompressionTerm::add(const std::array<int, 12>& stencil, double kappa, double contact_distance) {
  if (!(std::isfinite(kappa) && kappa >= 0.0 && std::isfinite(contact_distance) && contact_distance > 0.0))
    throw std::invalid_argument("YarnCompressionTerm::add: expected κ ≥ 0 and a contact distance > 0");
  stencils_.push_back(stencil);
  kappa_.push_back(kappa);
  contact_distance_.push_back(contact_distance);
}

double YarnCompressionTerm::distance(const double* q) {
  return segment_distance<double>(Eigen::Map<const Eigen::Matrix<double, 12, 1>>(q), nullptr);
}

double YarnCompressionTerm::energy(int e, const double* q) const {
  const double gap = std::max(contact_distance_[e] - distance(q), 0.0);
  return 0.5 * kappa_[e] * gap * gap;  // V = ½ κ (D − d)²
}

void YarnCompressionTerm::evaluate(int e, const double* q, const double*, const ElementOutput& out) const {
  const double D = contact_distance_[e], k = kappa_[e];
  if (distance(q) >= D) return;  // inactive: no force, no stiffness
  Eigen::Map<Eigen::Matrix<double, 12, 1>> f(out.force);
  if (!out.dfdq) {
    Eigen::Matrix<double, 12, 1> g;
    const double d = segment_distance<double>(Eigen::Map<const Eigen::Matrix<double, 12, 1>>(q), &g);
    f = k * (D - d) * g;  // F = κ (D − d) ∇d
    return;
  }
  using AD = AutoDiff<12>;
  force_and_jacobian_by_autodiff<12>(
      q,
      [&](const Eigen::Matrix<AD, 12, 1>& x) {
        Eigen::Matrix<AD, 12, 1> g;
        const AD d = segment_distance<AD>(x, &g);
        return Eigen::Matrix<AD, 12, 1>(k * (D - d) * g);
      },
      out.force, out.dfdq);
}

}  // namespace wl
