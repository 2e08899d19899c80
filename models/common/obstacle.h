// A rigid obstacle of the scene (docs/models.md §3.11.1): its signed distance
// with gradient and Hessian, the first approach of a straight node path to a
// distance (continuous collision, §3.11.4) and a triangulated surface for output.
// The body frame is x = c(t) + R p with c(t) = c₀ + t·v (constant velocity, no
// spin); the shape is given in p:
//   plane     d = p_z
//   sphere    d = ‖p‖ − r
//   box       q = |p| − h (componentwise): d = ‖max(q, 0)‖ + min(max_k q_k, 0)
//   cylinder, disk (radius r, half height a about p_z): w = (‖p_xy‖ − r, |p_z| − a),
//             d = ‖max(w, 0)‖ + min(max(w₀, w₁), 0)
//   mesh      the distance to a triangle mesh (mesh_distance.h): signed for a
//             closed mesh, unsigned (two-sided) for an open one
// Every analytic shape is convex, so d is convex in p (used by first_approach).
// Outside (d > 0) d is C¹ and piecewise C² (a mesh: except on the medial axis
// of a concave region); the Hessian is that of the piece at p.
#pragma once
#include <array>
#include <memory>
#include <vector>

#include "models/common/mesh_distance.h"
#include "models/core/types.h"
#include "models/scene/scene.h"

namespace wl {

class Obstacle {
 public:
  explicit Obstacle(const ObstacleSpec& spec);

  // Signed distance of world point x at time t [m] (negative inside); the
  // gradient ∇d (unit outside) and Hessian ∇²d when asked.
  double signed_distance(const Vec3& x, double t, Vec3* gradient = nullptr, Mat3* hessian = nullptr) const;
  // Node moving on a straight line from x0 (time t0) to x1 (time t1) while the
  // obstacle moves too: the first fraction α ∈ [0, 1] of the path at which the
  // distance falls to tau, or 1 when it stays above it. Conservative: the
  // distance exceeds tau on [0, α). 0 when d(x0) ≤ tau already.
  // Analytic shapes: Newton's iteration on the convex d along the path; a mesh:
  // conservative advancement (docs/models.md §3.11.4).
  double first_approach(const Vec3& x0, double t0, const Vec3& x1, double t1, double tau) const;

  Vec3 center(double t) const { return c0_ + t * velocity_; }
  const Vec3& velocity() const { return velocity_; }
  const Mat3& body_rotation() const { return rotation_; }  // R: body to world
  double friction_coefficient() const { return mu_; }
  const ObstacleSpec& spec() const { return spec_; }
  // The surface at time t as triangles; a plane is drawn as a square of half
  // side `plane_extent` around its centre.
  void surface(double t, double plane_extent, std::vector<Vec3>& points, std::vector<std::array<int, 3>>& tris) const;

 private:
  // Signed distance in the body frame, with its gradient and Hessian there.
  double local_distance(const Vec3& p, Vec3* g, Mat3* h) const;
  // first_approach on a mesh: from f = d(p₀) − τ > 0 along Δ.
  double conservative_advance(const Vec3& p0, const Vec3& delta, double f, double tau, double tol) const;
  Vec3 to_body(const Vec3& x, double t) const { return rotation_.transpose() * (x - center(t)); }

  ObstacleSpec spec_;
  Vec3 c0_, velocity_, half_;  // half_: box half extents, or (r, r, a) for cylinders
  Mat3 rotation_;
  double mu_ = 0.0;
  std::shared_ptr<const MeshDistance> mesh_;  // shape = mesh
};

}  // namespace wl
