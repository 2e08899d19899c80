#include "models/common/self_contact_pair.h"

#include <cmath>
#include <sstream>
#include <stdexcept>

#include "models/common/obstacle_barrier.h"
#include "models/knit/terms/autodiff_jacobian.h"

namespace wl {

std::array<Vec3, 4> pair_nodes(const double* q) {
  std::array<Vec3, 4> x;
  for (int i = 0; i < 4; ++i) x[i] = Vec3(q[3 * i], q[3 * i + 1], q[3 * i + 2]);
  return x;
}

SelfContactPairTerm::SelfContactPairTerm(double dhat, double kappa, double contact_distance)
    : dhat_(dhat), kappa_(kappa), contact_distance_(contact_distance) {
  if (!(dhat > 0.0 && std::isfinite(dhat)) || !(kappa > 0.0 && std::isfinite(kappa)) ||
      !(contact_distance >= 0.0 && std::isfinite(contact_distance))) {
    std::ostringstream msg;
    msg << "SelfContactPairTerm: activation distance " << dhat << " m, stiffness " << kappa
        << " N/m and contact distance " << contact_distance << " m; expected finite values > 0 (≥ 0 for the last)";
    throw std::invalid_argument(msg.str());
  }
}

void SelfContactPairTerm::clear() {
  stencils_.clear();
  kind_.clear();
}

void SelfContactPairTerm::add(const std::array<int, 12>& stencil, PairKind kind) {
  stencils_.push_back(stencil);
  kind_.push_back(kind);
}

double SelfContactPairTerm::energy(int e, const double* q) const {
  const double d = closest_support(kind_[e], pair_nodes(q)).distance;
  return kappa_ * contact_barrier(d - contact_distance_, dhat_).b;
}

// F = −κ b'(g) λᵢ r/d, g = d − D (docs/models.md §3.11.7); the Jacobian by AD
// of F with the support fixed, b'(g) carried as b'(g₀) + b''(g₀)·δd.
void SelfContactPairTerm::evaluate(int e, const double* q, const double*, const ElementOutput& out) const {
  const ClosestPoints cp = closest_support(kind_[e], pair_nodes(q));
  const double gap = cp.distance - contact_distance_;
  if (!(gap < dhat_) || !(cp.distance > 0.0)) return;
  const BarrierValue b = contact_barrier(gap, dhat_);
  const double kappa = kappa_;
  auto force = [&](const auto& x) {
    using T = typename std::decay_t<decltype(x)>::Scalar;
    std::array<Point3<T>, 4> p;
    for (int i = 0; i < 4; ++i) p[i] = x.template segment<3>(3 * i);
    const std::array<T, 4> w = support_weights<T>(p, cp.support);
    const Point3<T> r = w[0] * p[0] + w[1] * p[1] + w[2] * p[2] + w[3] * p[3];
    using std::sqrt;
    const T d = sqrt(r.squaredNorm());
    const T db = T(b.db) + b.d2b * (d - cp.distance);  // b'(g) to first order about g₀
    Eigen::Matrix<T, 12, 1> f;
    for (int i = 0; i < 4; ++i) f.template segment<3>(3 * i) = (-kappa * db * w[i] / d) * r;
    return f;
  };
  if (!out.dfdq) {
    VecMap(out.force) = force(Eigen::Map<const LVec>(q));
    return;
  }
  force_and_jacobian_by_autodiff<12>(q, force, out.force, out.dfdq);
}

}  // namespace wl
