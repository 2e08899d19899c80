#include "models/common/mesh_distance.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Geometry>

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Simple_cartesian.h>

namespace wl {

struct MeshDistance::Tree {
  using K = CGAL::Simple_cartesian<double>;
  using Triangles = std::vector<K::Triangle_3>;
  using Primitive = CGAL::AABB_triangle_primitive<K, Triangles::const_iterator>;
  using AabbTree = CGAL::AABB_tree<CGAL::AABB_traits<K, Primitive>>;

  explicit Tree(Triangles t) : triangles(std::move(t)), tree(triangles.begin(), triangles.end()) {
    // Both the tree and the search structure of its distance queries are built
    // lazily by default; build them now so that queries are const and may run in parallel.
    tree.build();
    tree.accelerate_distance_queries();
  }
  // Index of a triangle nearest to p.
  int nearest(const Vec3& p) const {
    const auto hit = tree.closest_point_and_primitive(K::Point_3(p.x(), p.y(), p.z()));
    return static_cast<int>(hit.second - triangles.begin());
  }

  const Triangles triangles;
  AabbTree tree;
};

namespace {

enum class Feature { face, edge, vertex };

struct Closest {
  Feature feature;
  int index;  // the edge (k → k+1) or vertex k of the triangle
  Vec3 point;
};

// The closest point of triangle (a, b, c) to p and the region it lies in
// (Ericson, Real-Time Collision Detection §5.1.5).
Closest closest_on_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0.0 && d2 <= 0.0) return {Feature::vertex, 0, a};
  const Vec3 bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0.0 && d4 <= d3) return {Feature::vertex, 1, b};
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) return {Feature::edge, 0, a + d1 / (d1 - d3) * ab};
  const Vec3 cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0.0 && d5 <= d6) return {Feature::vertex, 2, c};
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) return {Feature::edge, 2, a + d2 / (d2 - d6) * ac};
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0.0 && d4 - d3 >= 0.0 && d5 - d6 >= 0.0)
    return {Feature::edge, 1, b + (d4 - d3) / ((d4 - d3) + (d5 - d6)) * (c - b)};
  const double s = 1.0 / (va + vb + vc);
  return {Feature::face, 0, a + ab * (vb * s) + ac * (vc * s)};
}

}  // namespace

MeshDistance::MeshDistance(const ObstacleMesh& mesh, bool signed_distance)
    : faces_(mesh.faces), signed_(signed_distance) {
  for (const auto& v : mesh.vertices) vertices_.emplace_back(v[0], v[1], v[2]);
  Tree::Triangles triangles;
  for (const auto& f : faces_) {
    auto pt = [&](int k) { return Tree::K::Point_3(vertices_[f[k]].x(), vertices_[f[k]].y(), vertices_[f[k]].z()); };
    triangles.emplace_back(pt(0), pt(1), pt(2));
    const Vec3 n = (vertices_[f[1]] - vertices_[f[0]]).cross(vertices_[f[2]] - vertices_[f[0]]);
    face_normal_.push_back(n.normalized());
  }
  tree_ = std::make_unique<Tree>(std::move(triangles));
  if (!signed_) return;
  const auto nb = face_neighbours(mesh);  // closed: every edge has exactly one other face
  vertex_normal_.assign(vertices_.size(), Vec3::Zero());
  edge_normal_.resize(faces_.size());
  for (size_t f = 0; f < faces_.size(); ++f)
    for (int k = 0; k < 3; ++k) {
      edge_normal_[f][k] = face_normal_[f] + face_normal_[nb[f][k]];
      const Vec3 &v = vertices_[faces_[f][k]], &u = vertices_[faces_[f][(k + 1) % 3]],
                 &w = vertices_[faces_[f][(k + 2) % 3]];
      const double angle = std::acos(std::clamp((u - v).normalized().dot((w - v).normalized()), -1.0, 1.0));
      vertex_normal_[faces_[f][k]] += angle * face_normal_[f];
    }
}

MeshDistance::~MeshDistance() = default;

double MeshDistance::distance(const Vec3& p, Vec3* gradient, Mat3* hessian) const {
  const int f = tree_->nearest(p);
  const auto& t = faces_[f];
  const Closest c = closest_on_triangle(p, vertices_[t[0]], vertices_[t[1]], vertices_[t[2]]);
  const Vec3 r = p - c.point;
  double d = 0.0;
  Vec3 g;
  Mat3 h = Mat3::Zero();
  Vec3 pseudo;  // the feature's pseudonormal (signed meshes)
  switch (c.feature) {
    case Feature::face: {
      const double s = face_normal_[f].dot(r);
      d = std::abs(s);
      g = s < 0.0 ? Vec3(-face_normal_[f]) : face_normal_[f];
      pseudo = face_normal_[f];
      break;
    }
    case Feature::edge: {
      const Vec3 e = (vertices_[t[(c.index + 1) % 3]] - vertices_[t[c.index]]).normalized();
      const Vec3 rp = r - r.dot(e) * e;  // r without its part along the edge
      d = rp.norm();
      g = d > 0.0 ? Vec3(rp / d) : face_normal_[f];
      if (d > 0.0) h = (Mat3::Identity() - e * e.transpose() - g * g.transpose()) / d;
      if (signed_) pseudo = edge_normal_[f][c.index];
      break;
    }
    case Feature::vertex: {
      d = r.norm();
      g = d > 0.0 ? Vec3(r / d) : face_normal_[f];
      if (d > 0.0) h = (Mat3::Identity() - g * g.transpose()) / d;
      if (signed_) pseudo = vertex_normal_[t[c.index]];
      break;
    }
  }
  if (signed_ && pseudo.dot(r) < 0.0) {  // inside: d < 0, ∇d = −r/‖r‖ (still pointing out)
    d = -d;
    g = -g;
    h = -h;
  }
  if (gradient) *gradient = g;
  if (hessian) *hessian = h;
  return d;
}

}  // namespace wl
