#include "models/common/obstacle_edge.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include <Eigen/Geometry>

#include "models/common/conservative_advance.h"
#include "models/common/obstacle_barrier.h"
#include "models/common/primitive_distance.h"
#include "models/knit/terms/autodiff_jacobian.h"

namespace wl {
namespace {

template <class T>
Point3<T> lift(const Vec3& a) {
  return Point3<T>(T(a.x()), T(a.y()), T(a.z()));
}

// The point of edge e closest to p: the clamped projection on a segment; on a
// circle, the point at radius r in the direction of p's offset from the axis
// (any point of it for p on the axis).
template <class T>
Point3<T> closest_point(const SharpEdge& e, const Point3<T>& p) {
  using std::sqrt;
  const Point3<T> rel = p - lift<T>(e.a);
  if (!e.circle) {
    const Vec3 ab = e.b - e.a;
    T u = rel.dot(lift<T>(ab)) / ab.squaredNorm();
    if (u < 0.0) u = T(0.0);
    if (u > 1.0) u = T(1.0);
    return lift<T>(e.a) + u * lift<T>(ab);
  }
  const Point3<T> radial = rel - rel.dot(lift<T>(e.k)) * lift<T>(e.k);
  const T rho = sqrt(radial.squaredNorm());
  if (!(rho > 0.0)) return lift<T>(Vec3(e.a + e.r * e.k.unitOrthogonal()));  // on the axis: every point is closest
  return lift<T>(e.a) + (e.r / rho) * radial;
}

// f_s = ∂D(p(s))/∂s = n·(x_b − x_a), n = (p − c)/D the unit vector from the
// edge's closest point c.
template <class T>
T slope(const SharpEdge& e, const Point3<T>& xa, const Point3<T>& xb, const T& s) {
  using std::sqrt;
  const Point3<T> p = (T(1.0) - s) * xa + s * xb, r = p - closest_point(e, p);
  return r.dot(xb - xa) / sqrt(r.squaredNorm());
}

double edge_distance(const SharpEdge& e, const Vec3& p) { return (p - closest_point<double>(e, p)).norm(); }

// f_ss at s, by forward-mode AD of f_s in s.
double curvature(const SharpEdge& e, const Vec3& xa, const Vec3& xb, double s) {
  using A = Eigen::AutoDiffScalar<Eigen::Matrix<double, 1, 1>>;
  return slope<A>(e, lift<A>(xa), lift<A>(xb), A(s, 1, 0)).derivatives()[0];
}

bool interior(double s) { return s > 0.0 && s < 1.0; }

}  // namespace

std::vector<SharpEdge> sharp_edges(const Obstacle& o, double t) {
  const ObstacleSpec& spec = o.spec();
  const Mat3& R = o.body_rotation();
  const Vec3 c = o.center(t);
  std::vector<SharpEdge> out;
  switch (spec.shape) {
    case ObstacleSpec::Shape::box: {
      const Vec3 h(spec.half_extents_m[0], spec.half_extents_m[1], spec.half_extents_m[2]);
      auto corner = [&](int k) {
        return Vec3(c + R * h.cwiseProduct(Vec3(k & 1 ? 1.0 : -1.0, k & 2 ? 1.0 : -1.0, k & 4 ? 1.0 : -1.0)));
      };
      for (int k = 0; k < 8; ++k)
        for (int bit : {1, 2, 4})
          if (!(k & bit)) out.push_back({false, corner(k), corner(k | bit), Vec3::Zero(), 0.0});
      break;
    }
    case ObstacleSpec::Shape::cylinder:
    case ObstacleSpec::Shape::disk: {
      const Vec3 axis = R * Vec3::UnitZ();
      for (double side : {-1.0, 1.0})
        out.push_back({true, c + side * 0.5 * spec.height_m * axis, Vec3::Zero(), axis, spec.radius_m});
      break;
    }
    default: break;
  }
  return out;
}

// D(p(s)) is convex in s for a straight edge (the distance to a convex set);
// for a circle it need not be, so the best of 9 samples brackets the search.
// Golden section in that bracket, then Newton on f_s = 0 to rounding.
SegmentEdgeClosest closest_to_edge(const SharpEdge& e, const Vec3& xa, const Vec3& xb) {
  auto f = [&](double s) { return edge_distance(e, xa + s * (xb - xa)); };
  int best = 0;
  double fbest = f(0.0);
  for (int i = 1; i <= 8; ++i)
    if (const double fi = f(i / 8.0); fi < fbest) {
      best = i;
      fbest = fi;
    }
  double lo = std::max(0.0, (best - 1) / 8.0), hi = std::min(1.0, (best + 1) / 8.0);
  const double g = 0.5 * (std::sqrt(5.0) - 1.0);
  double m1 = hi - g * (hi - lo), m2 = lo + g * (hi - lo), f1 = f(m1), f2 = f(m2);
  for (int it = 0; it < 60 && hi - lo > 1e-13; ++it) {
    if (f1 < f2) {
      hi = m2;
      m2 = m1;
      f2 = f1;
      m1 = hi - g * (hi - lo);
      f1 = f(m1);
    } else {
      lo = m1;
      m1 = m2;
      f1 = f2;
      m2 = lo + g * (hi - lo);
      f2 = f(m2);
    }
  }
  double s = 0.5 * (lo + hi);
  if (s < 1e-9 && slope<double>(e, xa, xb, 0.0) >= 0.0) s = 0.0;
  else if (s > 1.0 - 1e-9 && slope<double>(e, xa, xb, 1.0) <= 0.0) s = 1.0;
  else
    for (int it = 0; it < 3; ++it) {
      const double fss = curvature(e, xa, xb, s);
      if (!(fss > 0.0)) break;
      s = std::clamp(s - slope<double>(e, xa, xb, s) / fss, 0.0, 1.0);
    }
  return {s, f(s)};
}

ObstacleEdgeTerm::ObstacleEdgeTerm(std::shared_ptr<const std::vector<Obstacle>> obstacles, double dhat, double kappa)
    : obstacles_(std::move(obstacles)), dhat_(dhat), kappa_(kappa), edges_(obstacles_->size()) {
  if (!(dhat > 0.0 && std::isfinite(dhat)) || !(kappa > 0.0 && std::isfinite(kappa))) {
    std::ostringstream msg;
    msg << "ObstacleEdgeTerm: activation distance " << dhat << " m and stiffness " << kappa
        << " N/m; expected finite values > 0";
    throw std::invalid_argument(msg.str());
  }
  for (size_t k = 0; k < obstacles_->size(); ++k) edges_[k] = sharp_edges((*obstacles_)[k], 0.0);
}

void ObstacleEdgeTerm::add(const std::array<int, 6>& stencil, int obstacle) {
  stencils_.push_back(stencil);
  obstacle_.push_back(obstacle);
}

void ObstacleEdgeTerm::prepare(const EvalContext& ctx) {
  if (ctx.t == t_) return;
  t_ = ctx.t;
  for (size_t k = 0; k < obstacles_->size(); ++k) edges_[k] = sharp_edges((*obstacles_)[k], t_);
}

// Every point of the segment is within half its length of an end, and the
// distance to an edge is at least the distance to the obstacle (1-Lipschitz).
bool ObstacleEdgeTerm::near(int e, const Vec3& xa, const Vec3& xb, double t, double reach) const {
  const Obstacle& o = (*obstacles_)[obstacle_[e]];
  const double half = 0.5 * (xb - xa).norm();
  return std::min(o.signed_distance(xa, t), o.signed_distance(xb, t)) - half < reach;
}

double ObstacleEdgeTerm::energy(int e, const double* q) const {
  const Vec3 xa(q[0], q[1], q[2]), xb(q[3], q[4], q[5]);
  if (!near(e, xa, xb, t_, dhat_)) return 0.0;
  double energy = 0.0;
  for (const SharpEdge& edge : edges_[obstacle_[e]])
    energy += kappa_ * contact_barrier(closest_to_edge(edge, xa, xb).distance, dhat_).b;
  return energy;
}

// F = −κ b'(d) ((1 − s) n, s n) per edge (docs/models.md §3.11.10); the
// Jacobian by AD of F with s = s* − f_s/f_ss at an interior s* (∂s*/∂x of the
// implicit function f_s = 0), b'(d) carried as b'(d₀) + b''(d₀)·δd.
void ObstacleEdgeTerm::evaluate(int e, const double* q, const double*, const ElementOutput& out) const {
  if (near(e, Vec3(q[0], q[1], q[2]), Vec3(q[3], q[4], q[5]), t_, dhat_)) add_edges(edges_[obstacle_[e]], q, out);
}

ObstacleEdgeTerm::LVec ObstacleEdgeTerm::force(int e, double t, const double* q) const {
  LVec f = LVec::Zero();
  if (near(e, Vec3(q[0], q[1], q[2]), Vec3(q[3], q[4], q[5]), t, dhat_))
    add_edges(sharp_edges((*obstacles_)[obstacle_[e]], t), q, ElementOutput{f.data()});
  return f;
}

void ObstacleEdgeTerm::add_edges(const std::vector<SharpEdge>& edges, const double* q, const ElementOutput& out) const {
  const Vec3 xa(q[0], q[1], q[2]), xb(q[3], q[4], q[5]);
  const double half = 0.5 * (xb - xa).norm();
  for (const SharpEdge& edge : edges) {
    if (std::min(edge_distance(edge, xa), edge_distance(edge, xb)) - half >= dhat_) continue;
    const SegmentEdgeClosest c = closest_to_edge(edge, xa, xb);
    if (!(c.distance < dhat_) || !(c.distance > 0.0)) continue;
    const BarrierValue b = contact_barrier(c.distance, dhat_);
    // f_ss, floored at 0.1 ‖x_b − x_a‖²/d̂ where the segment runs nearly along the edge
    // (docs/models.md §3.11.10: there ∂s*/∂x = −f_xs/f_ss grows without bound).
    const double fss =
        interior(c.s) ? std::max(curvature(edge, xa, xb, c.s), kCurvatureFloor * (xb - xa).squaredNorm() / dhat_) : 0.0;
    const double kappa = kappa_;
    auto force = [&](const auto& x) {
      using T = typename std::decay_t<decltype(x)>::Scalar;
      using std::sqrt;
      const Point3<T> pa = x.template segment<3>(0), pb = x.template segment<3>(3);
      T s = T(c.s);
      if (fss > 0.0) s = s - slope<T>(edge, pa, pb, T(c.s)) / fss;  // s* − f_s/f_ss
      const Point3<T> p = (T(1.0) - s) * pa + s * pb, r = p - closest_point(edge, p);
      const T d = sqrt(r.squaredNorm());
      const T db = T(b.db) + b.d2b * (d - c.distance);  // b'(d) to first order about d₀
      Eigen::Matrix<T, 6, 1> f;
      f.template segment<3>(0) = (-kappa * db * (T(1.0) - s) / d) * r;
      f.template segment<3>(3) = (-kappa * db * s / d) * r;
      return f;
    };
    if (!out.dfdq) {
      VecMap(out.force) += force(Eigen::Map<const LVec>(q));
      continue;
    }
    LVec f;
    LMat k;
    force_and_jacobian_by_autodiff<6>(q, force, f.data(), k.data());
    VecMap(out.force) += f;
    MatMap(out.dfdq) += k;
  }
}

double ObstacleEdgeTerm::admissible_fraction(const EvalContext& from, const EvalContext& to) const {
  double alpha = 1.0;
  std::vector<std::vector<SharpEdge>> edges(obstacles_->size());
  for (size_t k = 0; k < obstacles_->size(); ++k) edges[k] = sharp_edges((*obstacles_)[k], from.t);
  for (int e = 0; e < num_elements(); ++e) {
    const auto& s = stencils_[e];
    Vec3 x0[2], dx[2];
    for (int i = 0; i < 2; ++i) {
      x0[i] = Vec3((*from.q)[s[3 * i]], (*from.q)[s[3 * i + 1]], (*from.q)[s[3 * i + 2]]);
      const Vec3 x1((*to.q)[s[3 * i]], (*to.q)[s[3 * i + 1]], (*to.q)[s[3 * i + 2]]);
      // The move relative to the obstacle, whose edges are taken at from.t.
      dx[i] = x1 - x0[i] - (to.t - from.t) * (*obstacles_)[obstacle_[e]].velocity();
    }
    const double lip = std::max(dx[0].norm(), dx[1].norm());  // |∂p(s, α)/∂α| ≤ max of the ends'
    if (!near(e, x0[0], x0[1], from.t, dhat_ + lip)) continue;
    for (const SharpEdge& edge : edges[obstacle_[e]]) {
      const double d0 = closest_to_edge(edge, x0[0], x0[1]).distance;
      if (!(d0 > 0.0) || d0 - lip >= kApproachFraction * std::min(d0, dhat_)) continue;
      alpha = std::min(alpha, conservative_advance(d0, kApproachFraction * std::min(d0, dhat_), lip, [&](double a) {
                         return closest_to_edge(edge, x0[0] + a * dx[0], x0[1] + a * dx[1]).distance;
                       }));
    }
  }
  return alpha;
}

}  // namespace wl
