// The triangle mesh of the continuum model (docs/models.md §6.1): per-vertex
// rest material coordinates (u, v) in metres (u along the warp, v along the
// weft) and initial 3-D positions. The rest state of the material is the flat
// UV layout; 3-D positions are only the initial state.
//
// Built from a Scene: the cloth rectangle of the yarn model, vertices at every
// `scene.fem.stride`-th crossing (the last row/column always included), vertex
// (a, b) at crossing (i, j) = (grid_i[a], grid_j[b]), material (u, v) = (iL, jL),
// positioned by the pose exactly as the yarn model (yarn_model.cpp):
//   upright: x = (u, 0, height − v)   (cloth in the xz plane, top row at z = height)
//   flat:    x = (u, v, height).
// Each cell is split along its diagonal (i, j)-(i+1, j+1) into the CCW (in UV)
// triangles (i,j),(i+1,j),(i+1,j+1) and (i,j),(i+1,j+1),(i,j+1).
//
// Or read from an ASCII VTK XML UnstructuredGrid (.vtu) with triangle cells
// (VTK type 5) and a point-data array "uv" of 2 components holding the rest
// material coordinates in metres ("obj:vt", as meshio names OBJ texture
// coordinates, is accepted too: its first two components). Other formats (OBJ
// with vt, PLY, …) convert with meshio, e.g.
//   meshio convert cloth.obj cloth.vtu --ascii
// (see experiments/scenes/README_fem.md, also for scaling UVs to metres).
// Triangles clockwise in UV are reoriented; degenerate ones are an error.
#pragma once
#include <array>
#include <stdexcept>
#include <string>
#include <vector>

#include "models/core/types.h"
#include "models/scene/scene.h"

namespace wl {

// A mesh file that cannot be used; what() reads "<file>:<line>: <problem>".
class FemMeshError : public std::invalid_argument {  // bad input: exit 2
 public:
  using std::invalid_argument::invalid_argument;
};

struct FemMesh {
  std::string source;                         // "grid" or the file it came from
  std::vector<Vec2> uv;                       // rest material coordinates [m]
  std::vector<Vec3> x;                        // initial positions [m]
  std::vector<std::array<int, 3>> triangles;  // CCW in UV
  // Grid meshes only: crossing index of each vertex column / row (a knit's: contact column / row,
  // knit_contact_mesh.h).
  std::vector<int> grid_i, grid_j;

  int num_vertices() const { return static_cast<int>(uv.size()); }
  int num_triangles() const { return static_cast<int>(triangles.size()); }
  bool is_grid() const { return !grid_i.empty(); }
  // Grid meshes: vertex of column a, row b.
  int grid_vertex(int a, int b) const { return a + static_cast<int>(grid_i.size()) * b; }
};

// An interior edge with its two triangles: v[0]→v[1] is the edge as it runs
// (CCW) in the triangle (v[0], v[1], v[2]); v[3] is the other triangle's apex.
struct Hinge {
  std::array<int, 4> v;
  int tri0, tri1;
};

// Position of material point (u, v) by the scene's pose (see above).
Vec3 pose_position(const Scene& scene, double u, double v);
FemMesh build_grid_mesh(const Scene& scene);
// Splits every cell of a grid mesh's vertices (grid_i × grid_j, grid_vertex) along its diagonal
// (a, b)-(a+1, b+1) into the two CCW triangles above.
void add_grid_triangles(FemMesh& mesh);
// Whether every pin and handle of the scene lies on the lattice of stride k (i, j multiples of k).
bool boundary_on_lattice(const Scene& scene, int k);
// Throws FemMeshError (file, line, what is missing or wrong).
FemMesh read_vtu_mesh(const std::string& path);
// A knit scene's contact grid (knit_contact_mesh.h); else scene.fem.mesh_file if set, else the grid mesh.
FemMesh make_fem_mesh(const Scene& scene);
// Interior edges (shared by exactly two triangles). Throws FemMeshError for an
// edge shared by more than two triangles or by two with opposite orientation.
std::vector<Hinge> interior_hinges(const FemMesh& mesh);
// Vertex nearest (in UV) to the material point uv.
int nearest_vertex(const FemMesh& mesh, const Vec2& uv);

}  // namespace wl
