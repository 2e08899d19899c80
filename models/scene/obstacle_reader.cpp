#include "models/scene/obstacle_reader.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <sstream>
#include <string>

#include "models/scene/obstacle_mesh.h"

namespace wl::scene_detail {
namespace {

auto positive = [](double x) { return x > 0.0; };

// A required number > 0 (a size): missing and non-positive values are errors.
void read_size(TableReader& t, const char* key, double& out, const std::string& shape) {
  const std::string expected = "a number > 0 (m), required for shape = \"" + shape + "\"";
  if (!t.read_number(key, out, expected, positive)) t.fail_missing(key, expected);
}

// The mesh's checks square its coordinates (areas) and cube them (the enclosed
// volume, orient_closed_mesh): the largest one, scaled, must cube to a finite
// double that is not lost to underflow, so |scale·x| lies within
// [1e-100, 1e100] m. Else the scale key is refused (and not the triangle it
// would make look degenerate).
void check_mesh_scale(TableReader& t, const ObstacleMesh& mesh, double scale) {
  double largest = 0.0;
  for (const auto& v : mesh.vertices)
    for (double x : v) largest = std::max(largest, std::abs(x));
  const double scaled = scale * largest;
  if (scaled >= 1e-100 && scaled <= 1e100) return;
  const std::string expected = "a number > 0 that keeps the mesh's largest coordinate (" + format_number(largest) +
                               " in the file) within 1e-100 to 1e100 m once scaled (it gives " + format_number(scaled) +
                               " m)";
  if (const toml::node* n = t.table().get("scale")) t.fail_at(*n, "scale", expected);
  t.fail_key("scale", expected, format_number(scale));
}

// shape = "mesh": file (relative to the scene file), scale > 0, side; the
// surface is read and checked here, so a bad mesh fails at load (§3.11.9).
void read_mesh(TableReader& t, const Scene& s, ObstacleSpec& o) {
  namespace fs = std::filesystem;
  const std::string expected_file =
      "a path to a Wavefront OBJ file (string), relative to the scene file's directory, required for shape = \"mesh\"";
  std::string rel;
  if (!t.read_string("file", rel, expected_file, [](const std::string& x) { return !x.empty(); }))
    t.fail_missing("file", expected_file);
  const fs::path p =
      fs::path(rel).is_absolute() ? fs::path(rel) : (fs::path(s.source).parent_path() / rel).lexically_normal();
  std::error_code ec;
  if (!fs::is_regular_file(p, ec))
    t.fail_at(*t.table().get("file"), "file",
              "an existing OBJ file, relative to the scene file's directory (looked for " + p.string() + ")");
  o.mesh_file = p.string();
  t.read_number("scale", o.scale, "a number > 0 (the mesh's coordinates are multiplied by it to give metres)",
                positive);
  int side = 0;
  t.read_choice("side", side, {"outside", "both"});
  o.side = static_cast<ObstacleSpec::Side>(side);
  auto mesh = std::make_shared<ObstacleMesh>(read_obj_mesh(o.mesh_file, 1.0));
  check_mesh_scale(t, *mesh, o.scale);
  for (auto& v : mesh->vertices)
    for (double& x : v) x *= o.scale;
  if (o.side == ObstacleSpec::Side::outside) orient_closed_mesh(*mesh);
  o.mesh = std::move(mesh);
}

void read_one(TableReader& t, Scene& s) {
  ObstacleSpec o;
  o.line = t.line();
  const std::vector<std::string> shapes{"plane", "sphere", "box", "cylinder", "disk", "mesh"};
  int shape = 0;
  if (!t.read_choice("shape", shape, shapes))
    t.fail_missing("shape", "one of \"plane\", \"sphere\", \"box\", \"cylinder\", \"disk\", \"mesh\"");
  o.shape = static_cast<ObstacleSpec::Shape>(shape);
  const std::string vec = "an array of 3 numbers [x, y, z]";
  if (!t.read_vec3("center_m", o.center_m, vec + " (m)")) t.fail_missing("center_m", vec + " (m)");
  t.read_vec3("rotation_deg", o.rotation_deg, vec + " (degrees about the fixed x, y, z axes)");
  t.read_vec3("velocity_m_per_s", o.velocity_m_per_s, vec + " (m/s)");
  t.read_number("friction_coefficient", o.friction_coefficient, "a number ≥ 0", [](double x) { return x >= 0.0; });
  const std::string name = shapes[shape];
  switch (o.shape) {
    case ObstacleSpec::Shape::plane: break;
    case ObstacleSpec::Shape::sphere: read_size(t, "radius_m", o.radius_m, name); break;
    case ObstacleSpec::Shape::box: {
      const std::string expected = "an array of 3 numbers > 0 [a, b, c] (m), required for shape = \"box\"";
      if (!t.read_vec3("half_extents_m", o.half_extents_m, expected)) t.fail_missing("half_extents_m", expected);
      for (double h : o.half_extents_m)
        if (!(h > 0.0)) t.fail_at(*t.table().get("half_extents_m"), "half_extents_m", expected);
      break;
    }
    case ObstacleSpec::Shape::cylinder:
      read_size(t, "radius_m", o.radius_m, name);
      read_size(t, "height_m", o.height_m, name);
      break;
    case ObstacleSpec::Shape::disk:
      read_size(t, "radius_m", o.radius_m, name);
      read_size(t, "thickness_m", o.height_m, name);
      break;
    case ObstacleSpec::Shape::mesh: read_mesh(t, s, o); break;
  }
  t.finish("(for shape = \"" + name + "\")");
  s.obstacles.push_back(o);
}

// A d̂ that no model of the scene can take, refused where it is set (a scene
// edit in Python as much as a file): the cloth would feel itself at rest. The
// models refuse d̂ at or above their node spacing ℓ or the distance of the
// closest two surface primitives at rest that share no node (docs/models.md
// §3.11.7): √½ ℓ on the flat grid, a node to its cell's far diagonal. The
// continuum's ℓ = stride · cloth.spacing_m is the largest, so that is the bound
// here; the yarn level's √½ · cloth.spacing_m is checked when it is built.
void check_self_contact_distance(const TableReader& sc, const Scene& s) {
  const SelfContactParams& p = s.self_contact;
  if (!p.enabled || !p.activation_distance_m) return;
  const double spacing = std::max(1, s.fem.stride) * s.spacing_m;
  const bool grid = s.fem.mesh_file.empty();
  const double bound = grid ? std::sqrt(0.5) * spacing : spacing;
  if (*p.activation_distance_m < bound) return;
  std::ostringstream expected;
  expected << "a number below " << bound << " m: " << (grid ? "√½ × " : "") << "the node spacing " << spacing << " m ("
           << (s.fem.stride > 1 ? "fem.stride × " : "") << "cloth.spacing_m)"
           << (grid ? ", the distance at rest of a node from its cell's far diagonal" : "")
           << "; the cloth must not feel itself at rest";
  sc.fail_key("activation_distance_m", expected.str(), "");
}

}  // namespace

void read_obstacles(TableReader& top, Scene& s) {
  for (TableReader& t : top.table_array("obstacles")) read_one(t, s);
  if (auto sc = top.subtable("self_contact")) {
    SelfContactParams& p = s.self_contact;
    p.line = sc->line();
    sc->read_bool("enabled", p.enabled);
    sc->read_number("activation_distance_m", p.activation_distance_m, "a number > 0 (m)", positive);
    sc->read_number("stiffness_N_per_m", p.stiffness_N_per_m, "a number > 0 (N/m)", positive);
    sc->finish();
    check_self_contact_distance(*sc, s);
  }
  auto c = top.subtable("obstacle_contact");
  if (!c) return;
  ObstacleContactParams& p = s.obstacle_contact;
  c->read_number("activation_distance_m", p.activation_distance_m, "a number > 0 (m)", positive);
  c->read_number("stiffness_N_per_m", p.stiffness_N_per_m, "a number > 0 (N/m)", positive);
  c->read_number("friction_speed_m_per_s", p.friction_speed_m_per_s, "a number > 0 (m/s)", positive);
  c->read_bool("segment_edges", p.segment_edges);
  int step_hessian = p.projected_step_hessian ? 0 : 1;
  if (c->read_choice("step_hessian", step_hessian, {"projected", "exact"}))
    p.projected_step_hessian = step_hessian == 0;
  c->finish();
}

}  // namespace wl::scene_detail
