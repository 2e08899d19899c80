#include "calibration/knit_test_patch.h"

#include <algorithm>
#include <numeric>
#include <stdexcept>
#include <string>

#include "models/knit/knit_model.h"
#include "models/knit/knit_rest_shape.h"

namespace wl {
namespace {

// The contact grid (docs/models.md §11.2, §11.7): column κ = 2·wale + side at
// x = κW/2 − W/4, row ρ at y = (ρ − ½)C; its ring depth, the rings of the strip
// test's grips: rows 0 and `courses`, the first and last wale.
struct ContactGrid {
  int courses, wales;
  double W, C;
  int columns() const { return 2 * wales; }
  int rows() const { return courses + 1; }
  Vec3 generated(int column, int row) const { return Vec3(column * W / 2 - W / 4, (row - 0.5) * C, 0.0); }
  Vec3 centre() const { return Vec3((wales - 1) * W / 2, (courses - 1) * C / 2, 0.0); }
  int depth(int column, int row) const {
    const int wale = column / 2;
    return std::min({row, courses - row, wale, wales - 1 - wale});
  }
  double span() const { return (2 * wales - 1) * W / 2; }
  double area() const { return span() * courses * C; }
};

ContactGrid contact_grid(const KnitLayout& l) { return {l.courses, l.wales, l.wale_spacing, l.course_spacing}; }
ContactGrid contact_grid(const Scene& s) { return contact_grid(knit_layout(s, false)); }

// The tile of a knit pattern (courses × wales), as knit_layout(scene, true) builds it.
std::pair<int, int> tile_size(const Scene& s) {
  const KnitLayout tile = knit_layout(s, true);
  return {tile.courses, tile.wales};
}

TestPoints grid_frame(const ContactGrid& g) {
  TestPoints p;
  p.centre = g.centre();
  p.span_m = g.span();
  p.area_m2 = g.area();
  return p;
}

}  // namespace

int minimum_knit_patch(const Scene& scene) {
  const auto [courses, wales] = tile_size(scene);
  return std::max(6, std::max(courses, wales) + 4);
}

int default_knit_patch(const Scene& scene, int largest) {
  const auto [tile_courses, tile_wales] = tile_size(scene);
  const int step = std::lcm(tile_courses, tile_wales), smallest = minimum_knit_patch(scene);
  const int below = largest / step * step;
  return below >= smallest ? below : (smallest + step - 1) / step * step;
}

int check_knit_patch(const Scene& scene, int patch) {
  const int min_patch = minimum_knit_patch(scene);
  const auto [tile_courses, tile_wales] = tile_size(scene);
  if (patch < min_patch || patch % tile_courses != 0 || patch % tile_wales != 0)
    throw std::invalid_argument("patch of " + std::to_string(patch) +
                                " courses × wales does not suit the knit pattern: need at least " +
                                std::to_string(min_patch) + " (one tile inside the two clamped rings of the " +
                                "bending tests) and a multiple of its tile (" + std::to_string(tile_courses) + " × " +
                                std::to_string(tile_wales) + ")");
  return patch;
}

TestPoints knit_contact_points(const KnitModel& model) {
  const KnitGraph& graph = model.graph();
  const ContactGrid g = contact_grid(graph.layout());
  TestPoints p = grid_frame(g);
  const Vec& q0 = model.initial_q();
  for (int row = 0; row < g.rows(); ++row)
    for (int column = 0; column < g.columns(); ++column)
      for (int end : {0, 1}) {
        const KnitNode& n = graph.node(graph.contact_node(row - 1, column / 2, column % 2, end));
        p.x_of.push_back(n.x_dof);
        p.rest.push_back(q0.segment<3>(n.x_dof) - p.centre);
        p.depth.push_back(g.depth(column, row));
        std::vector<int> coordinates;
        for (int k : n.coord)
          if (is_dof(k)) coordinates.push_back(k);
        p.held_with.push_back(std::move(coordinates));
      }
  p.settle_at_rest = true;
  p.hold_depth_in_plane = true;
  return p;
}

FemMesh knit_contact_mesh(const Scene& test_scene) {
  const ContactGrid g = contact_grid(test_scene);
  FemMesh m;
  m.source = "knit contact grid";
  for (int row = 0; row < g.rows(); ++row)
    for (int column = 0; column < g.columns(); ++column) {
      m.uv.emplace_back(column * g.W / 2, row * g.C);
      m.x.push_back(g.generated(column, row));
    }
  // Not a crossing grid (grid_i, grid_j empty): its two spacings differ.
  auto vertex = [&](int column, int row) { return column + g.columns() * row; };
  for (int b = 0; b + 1 < g.rows(); ++b)
    for (int a = 0; a + 1 < g.columns(); ++a) {
      const int v00 = vertex(a, b), v10 = vertex(a + 1, b), v11 = vertex(a + 1, b + 1), v01 = vertex(a, b + 1);
      m.triangles.push_back({v00, v10, v11});
      m.triangles.push_back({v00, v11, v01});
    }
  return m;
}

TestPoints knit_continuum_points(const Scene& test_scene) {
  const ContactGrid g = contact_grid(test_scene);
  TestPoints p = grid_frame(g);
  for (int row = 0; row < g.rows(); ++row)
    for (int column = 0; column < g.columns(); ++column) {
      p.x_of.push_back(3 * (column + g.columns() * row));
      p.rest.push_back(g.generated(column, row) - p.centre);
      p.depth.push_back(g.depth(column, row));
    }
  return p;
}

std::vector<double> default_knit_ladder(TestKind kind, const Scene& test_scene) {
  const ContactGrid g = contact_grid(test_scene);
  std::vector<double> l;
  for (int k = 1; k <= 8; ++k) switch (kind) {
      case TestKind::uniaxial_warp:
      case TestKind::uniaxial_weft:
      case TestKind::biaxial:
      case TestKind::stretch_shear:
      case TestKind::stretch_bending: l.push_back(0.0125 * k); break;
      case TestKind::shear: l.push_back(0.05 * k); break;
      case TestKind::bending_warp: l.push_back(k / (8.0 * g.span())); break;
      case TestKind::bending_weft: l.push_back(k / (8.0 * g.courses * g.C)); break;
      case TestKind::bending_diagonal:
      case TestKind::bending_antidiagonal: l.push_back(k / (8.0 * 0.5 * (g.span() + g.courses * g.C))); break;
    }
  return l;
}

double knit_areal_density(const Scene& test_scene) {
  const KnitModel model(test_scene);
  const Vec& q = model.initial_q();
  const auto& types = test_scene.warp_yarn_types;
  double mass = 0.0;
  for (int y = 0; y < static_cast<int>(model.graph().yarns().size()); ++y)
    mass += test_scene.yarn_types.at(types[y % types.size()]).density_kg_per_m * model.yarn_length(q, y);
  return mass / contact_grid(test_scene).area();
}

EquilibriumOptions knit_equilibrium_options(const Scene& test_scene) {
  EquilibriumOptions o;
  o.descent_tolerance = kKnitRestTolerance * stiffest_yarn_N(test_scene);
  return o;
}

}  // namespace wl
