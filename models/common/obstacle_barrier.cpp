#include "models/common/obstacle_barrier.h"

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace wl {

// b = −(d − d̂)² ln(d/d̂), b' = −2(d − d̂) ln(d/d̂) − (d − d̂)²/d,
// b'' = −2 ln(d/d̂) − 4(d − d̂)/d + (d − d̂)²/d²   (docs/models.md §3.11.2)
BarrierValue contact_barrier(double d, double dhat) {
  if (d >= dhat) return {};
  const double floor = 1e-9 * dhat;
  const double s = std::max(d, floor), r = s - dhat, l = std::log(s / dhat);
  BarrierValue v{-r * r * l, -2.0 * r * l - r * r / s, -2.0 * l - 4.0 * r / s + r * r / (s * s)};
  if (d < floor) {  // second-order continuation below d_f
    const double x = d - floor;
    v = {v.b + v.db * x + 0.5 * v.d2b * x * x, v.db + v.d2b * x, v.d2b};
  }
  return v;
}

ObstacleBarrierTerm::ObstacleBarrierTerm(std::shared_ptr<const std::vector<Obstacle>> obstacles, double dhat,
                                         double kappa)
    : obstacles_(std::move(obstacles)), dhat_(dhat), kappa_(kappa) {
  if (!(dhat > 0.0 && std::isfinite(dhat)) || !(kappa > 0.0 && std::isfinite(kappa))) {
    std::ostringstream msg;
    msg << "ObstacleBarrierTerm: activation distance " << dhat << " m and stiffness " << kappa
        << " N/m; expected finite values > 0";
    throw std::invalid_argument(msg.str());
  }
}

void ObstacleBarrierTerm::add(const std::array<int, 3>& stencil, int node, int obstacle) {
  stencils_.push_back(stencil);
  node_.push_back(node);
  obstacle_.push_back(obstacle);
}

double ObstacleBarrierTerm::energy(int e, const double* q) const {
  const double d = obstacle(e).signed_distance(Eigen::Map<const Vec3>(q), t_);
  return kappa_ * contact_barrier(d, dhat_).b;
}

void ObstacleBarrierTerm::evaluate(int e, const double* q, const double*, const ElementOutput& out) const {
  Vec3 g;
  Mat3 h;
  const double d = obstacle(e).signed_distance(Eigen::Map<const Vec3>(q), t_, &g, out.dfdq ? &h : nullptr);
  if (d >= dhat_) return;
  const BarrierValue b = contact_barrier(d, dhat_);
  VecMap(out.force) = -kappa_ * b.db * g;
  if (out.dfdq) MatMap(out.dfdq) = -kappa_ * (b.d2b * g * g.transpose() + b.db * h);
}

Vec3 ObstacleBarrierTerm::force(int e, double t, const Vec3& x) const {
  Vec3 g;
  const double d = obstacle(e).signed_distance(x, t, &g);
  return d >= dhat_ ? Vec3::Zero() : Vec3(-kappa_ * contact_barrier(d, dhat_).db * g);
}

double ObstacleBarrierTerm::admissible_fraction(const EvalContext& from, const EvalContext& to) const {
  double alpha = 1.0;
  for (int e = 0; e < num_elements(); ++e) {
    const auto& s = stencils_[e];
    const Vec3 x0((*from.q)[s[0]], (*from.q)[s[1]], (*from.q)[s[2]]);
    const Vec3 x1((*to.q)[s[0]], (*to.q)[s[1]], (*to.q)[s[2]]);
    const Obstacle& o = obstacle(e);
    const double d0 = o.signed_distance(x0, from.t);
    if (!(d0 > 0.0)) continue;  // a start already inside constrains nothing (never an accepted state)
    alpha = std::min(alpha, o.first_approach(x0, from.t, x1, to.t, kApproachFraction * std::min(d0, dhat_)));
  }
  return alpha;
}

}  // namespace wl
