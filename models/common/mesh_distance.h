// Distance from a point to a triangle mesh (docs/models.md §3.11.9), in the
// mesh's body frame. CGAL's AABB tree finds the nearest triangle; the point's
// region of that triangle (its inside, an edge, a vertex) gives the closest
// feature c and the piece of the distance there, r = p − c, d = ‖r‖, ∇d = r/d:
//   face   (unit normal n)     ∇²d = 0
//   edge   (unit direction e)  ∇²d = (I − e eᵀ − ∇d ∇dᵀ)/d
//   vertex                     ∇²d = (I − ∇d ∇dᵀ)/d
// A closed mesh (signed) takes the sign of r·ñ with ñ the feature's pseudonormal
// (Bærentzen & Aanæs 2005: the face normal, the sum of an edge's two face
// normals, the angle-weighted sum of a vertex's face normals), negative
// inside; an open mesh is two-sided: the unsigned distance. Where the nearest
// feature is unique d is C¹ with this piecewise Hessian; on the medial axis
// of a concave region (two features equally near) ∇d jumps.
#pragma once
#include <memory>
#include <vector>

#include "models/core/types.h"
#include "models/scene/obstacle_mesh.h"

namespace wl {

class MeshDistance {
 public:
  // `signed_distance`: the mesh is closed and oriented outwards (orient_closed_mesh).
  MeshDistance(const ObstacleMesh& mesh, bool signed_distance);
  ~MeshDistance();
  MeshDistance(const MeshDistance&) = delete;
  MeshDistance& operator=(const MeshDistance&) = delete;

  // Distance of body-frame point p [m], with ∇d and ∇²d when asked.
  double distance(const Vec3& p, Vec3* gradient, Mat3* hessian) const;
  const std::vector<Vec3>& vertices() const { return vertices_; }
  const std::vector<std::array<int, 3>>& faces() const { return faces_; }

 private:
  struct Tree;  // CGAL's AABB tree over the triangles (mesh_distance.cpp)
  std::unique_ptr<Tree> tree_;
  std::vector<Vec3> vertices_;
  std::vector<std::array<int, 3>> faces_;
  bool signed_ = false;
  // Pseudonormals (signed meshes only): per face, per face edge k (vertices k → k+1), per vertex.
  std::vector<Vec3> face_normal_, vertex_normal_;
  std::vector<std::array<Vec3, 3>> edge_normal_;
};

}  // namespace wl
