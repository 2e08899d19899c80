#include "models/common/obstacle_friction.h"

#include <cmath>
#include <sstream>
#include <stdexcept>

#include "models/common/obstacle_barrier.h"

namespace wl {

ObstacleFrictionTerm::ObstacleFrictionTerm(std::shared_ptr<const std::vector<Obstacle>> obstacles, double dhat,
                                           double kappa, double speed)
    : obstacles_(std::move(obstacles)), dhat_(dhat), kappa_(kappa), eps_(speed) {
  if (!(speed > 0.0 && std::isfinite(speed))) {
    std::ostringstream msg;
    msg << "ObstacleFrictionTerm: friction speed " << speed << " m/s; expected a finite value > 0";
    throw std::invalid_argument(msg.str());
  }
}

void ObstacleFrictionTerm::add(const std::array<int, 3>& stencil, int node, int obstacle) {
  stencils_.push_back(stencil);
  node_.push_back(node);
  obstacle_.push_back(obstacle);
  lambda_.push_back(0.0);
  slip_.push_back(0.0);
  normal_.push_back(Vec3::UnitZ());
}

void ObstacleFrictionTerm::set_lagged(int e, double lambda, const Vec3& n, double slip_speed) {
  lambda_[e] = lambda;
  normal_[e] = n.normalized();
  slip_[e] = slip_speed;
  lagged_ = true;
}

// λ = −κ b'(d), n = ∇d, y₀ = ‖(I − n nᵀ)(ẋ − v_o)‖ at the state of ctx (docs/models.md §3.11.3).
void ObstacleFrictionTerm::lag(const EvalContext& ctx) {
  for (int e = 0; e < num_elements(); ++e) {
    const auto& s = stencils_[e];
    const Vec3 x((*ctx.q)[s[0]], (*ctx.q)[s[1]], (*ctx.q)[s[2]]);
    const Obstacle& o = (*obstacles_)[obstacle_[e]];
    Vec3 g;
    const double d = o.signed_distance(x, ctx.t, &g);
    lambda_[e] = std::max(0.0, -kappa_ * contact_barrier(d, dhat_).db);
    normal_[e] = g;
    const Vec3 w = ctx.v ? Vec3(Vec3((*ctx.v)[s[0]], (*ctx.v)[s[1]], (*ctx.v)[s[2]]) - o.velocity()) : Vec3::Zero();
    slip_[e] = (w - g * g.dot(w)).norm();
  }
  lagged_ = true;
}

void ObstacleFrictionTerm::prepare(const EvalContext& ctx) {
  if (!lagged_) lag(ctx);
}

void ObstacleFrictionTerm::accept_step(const EvalContext& ctx, double) { lag(ctx); }

Vec3 ObstacleFrictionTerm::force(int e, const Vec3& xdot) const {
  Vec3 f = Vec3::Zero();
  const Vec3 zero = Vec3::Zero();
  evaluate(e, zero.data(), xdot.data(), ElementOutput{f.data()});
  return f;
}

// F = −μλ m(y₀) u, u = T(ẋ − v_o) (docs/models.md §3.11.3)
void ObstacleFrictionTerm::evaluate(int e, const double*, const double* v, const ElementOutput& out) const {
  const Obstacle& o = (*obstacles_)[obstacle_[e]];
  const double y = slip_[e], m = y < eps_ ? 2.0 / eps_ - y / eps_ / eps_ : 1.0 / y;
  const double c = o.friction_coefficient() * lambda_[e] * m;
  if (c == 0.0) return;
  const Vec3& n = normal_[e];
  const Mat3 T = Mat3::Identity() - n * n.transpose();
  VecMap(out.force) = -c * (T * (Eigen::Map<const Vec3>(v) - o.velocity()));
  if (out.dfdv) MatMap(out.dfdv) = -c * T;
}

}  // namespace wl
