#include "output/self_intersection.h"

#include <iterator>
#include <utility>
#include <vector>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Surface_mesh.h>

namespace wl {

long count_self_intersections(const Frame& frame) {
  using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
  using Mesh = CGAL::Surface_mesh<Kernel::Point_3>;
  Mesh mesh;
  std::vector<Mesh::Vertex_index> v;
  for (Eigen::Index i = 0; i < frame.points.rows(); ++i)
    v.push_back(mesh.add_vertex(Kernel::Point_3(frame.points(i, 0), frame.points(i, 1), frame.points(i, 2))));
  auto add = [&](int a, int b, int c) { return mesh.add_face(v[a], v[b], v[c]) != Mesh::null_face(); };
  for (const CellBlock& block : frame.cells) {
    const auto& k = block.connectivity;
    if (block.type == CellType::triangle) {
      for (size_t i = 0; i + 2 < k.size(); i += 3)
        if (!add(k[i], k[i + 1], k[i + 2])) return -1;
    } else if (block.type == CellType::quad) {
      for (size_t i = 0; i + 3 < k.size(); i += 4)
        if (!add(k[i], k[i + 1], k[i + 2]) || !add(k[i], k[i + 2], k[i + 3])) return -1;
    }
  }
  std::vector<std::pair<Mesh::Face_index, Mesh::Face_index>> pairs;
  CGAL::Polygon_mesh_processing::self_intersections(faces(mesh), mesh, std::back_inserter(pairs));
  return static_cast<long>(pairs.size());
}

}  // namespace wl
