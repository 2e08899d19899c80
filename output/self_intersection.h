// Cloth–cloth intersections of an output frame (docs/models.md §3.11.7): the
// number of pairs of the cloth's surface triangles (triangle cells, quads split
// along a diagonal) that intersect, other than neighbours meeting at their
// shared vertex or edge, by CGAL's self-intersection test
// (Polygon_mesh_processing::self_intersections on a Surface_mesh).
#pragma once
#include "models/core/frame.h"

namespace wl {

// −1 when the cells do not form a surface CGAL accepts (a non-manifold edge).
long count_self_intersections(const Frame& frame);

}  // namespace wl
