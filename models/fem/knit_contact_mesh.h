// The continuum of a knit (docs/models.md §11.9, docs/calibration.md §8): a
// triangle mesh through the knit's contact grid. Column κ = 2·wale + side (left
// 0, right 1), 0 ≤ κ < 2·wales, row ρ, 0 ≤ ρ ≤ courses (the contact rows of
// docs/models.md §11.7): material point (u, v) = (κW/2, ρC), the course along u
// (the woven warp's place), the wale along v (the weft's). Generated position
// (κW/2 − W/4, (ρ − ½)C, 0), posed as the knit model poses its nodes. Every
// cell is split along its diagonal as the woven grid mesh (fem_mesh.h); with a
// stride k the vertices lie on every k-th column and row.
#pragma once
#include <vector>

#include "models/core/types.h"
#include "models/fem/fem_mesh.h"
#include "models/knit/knit_graph.h"
#include "models/scene/scene.h"

namespace wl {

struct KnitContactGrid {
  int courses = 0, wales = 0;
  double W = 0, C = 0;  // loop width and height [m]
  int columns() const { return 2 * wales; }
  int rows() const { return courses + 1; }
  Vec2 material(int column, int row) const { return Vec2(column * W / 2, row * C); }
  Vec3 generated(int column, int row) const { return Vec3(column * W / 2 - W / 4, (row - 0.5) * C, 0.0); }
  // The grid's extent along u and v and its area [m, m²].
  double span_u() const { return (columns() - 1) * W / 2; }
  double span_v() const { return courses * C; }
  double area() const { return span_u() * span_v(); }
};
KnitContactGrid knit_contact_grid(const KnitLayout& layout);
KnitContactGrid knit_contact_grid(const Scene& knit_scene);

// A scene node = [i, j] of a knit (contact row i, column j) on the grid: its material point.
inline Vec2 knit_contact_material(const KnitContactGrid& g, const NodeRef& node) { return g.material(node.j, node.i); }

// The two nodes (a, b) of every stitch contact of a knit graph (non-periodic), with the
// contact's material point, row by row (ρ), column by column (κ): contact κ + 2·wales·ρ.
struct KnitGridContact {
  int a = 0, b = 0;
  Vec2 uv;
};
std::vector<KnitGridContact> knit_grid_contacts(const KnitGraph& graph);
// Those of the knit model built from the scene.
std::vector<KnitGridContact> knit_grid_contacts(const Scene& knit_scene);
// The contacts' points from a knit's node positions (one row per node): the midpoint of each
// contact's two nodes, which sit ±R through the cloth (Points: an n × 3 Eigen matrix).
template <class Points>
Points knit_contact_midpoints(const std::vector<KnitGridContact>& contacts, const Points& nodes) {
  Points x(static_cast<Eigen::Index>(contacts.size()), 3);
  for (size_t n = 0; n < contacts.size(); ++n)
    x.row(static_cast<Eigen::Index>(n)) = 0.5 * (nodes.row(contacts[n].a) + nodes.row(contacts[n].b));
  return x;
}

// Whether a stride k fits the knit's contact grid: k divides 2·wales − 1 and
// courses, and every pin and handle lies on the lattice (i, j multiples of k).
bool knit_stride_fits(const Scene& knit_scene, int k);

// The mesh of the knit scene's continuum at stride scene.fem.stride, posed.
FemMesh knit_contact_mesh(const Scene& knit_scene);

// The yarn level's mass of the knit [kg]: Σ over courses of ρ × the yarn's
// length in the relaxed rest shape (KnitModel::yarn_length), the mass its
// segments' inertia carries (docs/models.md §11.4).
double knit_yarn_mass(const Scene& knit_scene);
// knit_yarn_mass over the contact grid's area [kg/m²]: the continuum's mass per area.
double knit_areal_density(const Scene& knit_scene);

}  // namespace wl
