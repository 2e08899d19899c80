#include "calibration/knit_test_patch.h"

#include <algorithm>
#include <numeric>
#include <stdexcept>
#include <string>

#include "models/fem/knit_contact_mesh.h"
#include "models/knit/knit_model.h"
#include "models/knit/knit_rest_shape.h"

namespace wl {
namespace {

// The contact grid (models/fem/knit_contact_mesh.h): its centre and a contact's ring depth, the
// rings of the strip test's grips: rows 0 and `courses`, the first and last wale.
Vec3 centre(const KnitContactGrid& g) { return Vec3((g.wales - 1) * g.W / 2, (g.courses - 1) * g.C / 2, 0.0); }
int depth(const KnitContactGrid& g, int column, int row) {
  const int wale = column / 2;
  return std::min({row, g.courses - row, wale, g.wales - 1 - wale});
}

// The tile of a knit pattern (courses × wales), as knit_layout(scene, true) builds it.
std::pair<int, int> tile_size(const Scene& s) {
  const KnitLayout tile = knit_layout(s, true);
  return {tile.courses, tile.wales};
}

TestPoints grid_frame(const KnitContactGrid& g) {
  TestPoints p;
  p.centre = centre(g);
  p.span_m = g.span_u();
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
  const KnitContactGrid g = knit_contact_grid(graph.layout());
  TestPoints p = grid_frame(g);
  const Vec& q0 = model.initial_q();
  const std::vector<KnitGridContact> contacts = knit_grid_contacts(graph);
  for (size_t n = 0; n < contacts.size(); ++n)
    for (int k : {contacts[n].a, contacts[n].b}) {
      const KnitNode& node = graph.node(k);
      p.x_of.push_back(node.x_dof);
      p.rest.push_back(q0.segment<3>(node.x_dof) - p.centre);
      p.depth.push_back(depth(g, static_cast<int>(n) % g.columns(), static_cast<int>(n) / g.columns()));
      std::vector<int> coordinates;
      for (int c : node.coord)
        if (is_dof(c)) coordinates.push_back(c);
      p.held_with.push_back(std::move(coordinates));
    }
  p.settle_at_rest = true;
  p.hold_depth_in_plane = true;
  return p;
}

TestPoints knit_continuum_points(const Scene& test_scene) {
  const KnitContactGrid g = knit_contact_grid(test_scene);
  TestPoints p = grid_frame(g);
  for (int row = 0; row < g.rows(); ++row)
    for (int column = 0; column < g.columns(); ++column) {
      p.x_of.push_back(3 * (column + g.columns() * row));
      p.rest.push_back(g.generated(column, row) - p.centre);  // the patch is flat at height 0
      p.depth.push_back(depth(g, column, row));
    }
  return p;
}

std::vector<double> default_knit_ladder(TestKind kind, const Scene& test_scene) {
  const KnitContactGrid g = knit_contact_grid(test_scene);
  std::vector<double> l;
  for (int k = 1; k <= 8; ++k) switch (kind) {
      case TestKind::uniaxial_warp:
      case TestKind::uniaxial_weft:
      case TestKind::biaxial:
      case TestKind::stretch_shear:
      case TestKind::stretch_bending: l.push_back(0.0125 * k); break;
      case TestKind::shear: l.push_back(0.05 * k); break;
      case TestKind::bending_warp: l.push_back(k / (8.0 * g.span_u())); break;
      case TestKind::bending_weft: l.push_back(k / (8.0 * g.span_v())); break;
      case TestKind::bending_diagonal:
      case TestKind::bending_antidiagonal: l.push_back(k / (8.0 * 0.5 * (g.span_u() + g.span_v()))); break;
    }
  return l;
}

EquilibriumOptions knit_equilibrium_options(const Scene& test_scene) {
  EquilibriumOptions o;
  o.descent_tolerance = kKnitRestTolerance * stiffest_yarn_N(test_scene);
  return o;
}

}  // namespace wl
