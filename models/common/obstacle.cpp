#include "models/common/obstacle.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include <Eigen/Geometry>

namespace wl {
namespace {

Vec3 vec3_of(const std::array<double, 3>& a) { return Vec3(a[0], a[1], a[2]); }
double sign(double x) { return x < 0.0 ? -1.0 : 1.0; }

// R = R_z R_y R_x: turns about the fixed x, then y, then z axis.
Mat3 rotation(const std::array<double, 3>& deg) {
  const double k = std::numbers::pi / 180.0;
  return (Eigen::AngleAxisd(k * deg[2], Vec3::UnitZ()) * Eigen::AngleAxisd(k * deg[1], Vec3::UnitY()) *
          Eigen::AngleAxisd(k * deg[0], Vec3::UnitX()))
      .toRotationMatrix();
}

}  // namespace

Obstacle::Obstacle(const ObstacleSpec& spec)
    : spec_(spec),
      c0_(vec3_of(spec.center_m)),
      velocity_(vec3_of(spec.velocity_m_per_s)),
      rotation_(rotation(spec.rotation_deg)),
      mu_(spec.friction_coefficient) {
  switch (spec.shape) {
    case ObstacleSpec::Shape::box: half_ = vec3_of(spec.half_extents_m); break;
    case ObstacleSpec::Shape::cylinder:
    case ObstacleSpec::Shape::disk: half_ = Vec3(spec.radius_m, spec.radius_m, 0.5 * spec.height_m); break;
    case ObstacleSpec::Shape::mesh:
      if (!spec.mesh) throw std::invalid_argument("Obstacle: shape = \"mesh\" without its surface (read at load)");
      mesh_ = std::make_shared<MeshDistance>(*spec.mesh, spec.side == ObstacleSpec::Side::outside);
      break;
    default: half_ = Vec3::Constant(spec.radius_m);
  }
}

double Obstacle::signed_distance(const Vec3& x, double t, Vec3* gradient, Mat3* hessian) const {
  Vec3 g;
  Mat3 h;
  const double d = local_distance(to_body(x, t), &g, hessian ? &h : nullptr);
  if (gradient) *gradient = rotation_ * g;
  if (hessian) *hessian = rotation_ * h * rotation_.transpose();
  return d;
}

double Obstacle::local_distance(const Vec3& p, Vec3* g, Mat3* h) const {
  if (h) h->setZero();
  switch (spec_.shape) {
    case ObstacleSpec::Shape::plane: *g = Vec3::UnitZ(); return p.z();
    case ObstacleSpec::Shape::sphere: {
      const double r = p.norm();
      *g = r > 0.0 ? Vec3(p / r) : Vec3::UnitZ();
      if (h && r > 0.0) *h = (Mat3::Identity() - *g * g->transpose()) / r;  // ∇²‖p‖
      return r - spec_.radius_m;
    }
    case ObstacleSpec::Shape::box: {
      const Vec3 q = p.cwiseAbs() - half_, s(sign(p.x()), sign(p.y()), sign(p.z()));
      const Vec3 out = q.cwiseMax(0.0);
      const double d = out.norm();
      if (d > 0.0) {  // nearest a face, an edge or a corner: d = ‖max(q, 0)‖
        const Vec3 m = out / d;
        *g = s.cwiseProduct(m);
        if (h) {
          Mat3 active = Mat3::Zero();
          for (int k = 0; k < 3; ++k) active(k, k) = q[k] > 0.0 ? 1.0 : 0.0;
          *h = s.asDiagonal() * ((active - m * m.transpose()) / d) * s.asDiagonal();
        }
        return d;
      }
      Eigen::Index k = 0;
      const double inside = q.maxCoeff(&k);
      *g = Vec3::Zero();
      (*g)[k] = s[k];
      return inside;
    }
    case ObstacleSpec::Shape::cylinder:
    case ObstacleSpec::Shape::disk: {
      const double rho = std::hypot(p.x(), p.y()), sz = sign(p.z());
      const Vec3 e = rho > 0.0 ? Vec3(p.x() / rho, p.y() / rho, 0.0) : Vec3::UnitX();
      const double w0 = rho - half_.x(), w1 = std::abs(p.z()) - half_.z();
      const Mat3 ring = rho > 0.0 ? Mat3((Mat3(Vec3(1, 1, 0).asDiagonal()) - e * e.transpose()) / rho) : Mat3::Zero();
      if (w0 > 0.0 && w1 > 0.0) {  // nearest the rim: d = ‖w‖ in (ρ, |z|)
        const double d = std::hypot(w0, w1), a = w0 / d, b = w1 / d;
        *g = a * e + b * sz * Vec3::UnitZ();
        if (h) {
          Eigen::Matrix<double, 2, 3> J;  // ∂(ρ, |z|)/∂p
          J.row(0) = e.transpose();
          J.row(1) = sz * Vec3::UnitZ().transpose();
          const Eigen::Vector2d n(a, b);
          *h = J.transpose() * ((Eigen::Matrix2d::Identity() - n * n.transpose()) / d) * J + a * ring;
        }
        return d;
      }
      if (w0 > 0.0) {  // the side
        *g = e;
        if (h) *h = ring;
        return w0;
      }
      if (w1 > 0.0 || w1 >= w0) {  // a cap (or inside, nearer a cap)
        *g = sz * Vec3::UnitZ();
        return w1;
      }
      *g = e;  // inside, nearer the side
      return w0;
    }
    case ObstacleSpec::Shape::mesh: return mesh_->distance(p, g, h);
  }
  return 0.0;
}

// d(α) = d(p₀ + αΔ) is convex (a convex shape's signed distance along a line),
// so its tangent lies below it: Newton's iteration from α = 0 never passes the
// first root of d(α) = τ, and stops at once where d stops decreasing.
double Obstacle::first_approach(const Vec3& x0, double t0, const Vec3& x1, double t1, double tau) const {
  const Vec3 p0 = to_body(x0, t0), delta = to_body(x1, t1) - p0;
  Vec3 g;
  double alpha = 0.0;
  double f = local_distance(p0, &g, nullptr) - tau;
  if (f <= 0.0) return 0.0;
  const double tol = 1e-6 * std::max(tau, 1e-300);
  if (mesh_) return conservative_advance(p0, delta, f, tau, tol);
  for (int it = 0; it < 60; ++it) {
    const double slope = g.dot(delta);
    if (slope >= 0.0) return 1.0;  // convex: d grows from here on
    const double next = alpha - f / slope;
    if (next >= 1.0) return 1.0;  // the tangent, below d, stays above τ up to α = 1
    alpha = next;
    f = local_distance(p0 + alpha * delta, &g, nullptr) - tau;
    if (f <= tol) break;
  }
  return alpha;
}

// d is 1-Lipschitz, so d(p₀ + α'Δ) ≥ d(p₀ + αΔ) − (α' − α)‖Δ‖: from α the
// distance stays above τ for a further (d − τ)/‖Δ‖ of the path (conservative
// advancement, docs/models.md §3.11.4). Exact in one step for a path straight
// at a face; a grazing path advances slowly and stops after 1000 steps, short.
double Obstacle::conservative_advance(const Vec3& p0, const Vec3& delta, double f, double tau, double tol) const {
  const double length = delta.norm();
  if (length == 0.0) return 1.0;
  double alpha = 0.0;
  for (int it = 0; it < 1000; ++it) {
    alpha += f / length;
    if (alpha >= 1.0) return 1.0;
    f = mesh_->distance(p0 + alpha * delta, nullptr, nullptr) - tau;
    if (f <= tol) break;
  }
  return alpha;
}

void Obstacle::surface(double t, double plane_extent, std::vector<Vec3>& points,
                       std::vector<std::array<int, 3>>& tris) const {
  const int base = static_cast<int>(points.size());
  std::vector<Vec3> local;
  std::vector<std::array<int, 3>> faces;
  auto quad = [&](int a, int b, int c, int d) {
    faces.push_back({a, b, c});
    faces.push_back({a, c, d});
  };
  const double pi = std::numbers::pi;
  switch (spec_.shape) {
    case ObstacleSpec::Shape::plane: {
      const double s = plane_extent;
      local = {{-s, -s, 0}, {s, -s, 0}, {s, s, 0}, {-s, s, 0}};
      quad(0, 1, 2, 3);
      break;
    }
    case ObstacleSpec::Shape::sphere: {
      const int nth = 16, nph = 32;
      for (int i = 0; i <= nth; ++i)
        for (int j = 0; j < nph; ++j) {
          const double th = pi * i / nth, ph = 2 * pi * j / nph;
          local.push_back(spec_.radius_m *
                          Vec3(std::sin(th) * std::cos(ph), std::sin(th) * std::sin(ph), std::cos(th)));
        }
      for (int i = 0; i < nth; ++i)
        for (int j = 0; j < nph; ++j)
          quad(i * nph + j, (i + 1) * nph + j, (i + 1) * nph + (j + 1) % nph, i * nph + (j + 1) % nph);
      break;
    }
    case ObstacleSpec::Shape::box: {
      for (int k = 0; k < 8; ++k)
        local.push_back(half_.cwiseProduct(Vec3(k & 1 ? 1.0 : -1.0, k & 2 ? 1.0 : -1.0, k & 4 ? 1.0 : -1.0)));
      quad(0, 2, 3, 1);
      quad(4, 5, 7, 6);
      quad(0, 1, 5, 4);
      quad(2, 6, 7, 3);
      quad(0, 4, 6, 2);
      quad(1, 3, 7, 5);
      break;
    }
    case ObstacleSpec::Shape::mesh:
      local = mesh_->vertices();
      faces = mesh_->faces();
      break;
    case ObstacleSpec::Shape::cylinder:
    case ObstacleSpec::Shape::disk: {
      const int n = 48;
      for (int s : {-1, 1})
        for (int j = 0; j < n; ++j)
          local.push_back(
              Vec3(half_.x() * std::cos(2 * pi * j / n), half_.x() * std::sin(2 * pi * j / n), s * half_.z()));
      local.push_back(Vec3(0, 0, -half_.z()));
      local.push_back(Vec3(0, 0, half_.z()));
      for (int j = 0; j < n; ++j) {
        const int k = (j + 1) % n;
        quad(j, k, n + k, n + j);
        faces.push_back({2 * n, k, j});
        faces.push_back({2 * n + 1, n + j, n + k});
      }
      break;
    }
  }
  const Vec3 c = center(t);
  for (const Vec3& p : local) points.push_back(c + rotation_ * p);
  for (const auto& f : faces) tris.push_back({base + f[0], base + f[1], base + f[2]});
}

}  // namespace wl
