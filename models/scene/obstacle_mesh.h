// The surface of a triangle-mesh obstacle (docs/models.md §3.11.9), read from
// a Wavefront OBJ file: `v x y z [w]` vertices, `f` faces of 3 or more vertex
// references (`i`, `i/t`, `i//n`, `i/t/n`; negative = relative to the last
// vertex), polygons split into a fan from their first vertex. The statements
// vt, vn, vp, o, g, s, usemtl and mtllib are ignored; any other is an error.
// Every problem is a SceneError located in the OBJ file (file, line, the
// statement, the text, what was expected).
#pragma once
#include <array>
#include <string>
#include <vector>

#include "models/scene/scene.h"

namespace wl {

struct ObstacleMesh {
  std::string file;
  std::vector<std::array<double, 3>> vertices;  // body frame [m], scaled
  std::vector<std::array<int, 3>> faces;        // vertex indices, 0-based
  std::vector<int> face_lines;                  // the OBJ line of each face
};

// Reads `path` and multiplies every coordinate by `scale` (> 0). Rejects an
// unreadable file, a malformed statement, an index out of range, a mesh with
// no face and a degenerate triangle (‖(b − a) × (c − a)‖ ≤ 10⁻¹² × its longest
// edge², zero area or a repeated vertex).
ObstacleMesh read_obj_mesh(const std::string& path, double scale);

// For face f and its edge k (vertices k → k+1 mod 3): the face across that
// edge, or −1 when the edge has no other face, or −2 when it has more than one.
std::vector<std::array<int, 3>> face_neighbours(const ObstacleMesh& m);

// A mesh that bounds a solid: every edge in exactly two faces that run it in
// opposite directions (closed, manifold, consistently oriented). Turns every
// face so that the normals (b − a) × (c − a) point out (positive enclosed
// volume). Throws SceneError at the first face with an open, shared or
// inconsistently oriented edge.
void orient_closed_mesh(ObstacleMesh& m);

}  // namespace wl
