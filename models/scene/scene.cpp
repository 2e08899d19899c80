// Scene files: TOML (toml++ 3.3) → validated wl::Scene in SI units.
//
// FORMAT (also in experiments/scenes/README.md). Every table and key is
// optional and defaults to the value in scene.h, but an unknown table or key
// is an error, so a typo never falls back to a default. Integers must be
// written as integers (17, not 17.0); a number may be written as an integer
// (1000 for 1000.0). NaN and ±inf are rejected everywhere.
//
//   [cloth]
//     warps, wefts           integers, 3 ≤ n ≤ 16384 (yarn counts; nodes (i, j): i < wefts, j < warps)
//     spacing_m              L > 0
//     radius_m               R, 0 < R < spacing_m/√2 (shear lock angle 2 arcsin(R/L) < π/2)
//     sliding                bool (false: u, v frozen)
//     warp_yarn_types        non-empty array of yarn type names, cycled over the warps (j)
//     weft_yarn_types        same, cycled over the wefts (i)
//   [cloth.pattern]
//     kind                   "plain" | "twill" | "satin" | "stockinette" | "garter" | "rib2x2"
//     courses, wales         knits only: integers ≥ 2 and ≤ 256; garter: courses even (its
//                            tile is 2 courses); rib2x2: wales a multiple of 4
//     course_spacing_m       knits only: loop height C ≥ 2·cloth.radius_m when written (default 0.8·cloth.spacing_m,
//     the loop width) over, under, shift     twill only: over, under ≥ 1; 0 < |shift| < over+under;
//                            over+under ≤ min(warps, wefts)
//     harness, step          satin only: 5 ≤ harness ≤ min(warps, wefts);
//                            1 < step < harness−1, gcd(step, harness) = 1
//   [yarn_types.NAME]        one table per yarn type; every defined type must be used
//     density_kg_per_m, stretch_modulus_Pa, bending_modulus_Pa   all > 0
//     "default" is YarnType{} of scene.h unless defined here.
//   [knit]                   knit scenes only (docs/models.md §11)
//     roll_stiffness_N, stitch_length_stiffness_N, compression_stiffness_N_per_m   ≥ 0
//   A knit scene takes no [wind] or [[obstacles]] (not supported yet); its [self_contact] is the
//   yarn–yarn contact (docs/models.md §11.7, activation distance below the yarn radius); its [[pins]] and
//   [[handles]] name stitch contacts: node = [i, j], 0 ≤ i ≤ courses (contact row), 0 ≤ j < 2·wales.
//   Its [fem] (the continuum on the contact grid, docs/models.md §11.9): stride dividing 2·wales − 1 and
//   courses; no mesh_file, border_strip, grid_line_bending, yarn_node_mass or areal_density_kg_per_m2.
//   [contact]
//     shear_model, friction_model      "gong" | "cirio"
//     shear_modulus_Pa, friction_coefficient, friction_stiffness_N_per_m,
//     friction_damping_Ns_per_m, parallel_stiffness_N_per_m2                  ≥ 0
//     tanh_sharpness_per_m, lock_exponent, lock_sigma                         > 0
//   [pose]
//     kind = "flat" | "upright";  height_m (any number)
//   [[pins]]      node = [i, j]                 (0 ≤ i < wefts, 0 ≤ j < warps; knits: see [knit])
//   [[handles]]   node = [i, j] (required); stiffness_N_per_m > 0;
//                 velocity_m_per_s = [x, y, z] (the target's prescribed motion), start_s ≥ 0,
//                 stop_s > start_s (both only with velocity_m_per_s)
//                 A node is pinned or held at most once.
//   [gravity]     acceleration_m_per_s2 = [x, y, z]
//   [wind]        velocity_m_per_s = [x, y, z]; air_density_kg_per_m3 ≥ 0; drag_Ns_per_m3 ≥ 0
//   [time]
//     duration_s, dt_s, output_interval_s > 0 with dt_s ≤ output_interval_s ≤ duration_s,
//     at most 1e7 fixed steps (duration_s / dt_s) and 1e5 frames (time_settings_violation)
//     integrator (non-empty string; the run checks the name), adaptive (bool)
//     linear_solver (non-empty string; the run checks the name)
//     rtol in [1e-12, 1) (below it a step's round-off is a sizeable part of the tolerance), atol > 0
//     settle_after_s ≥ 0 (< duration_s), settle_dt_s > 0 (≤ output_interval_s): fixed
//       steps only, no error_estimate or accuracy_m
//   [terms]       stretch, bending, shear, parallel_contact, friction, gravity, wind,
//                 handles, inertia (bools); stretch_step_hessian = "exact" | "projected"
//   [fem]
//     stride ≥ 1, dividing wefts−1 and warps−1; with stride > 1 every pin and
//       handle must lie on the stride lattice (i and j multiples of stride)
//     mesh_file, parameter_file, tile_law   paths relative to the scene file's directory,
//       resolved on load; the file must exist (a tile law's rows are checked when the
//       continuum is built, models/fem/tile_law_file.h)
//     areal_density_kg_per_m2, warp_stretch_N_per_m, weft_stretch_N_per_m, shear_N_per_m,
//     shear_lock_angle_rad, shear_lock_exponent, warp_bending_N_m, weft_bending_N_m,
//     diagonal_bending_N_m, stretch_coupling_N_per_m, warp_stretch_quartic_N_per_m,
//     weft_stretch_quartic_N_per_m, areal_stretch_quartic_N_per_m
//       optional numbers > 0 (the coupling, once merged with the parameter file and the
//       defaults, below √(warp·weft stretch): checked by fem_material)
//     shear_law = "linear_lock" (default) | "spline"; with "spline": shear_knots_rad, 1–6 increasing
//       angles in (0, 1.5] (default [0.1, 0.2, 0.3, 0.4]), and shear_knot1_N_per_m … shear_knot<n>_N_per_m,
//       optional numbers > 0 (absent: shear_N_per_m); neither key without the spline law
//     border_strip, grid_line_bending, yarn_node_mass   optional booleans (default false); grid_line_bending
//       needs the grid mesh (no mesh_file), yarn_node_mass also stride 1
//       (absent = computed / taken from parameter_file)
//
//   [[obstacles]]  rigid obstacles (obstacle_reader.cpp, docs/models.md §3.11):
//     shape = "plane" | "sphere" | "box" | "cylinder" | "disk"   (required)
//     center_m = [x, y, z] (required); rotation_deg, velocity_m_per_s = [x, y, z];
//     friction_coefficient ≥ 0; sizes > 0, required by shape: radius_m (sphere,
//     cylinder, disk), half_extents_m = [a, b, c] (box), height_m (cylinder),
//     thickness_m (disk)
//   [obstacle_contact]  activation_distance_m, stiffness_N_per_m, friction_speed_m_per_s > 0, segment_edges,
//     step_hessian = "projected" | "exact"
//   [self_contact]  enabled (bool), activation_distance_m, stiffness_N_per_m > 0
//   [measures]      what the run measures on its last frame, into summary.json "measures"
//     (measure_reader.cpp, docs/models.md §3.11.6):
//     drape (bool): drape coefficient and fold count over the pedestal, the first disk, cylinder
//       or sphere obstacle, not turned about x or y; woven cloth only
//     drape_pixel_m (cloth side / 8192 ≤ x ≤ cloth.spacing_m, default 1e-4),
//     fold_prominence_m (> 0, default 5e-4): only with drape = true
//   [mixed]         the mixed model's yarn-level region (mixed_reader.cpp, docs/models.md §12.1):
//     yarn_region = [[i0, j0, i1, j1], ...], rectangles of crossings, integers
//       0 ≤ i0 ≤ i1 < wefts, 0 ≤ j0 ≤ j1 < warps (inclusive); [] for none; woven cloth only
//
// ERRORS: SceneError with file, line (source line of the offending value; for a
// missing key or a violated default, the line of its table), the dotted key
// ("cloth.radius_m", "pins[1].node"), the value as written and what was
// expected. Syntax errors: key "(syntax)"; missing file: line 0, key "(file)".
#include "models/scene/scene.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <numeric>
#include <set>
#include <sstream>

#include "models/scene/measure_reader.h"
#include "models/scene/mixed_reader.h"
#include "models/scene/obstacle_reader.h"
#include "models/scene/scene_limits.h"
#include "models/scene/toml_reader.h"

namespace wl {

namespace {

using scene_detail::format_number;
using scene_detail::line_of;
using scene_detail::Source;
using scene_detail::TableReader;

std::string eq(double x) { return " (= " + format_number(x) + ")"; }
std::string eq(int x) { return " (= " + std::to_string(x) + ")"; }
auto positive = [](double x) { return x > 0.0; };
auto non_negative = [](double x) { return x >= 0.0; };

struct YarnTypeDef {
  YarnType type;
  int line;
  std::string written;
};

std::map<std::string, YarnTypeDef> read_yarn_types(TableReader& top) {
  std::map<std::string, YarnTypeDef> defs;
  auto yt = top.subtable("yarn_types");
  if (!yt) return defs;
  yt->accept_all_keys();
  for (auto&& [k, v] : yt->table()) {
    const std::string name(k.str());
    const auto* t = v.as_table();
    if (!t) yt->fail_at(v, name, "a table [yarn_types." + name + "] of yarn parameters");
    TableReader r(top.source(), *t, yt->key_path(name));
    YarnType y;
    r.read_number("density_kg_per_m", y.density_kg_per_m, "a number > 0 (kg/m)", positive);
    r.read_number("stretch_modulus_Pa", y.stretch_modulus_Pa, "a number > 0 (Pa)", positive);
    r.read_number("bending_modulus_Pa", y.bending_modulus_Pa, "a number > 0 (Pa)", positive);
    r.finish();
    defs[name] = {y, line_of(v), top.source().written(v)};
  }
  return defs;
}

// Knit kinds: courses × wales loops that the pattern's tile (docs/models.md §11.2) must cover whole.
void read_knit_pattern(TableReader& p, Scene& s, KnitPattern::Kind kind) {
  KnitPattern k;
  k.kind = kind;
  // ≤ 256: 256 × 256 loops are about 1.3 million DoFs; the run's memory check
  // (driver/memory_estimate.h) refuses what does not fit, located at courses.
  const std::string count = "an integer ≥ 2 and ≤ 256";
  auto in_range = [](long long x) { return x >= 2 && x <= 256; };
  if (auto v = p.table()["courses"]) s.key_lines[p.key_path("courses")] = line_of(*v.node());
  p.read_int("courses", k.courses, count, in_range);
  p.read_int("wales", k.wales, count, in_range);
  p.read_number("course_spacing_m", k.course_spacing_m, "a number > 0 (m)", positive);
  p.finish("(for a knit kind)");
  // Consecutive courses' loop heads run side by side at the same depth, C apart
  // (docs/models.md §11.2): yarns of radius R overlap there unless C ≥ 2R. Checked
  // on a written C only: the default 0.8·W under the woven default radius R = W/2
  // fails it, and scenes and tests rely on that default knit.
  if (k.course_spacing_m != 0.0 && !(k.course_spacing_m >= 2.0 * s.radius_m))
    p.fail_key("course_spacing_m",
               "a loop height ≥ 2·cloth.radius_m" + eq(2.0 * s.radius_m) +
                   " (the loop heads of consecutive courses lie side by side C apart: yarns of radius R overlap "
                   "below 2R)",
               format_number(k.course_spacing_m));
  if (k.course_spacing_m == 0.0) k.course_spacing_m = 0.8 * s.spacing_m;
  if (kind == KnitPattern::Kind::garter && k.courses % 2 != 0)
    p.fail_key("courses", "an even number of courses (a garter tile is one knit and one purl course)",
               std::to_string(k.courses));
  if (kind == KnitPattern::Kind::rib2x2 && k.wales % 4 != 0)
    p.fail_key("wales", "a multiple of 4 wales (a 2×2 rib tile is 2 knit and 2 purl wales)", std::to_string(k.wales));
  s.knit = k;
}

void read_pattern(TableReader& p, Scene& s) {
  int kind = 0;
  p.read_choice("kind", kind, {"plain", "twill", "satin", "stockinette", "garter", "rib2x2"});
  if (auto v = p.table()["kind"]) s.key_lines[p.key_path("kind")] = line_of(*v.node());  // model_factory's errors
  if (kind >= 3) return read_knit_pattern(p, s, static_cast<KnitPattern::Kind>(kind - 3));
  Pattern& pat = s.pattern;
  pat.kind = static_cast<Pattern::Kind>(kind);
  const int grid = std::min(s.warps, s.wefts);
  const std::string grid_txt = "min(cloth.warps, cloth.wefts)" + eq(grid);
  switch (pat.kind) {
    case Pattern::Kind::plain: p.finish("(twill takes over, under, shift; satin takes harness, step)"); return;
    case Pattern::Kind::twill: {
      auto ge1 = [](long long x) { return x >= 1; };
      p.read_int("over", pat.twill_over, "an integer ≥ 1", ge1);
      p.read_int("under", pat.twill_under, "an integer ≥ 1", ge1);
      p.read_int("shift", pat.twill_shift, "an integer with 0 < |shift| < over + under");
      p.finish("(for kind = \"twill\")");
      const int period = pat.twill_over + pat.twill_under;
      if (period > grid)
        p.fail_key(p.table().get("under") ? "under" : "over",
                   "a twill period over + under" + eq(period) + " ≤ " + grid_txt, std::to_string(pat.twill_over));
      if (pat.twill_shift == 0 || std::abs(pat.twill_shift) >= period)
        p.fail_key("shift", "an integer with 0 < |shift| < over + under" + eq(period), std::to_string(pat.twill_shift));
      return;
    }
    case Pattern::Kind::satin: {
      p.read_int("harness", pat.satin_harness,
                 "an integer ≥ 5 (a regular satin needs 1 < step < harness−1 with gcd(step, harness) = 1)",
                 [](long long x) { return x >= 5; });
      p.read_int("step", pat.satin_step, "an integer with 1 < step < harness−1 and gcd(step, harness) = 1");
      p.finish("(for kind = \"satin\")");
      const int n = pat.satin_harness, k = pat.satin_step;
      if (n > grid) p.fail_key("harness", "a harness ≤ " + grid_txt, std::to_string(n));
      if (!(k > 1 && k < n - 1 && std::gcd(k, n) == 1))
        p.fail_key("step",
                   "an integer with 1 < step < harness−1" + eq(n - 1) + " and gcd(step, harness" + eq(n) + ") = 1",
                   std::to_string(k));
      return;
    }
  }
}

void read_cloth(TableReader& top, Scene& s, const std::map<std::string, YarnTypeDef>& defs) {
  auto c = top.subtable("cloth");
  const std::string yarns_expected = "an integer ≥ 3 and ≤ " + std::to_string(kMaxYarns);
  auto yarn_count = [](long long x) { return x >= 3 && x <= kMaxYarns; };
  const std::string names_expected = "a non-empty array of yarn type names (strings)";
  if (c) {
    c->read_int("warps", s.warps, yarns_expected, yarn_count);
    c->read_int("wefts", s.wefts, yarns_expected, yarn_count);
    c->read_number("spacing_m", s.spacing_m, "a number > 0 (m)", positive);
    const double L = s.spacing_m;
    // R/L < 1/√2 keeps the shear lock angle φ_l = 2 arcsin(R/L) inside [0, π/2) (docs/models.md §3.4.3).
    const std::string lock = ", so that the shear lock angle 2·arcsin(R/L) stays below π/2";
    c->read_number("radius_m", s.radius_m, "a number > 0 and < cloth.spacing_m/√2" + eq(L / std::sqrt(2.0)) + lock,
                   [L](double r) { return r > 0.0 && r * std::sqrt(2.0) < L; });
    if (s.radius_m * std::sqrt(2.0) >= s.spacing_m)  // only reachable with the default radius
      c->fail_key("spacing_m", "a number > √2·cloth.radius_m" + eq(std::sqrt(2.0) * s.radius_m) + lock,
                  format_number(s.spacing_m));
    c->read_bool("sliding", s.sliding);
    c->read_string_array("warp_yarn_types", s.warp_yarn_types, names_expected);
    c->read_string_array("weft_yarn_types", s.weft_yarn_types, names_expected);
    if (auto p = c->subtable("pattern")) read_pattern(*p, s);
    c->finish();
    s.key_lines["cloth"] = c->line();  // the size is checked against memory at run time
    for (const char* k : {"warps", "wefts"})
      if (auto v = c->table()[k]) s.key_lines[c->key_path(k)] = line_of(*v.node());
  }

  // Every referenced name must exist; "default" exists implicitly.
  std::string defined;
  for (const auto& [name, d] : defs) defined += (defined.empty() ? "" : ", ") + name;
  const std::string expected = "a yarn type defined in [yarn_types] (" +
                               (defined.empty() ? std::string("none defined") : "defined: " + defined) +
                               "; \"default\" is always available)";
  std::set<std::string> used;
  for (const char* key : {"warp_yarn_types", "weft_yarn_types"}) {
    const auto& names = std::string(key) == "warp_yarn_types" ? s.warp_yarn_types : s.weft_yarn_types;
    for (size_t k = 0; k < names.size(); ++k) {
      if (names[k] != "default" && !defs.count(names[k])) {
        const toml::node* arr = c ? c->table().get(key) : nullptr;
        const toml::node* elem = arr && arr->as_array() ? arr->as_array()->get(k) : nullptr;
        if (elem) c->fail_at(*elem, key, expected);
        top.source().fail(c ? c->line() : 1, std::string("cloth.") + key, '"' + names[k] + "\" (the default)",
                          expected);
      }
      used.insert(names[k]);
    }
  }
  s.yarn_types.clear();
  for (const auto& [name, d] : defs) {
    if (!used.count(name))
      top.source().fail(d.line, "yarn_types." + name, d.written,
                        "a yarn type used by cloth.warp_yarn_types or cloth.weft_yarn_types");
    s.yarn_types[name] = d.type;
  }
  if (used.count("default") && !defs.count("default")) s.yarn_types["default"] = YarnType{};
}

void read_contact(TableReader& top, Scene& s) {
  auto c = top.subtable("contact");
  if (!c) return;
  ContactParams& p = s.contact;
  int m = 0;
  if (c->read_choice("shear_model", m, {"gong", "cirio"}))
    p.shear_model = m == 0 ? ContactParams::ShearModel::gong : ContactParams::ShearModel::cirio;
  if (c->read_choice("friction_model", m, {"gong", "cirio"}))
    p.friction_model = m == 0 ? ContactParams::FrictionModel::gong : ContactParams::FrictionModel::cirio;
  c->read_number("shear_modulus_Pa", p.shear_modulus_Pa, "a number ≥ 0 (Pa)", non_negative);
  c->read_number("friction_coefficient", p.friction_coefficient, "a number ≥ 0", non_negative);
  c->read_number("friction_stiffness_N_per_m", p.friction_stiffness_N_per_m, "a number ≥ 0 (N/m)", non_negative);
  c->read_number("friction_damping_Ns_per_m", p.friction_damping_Ns_per_m, "a number ≥ 0 (N·s/m)", non_negative);
  c->read_number("tanh_sharpness_per_m", p.tanh_sharpness_per_m, "a number > 0 (1/m)", positive);
  c->read_number("parallel_stiffness_N_per_m2", p.parallel_stiffness_N_per_m2, "a number ≥ 0 (N/m²)", non_negative);
  c->read_number("lock_exponent", p.lock_exponent, "a number > 0", positive);
  c->read_number("lock_sigma", p.lock_sigma, "a number > 0", positive);
  c->finish();
}

void read_pose(TableReader& top, Scene& s) {
  auto p = top.subtable("pose");
  if (!p) return;
  int kind = 0;
  if (p->read_choice("kind", kind, {"flat", "upright"})) s.pose = kind == 0 ? Scene::Pose::flat : Scene::Pose::upright;
  p->read_number("height_m", s.height_m, "a number (m)");
  p->finish();
}

// shear_law = "linear_lock" | "spline"; the spline law's knot angles and the tangent stiffness at
// each (docs/models.md §6.4.1). Knots and knot values belong to the spline law only.
void read_shear_law(TableReader& f, FemSettings& fem) {
  int law = 0;
  if (f.read_choice("shear_law", law, {"linear_lock", "spline"}))
    fem.shear_law = law == 0 ? FemSettings::ShearLaw::linear_lock : FemSettings::ShearLaw::spline;
  const bool spline = fem.shear_law == FemSettings::ShearLaw::spline;
  const std::string knots_expected = "an array of 1 to " + std::to_string(FemSettings::kMaxShearKnots) +
                                     " increasing shear angles in (0, 1.5] rad, with fem.shear_law = \"spline\"";
  std::vector<double> knots;
  if (f.read_number_array("shear_knots_rad", knots, knots_expected, [&](const std::vector<double>& k) {
        if (!spline || k.empty() || k.size() > FemSettings::kMaxShearKnots) return false;
        for (size_t i = 0; i < k.size(); ++i)
          if (!(k[i] > (i ? k[i - 1] : 0.0)) || k[i] > 1.5) return false;
        return true;
      }))
    fem.shear_knots_rad = knots;
  else if (spline) fem.shear_knots_rad = {0.1, 0.2, 0.3, 0.4};
  for (int i = 0; i < FemSettings::kMaxShearKnots; ++i) {
    const std::string key = shear_knot_key(i);
    const std::string expected = "a number > 0 (N/m), the tangent shear stiffness at knot " + std::to_string(i + 1) +
                                 " of fem.shear_knots_rad (fem.shear_law = \"spline\" with " + std::to_string(i + 1) +
                                 " knots or more)";
    const bool allowed = i < static_cast<int>(fem.shear_knots_rad.size());
    f.read_number(key, fem.shear_knot_N_per_m[i], expected, [&](double x) { return allowed && x > 0; });
  }
}

void read_fem(TableReader& top, Scene& s) {
  auto f = top.subtable("fem");
  if (!f) return;
  FemSettings& fem = s.fem;
  s.key_lines["fem"] = f->line();
  f->read_int("stride", fem.stride, "an integer ≥ 1", [](long long x) { return x >= 1; });
  if (s.knit) {
    // The continuum of a knit lies on its contact grid (docs/models.md §11.9): 2·wales columns, courses + 1 rows.
    const int columns = 2 * s.knit->wales - 1, rows = s.knit->courses;
    if (columns % fem.stride != 0 || rows % fem.stride != 0)
      f->fail_key("stride",
                  "an integer ≥ 1 dividing the knit's contact grid: 2·cloth.pattern.wales − 1" + eq(columns) +
                      " and cloth.pattern.courses" + eq(rows),
                  std::to_string(fem.stride));
    // What has no knit counterpart: a mesh file, the woven border strip and grid-line widths (one
    // crossing spacing), the woven node masses, and a mass per area other than the yarn level's.
    for (const char* key :
         {"mesh_file", "border_strip", "grid_line_bending", "yarn_node_mass", "areal_density_kg_per_m2", "tile_law"})
      if (const toml::node* n = f->table().get(key))
        f->fail_at(*n, key,
                   "no " + std::string(key) +
                       " in a knit scene (its continuum is the contact grid's mesh with the yarn level's mass per "
                       "area, docs/models.md §11.9)");
  } else if ((s.wefts - 1) % fem.stride != 0 || (s.warps - 1) % fem.stride != 0)
    f->fail_key("stride",
                "an integer ≥ 1 dividing cloth.wefts − 1" + eq(s.wefts - 1) + " and cloth.warps − 1" + eq(s.warps - 1),
                std::to_string(fem.stride));
  namespace fs = std::filesystem;
  const fs::path base = fs::path(s.source).parent_path();
  for (auto [key, out] : {std::pair<const char*, std::string*>{"mesh_file", &fem.mesh_file},
                          std::pair<const char*, std::string*>{"parameter_file", &fem.parameter_file},
                          std::pair<const char*, std::string*>{"tile_law", &fem.tile_law}}) {
    std::string rel;
    if (!f->read_string(key, rel, "a non-empty path (string), relative to the scene file's directory",
                        [](const std::string& x) { return !x.empty(); }))
      continue;
    const fs::path p = fs::path(rel).is_absolute() ? fs::path(rel) : (base / rel).lexically_normal();
    std::error_code ec;
    if (!fs::is_regular_file(p, ec))
      f->fail_at(*f->table().get(key), key,
                 "an existing file, relative to the scene file's directory (looked for " + p.string() + ")");
    *out = p.string();
  }
  f->read_bool("border_strip", fem.border_strip);
  f->read_bool("grid_line_bending", fem.grid_line_bending);
  if (fem.grid_line_bending && !fem.mesh_file.empty())
    f->fail_key("grid_line_bending", "false with a mesh_file (grid lines exist on the grid mesh only)", "true");
  f->read_bool("yarn_node_mass", fem.yarn_node_mass);
  if (fem.yarn_node_mass && (fem.stride != 1 || !fem.mesh_file.empty()))
    f->fail_key("yarn_node_mass",
                "false unless stride = 1 on the grid mesh (a vertex at every crossing, without mesh_file)", "true");
  f->read_number("areal_density_kg_per_m2", fem.areal_density_kg_per_m2, "a number > 0 (kg/m²)", positive);
  f->read_number("warp_stretch_N_per_m", fem.warp_stretch_N_per_m, "a number > 0 (N/m)", positive);
  f->read_number("weft_stretch_N_per_m", fem.weft_stretch_N_per_m, "a number > 0 (N/m)", positive);
  f->read_number("shear_N_per_m", fem.shear_N_per_m, "a number > 0 (N/m)", positive);
  f->read_number("shear_lock_angle_rad", fem.shear_lock_angle_rad, "a number > 0 (rad)", positive);
  f->read_number("shear_lock_exponent", fem.shear_lock_exponent, "a number > 0", positive);
  f->read_number("warp_bending_N_m", fem.warp_bending_N_m, "a number > 0 (N·m)", positive);
  f->read_number("weft_bending_N_m", fem.weft_bending_N_m, "a number > 0 (N·m)", positive);
  f->read_number("diagonal_bending_N_m", fem.diagonal_bending_N_m, "a number > 0 (N·m)", positive);
  if (f->read_number("stretch_coupling_N_per_m", fem.stretch_coupling_N_per_m,
                     "a number > 0 (N/m) below √(warp·weft stretch)", positive))
    fem.stretch_coupling_line = line_of(*f->table().get("stretch_coupling_N_per_m"));
  f->read_number("warp_stretch_quartic_N_per_m", fem.warp_stretch_quartic_N_per_m, "a number > 0 (N/m)", positive);
  f->read_number("weft_stretch_quartic_N_per_m", fem.weft_stretch_quartic_N_per_m, "a number > 0 (N/m)", positive);
  f->read_number("areal_stretch_quartic_N_per_m", fem.areal_stretch_quartic_N_per_m, "a number > 0 (N/m)", positive);
  read_shear_law(*f, fem);
  f->finish();
}

// node = [i, j] inside the grid, not used twice, on the FEM lattice when stride > 1.
// A knit scene's node = [i, j] names stitch contact j of contact row i (docs/models.md §11.7).
NodeRef read_node(TableReader& t, const Scene& s, std::map<std::pair<int, int>, std::string>& taken) {
  const int rows = s.knit ? s.knit->courses + 1 : s.wefts, columns = s.knit ? 2 * s.knit->wales : s.warps;
  const std::string expected =
      s.knit ? "[i, j], a stitch contact: integers 0 ≤ i ≤ cloth.pattern.courses" + eq(s.knit->courses) +
                   " (contact row) and 0 ≤ j < 2·cloth.pattern.wales" + eq(columns) + " (contact column)"
             : "[i, j] with integers 0 ≤ i < cloth.wefts" + eq(s.wefts) + " and 0 ≤ j < cloth.warps" + eq(s.warps);
  const toml::node* n = t.get("node");
  if (!n) t.fail_missing("node", expected);
  const auto* a = n->as_array();
  if (!a || a->size() != 2 || !a->get(0)->as_integer() || !a->get(1)->as_integer()) t.fail_at(*n, "node", expected);
  const long long i = a->get(0)->as_integer()->get(), j = a->get(1)->as_integer()->get();
  if (i < 0 || i >= rows || j < 0 || j >= columns) t.fail_at(*n, "node", expected);
  const int st = s.fem.stride;
  if (st > 1 && (i % st != 0 || j % st != 0))
    t.fail_at(*n, "node", "a node on the FEM lattice: i and j multiples of fem.stride" + eq(st));
  const auto key = std::make_pair(static_cast<int>(i), static_cast<int>(j));
  if (auto it = taken.find(key); it != taken.end())
    t.fail_at(*n, "node", "a node not already pinned or held (" + it->second + " uses it)");
  taken[key] = t.key_path("node");
  return NodeRef{static_cast<int>(i), static_cast<int>(j)};
}

// Prescribed motion of a handle's target (docs/models.md §3.10): velocity_m_per_s
// from start_s (default 0) until stop_s (default: the end of the run).
void read_handle_motion(TableReader& h, Handle& handle) {
  const bool moves =
      h.read_vec3("velocity_m_per_s", handle.velocity_m_per_s, "an array of 3 finite numbers [x, y, z] (m/s)");
  h.read_number("start_s", handle.start_s, "a finite number ≥ 0 (s)", non_negative);
  const double start = handle.start_s;
  h.read_number("stop_s", handle.stop_s, "a finite number > start_s" + eq(start) + " (s)",
                [start](double x) { return x > start; });
  const std::string still = "no timing without velocity_m_per_s (a handle without it does not move)";
  for (const char* key : {"start_s", "stop_s"})
    if (!moves && h.table().get(key)) h.fail_key(key, still, "");
}

void read_boundary(TableReader& top, Scene& s) {
  std::map<std::pair<int, int>, std::string> taken;
  for (TableReader& p : top.table_array("pins")) {
    s.pins.push_back(read_node(p, s, taken));
    p.finish();
  }
  for (TableReader& h : top.table_array("handles")) {
    Handle handle;
    handle.node = read_node(h, s, taken);
    h.read_number("stiffness_N_per_m", handle.stiffness_N_per_m, "a number > 0 (N/m)", positive);
    read_handle_motion(h, handle);
    h.finish();
    s.handles.push_back(handle);
  }
}

// [knit] holds the knit-specific stiffnesses; a knit scene rejects the tables
// the knit model does not support yet.
void read_knit(TableReader& top, Scene& s) {
  auto k = top.subtable("knit");
  if (k && !s.knit) {
    const auto first = k->table().begin();
    const std::string expected =
        "no [knit] table in a woven scene (it needs cloth.pattern.kind = \"stockinette\", "
        "\"garter\" or \"rib2x2\")";
    if (first == k->table().end()) top.source().fail(k->line(), "knit", "[knit]", expected);
    k->fail_at(first->second, first->first.str(), expected);
  }
  if (k) {
    k->read_number("roll_stiffness_N", s.knit->roll_stiffness_N, "a number ≥ 0 (N)", non_negative);
    k->read_number("stitch_length_stiffness_N", s.knit->stitch_length_stiffness_N, "a number ≥ 0 (N)", non_negative);
    k->read_number("compression_stiffness_N_per_m", s.knit->compression_stiffness_N_per_m, "a number ≥ 0 (N/m)",
                   non_negative);
    k->finish();
  }
  if (!s.knit) return;
  for (const char* table : {"wind", "obstacles"})
    if (const toml::node* n = top.table().get(table))
      top.source().fail(line_of(*n), table, "[" + std::string(table) + "]",
                        "no [" + std::string(table) + "] in a knit scene (not supported for knits yet)");
}

void read_loads(TableReader& top, Scene& s) {
  if (auto g = top.subtable("gravity")) {
    g->read_vec3("acceleration_m_per_s2", s.gravity_m_per_s2, "an array of 3 numbers [x, y, z] (m/s²)");
    g->finish();
  }
  if (auto w = top.subtable("wind")) {
    w->read_vec3("velocity_m_per_s", s.wind_velocity_m_per_s, "an array of 3 numbers [x, y, z] (m/s)");
    w->read_number("air_density_kg_per_m3", s.air_density_kg_per_m3, "a number ≥ 0 (kg/m³)", non_negative);
    w->read_number("drag_Ns_per_m3", s.wind_drag_Ns_per_m3, "a number ≥ 0 (N·s/m³)", non_negative);
    w->finish();
  }
  if (auto d = top.subtable("damping")) {
    d->read_number("yarn_viscosity_Pa_s", s.yarn_viscosity_Pa_s, "a finite number ≥ 0 (Pa·s)",
                   [](double x) { return std::isfinite(x) && x >= 0.0; });
    if (const toml::node* n = d->table().get("yarn_viscosity_Pa_s"))
      s.key_lines[d->key_path("yarn_viscosity_Pa_s")] = line_of(*n);
    d->finish();
  }
}

void read_time(TableReader& top, Scene& s) {
  auto t = top.subtable("time");
  if (t) {
    t->read_number("duration_s", s.duration_s, "a number > 0 (s)", positive);
    t->read_number("dt_s", s.dt_s, "a number > 0 (s)", positive);
    t->read_number("output_interval_s", s.output_interval_s, "a number > 0 (s)", positive);
    t->read_string("integrator", s.integrator, "a non-empty integrator name (string)",
                   [](const std::string& x) { return !x.empty(); });
    t->read_bool("adaptive", s.adaptive);
    t->read_string("linear_solver", s.linear_solver, "a non-empty linear solver name (string)",
                   [](const std::string& x) { return !x.empty(); });
    t->read_number("rtol", s.rtol, "a number ≥ 1e-12 and < 1 (smaller tolerances are below round-off)",
                   [](double x) { return x >= 1e-12 && x < 1.0; });
    t->read_number("atol", s.atol, "a number > 0", positive);
    t->read_bool("error_estimate", s.error_estimate);
    t->read_number("settle_after_s", s.settle_after_s, "a finite number ≥ 0 (s)",
                   [](double x) { return std::isfinite(x) && x >= 0.0; });
    t->read_number("settle_dt_s", s.settle_dt_s, "a number > 0 (s)", positive);
    t->read_bool("exact_contact_jacobian", s.exact_contact_jacobian);
    t->read_number("accuracy_m", s.accuracy_m, "a finite number > 0 (m)",
                   [](double x) { return std::isfinite(x) && x > 0.0; });
    t->finish();
    s.key_lines["time"] = t->line();
    for (auto&& [k, v] : t->table()) s.key_lines[t->key_path(k.str())] = line_of(v);
  }
  const auto bad = time_settings_violation(s, [&](const std::string& key) { return s.key_lines.count(key) ? 1 : 0; });
  if (!bad) return;
  const auto line = s.key_lines.find(bad->key);
  const std::string value = line != s.key_lines.end() ? bad->value : bad->value + " (the default)";
  top.source().fail(line != s.key_lines.end() ? line->second : t ? t->line() : 1, bad->key, value, bad->expected);
}

// [compat] (docs/published_code.md): the published code's convention where the lab differs,
// one key per difference. The exact contact Jacobian (§3.6.1) is derived for the lab's F_n only.
void read_compat(TableReader& top, Scene& s) {
  auto c = top.subtable("compat");
  if (!c) return;
  int stretch = s.compat.normal_force_on_centre_lines ? 1 : 0;
  if (c->read_choice("normal_force_stretch", stretch, {"crimped", "centre_line"}))
    s.compat.normal_force_on_centre_lines = stretch == 1;
  int diagonals = s.compat.wind_alternating_diagonals ? 1 : 0;
  if (c->read_choice("wind_diagonals", diagonals, {"one", "alternating"}))
    s.compat.wind_alternating_diagonals = diagonals == 1;
  const auto choose = [&](const char* key, bool& flag, const std::vector<std::string>& values) {
    int value = flag ? 1 : 0;
    if (c->read_choice(key, value, values)) flag = value == 1;
  };
  choose("bending_sliding_force", s.compat.bending_sliding_theta, {"theta_squared", "theta"});
  choose("parallel_contact_sign", s.compat.parallel_contact_attractive, {"repulsive", "attractive"});
  choose("ring_over_under", s.compat.ring_unsigned, {"pattern", "none"});
  choose("shear_lock_angle", s.compat.shear_lock_actual_angle, {"mirrored", "actual"});
  choose("shear_lock_derivative", s.compat.shear_lock_published_derivative, {"exact", "published"});
  choose("shear_quadrants", s.compat.shear_interior_only, {"every_node", "interior"});
  choose("normal_force_bending_uv", s.compat.normal_force_bending_at_rest, {"current", "rest"});
  const toml::node* key = c->table().get("normal_force_stretch");
  const toml::node* angle_key = c->table().get("shear_lock_angle");
  const toml::node* rest_key = c->table().get("normal_force_bending_uv");
  c->finish();
  const double exponent = s.contact.lock_exponent;  // γ < 0 beyond φ̄ at the actual angle: integer powers only
  if (s.compat.shear_lock_actual_angle && !(exponent >= 2.0 && exponent == std::floor(exponent)))
    top.source().fail(line_of(*angle_key), c->key_path("shear_lock_angle"), "\"actual\"",
                      "\"mirrored\" while contact.lock_exponent = " + format_number(exponent) +
                          " (the actual angle needs an integer exponent >= 2)");
  if (s.compat.normal_force_bending_at_rest && s.exact_contact_jacobian)
    top.source().fail(line_of(*rest_key), c->key_path("normal_force_bending_uv"), "\"rest\"",
                      "\"current\" while time.exact_contact_jacobian = true (the exact derivatives of F_n "
                      "exist for the current sliding coordinates only)");
  if (s.compat.normal_force_on_centre_lines && s.exact_contact_jacobian)
    top.source().fail(line_of(*key), c->key_path("normal_force_stretch"), "\"centre_line\"",
                      "\"crimped\" while time.exact_contact_jacobian = true (the exact derivatives of F_n "
                      "exist for the crimped stretch only)");
}

void read_terms(TableReader& top, Scene& s) {
  auto t = top.subtable("terms");
  if (!t) return;
  TermSwitches& w = s.terms;
  t->read_bool("stretch", w.stretch);
  t->read_bool("bending", w.bending);
  t->read_bool("shear", w.shear);
  t->read_bool("parallel_contact", w.parallel_contact);
  t->read_bool("friction", w.friction);
  t->read_bool("gravity", w.gravity);
  t->read_bool("wind", w.wind);
  t->read_bool("handles", w.handles);
  t->read_bool("inertia", w.inertia);
  int stretch_hessian = w.stretch_projected_step_hessian ? 0 : 1;
  if (t->read_choice("stretch_step_hessian", stretch_hessian, {"projected", "exact"}))
    w.stretch_projected_step_hessian = stretch_hessian == 0;
  t->finish();
}

}  // namespace

SceneError::SceneError(std::string file_, int line_, std::string key_, std::string value_, std::string expected_)
    : std::runtime_error(file_ + ":" + std::to_string(line_) + ": key '" + key_ + "': got " + value_ + ", expected " +
                         expected_),
      file(std::move(file_)),
      key(std::move(key_)),
      value(std::move(value_)),
      expected(std::move(expected_)),
      line(line_) {}

Scene parse_scene(const std::string& toml_text, const std::string& source_name) {
  const Source src(toml_text, source_name);
  toml::table root;
  try {
    root = toml::parse(std::string_view(toml_text), std::string_view(source_name));
  } catch (const toml::parse_error& e) {
    const int line = static_cast<int>(e.source().begin.line);
    const std::string text = src.line_text(line);
    src.fail(line, "(syntax)", text.empty() ? "(end of line)" : text,
             "valid TOML (" + std::string(e.description()) + ")");
  }

  Scene s;
  s.source = source_name;
  s.text = toml_text;
  TableReader top(src, root, "");
  // Unknown tables first: a misspelt table name is the likeliest error.
  top.declare({"cloth", "yarn_types", "contact", "pose", "pins", "handles", "gravity", "wind", "damping", "time",
               "terms", "compat", "fem", "obstacles", "obstacle_contact", "self_contact", "knit", "measures", "mixed"});
  top.finish();
  const auto yarn_defs = read_yarn_types(top);
  read_cloth(top, s, yarn_defs);
  read_knit(top, s);
  read_contact(top, s);
  read_pose(top, s);
  read_fem(top, s);
  read_boundary(top, s);
  read_loads(top, s);
  read_time(top, s);
  read_terms(top, s);
  read_compat(top, s);
  scene_detail::read_obstacles(top, s);
  scene_detail::read_measures(top, s);
  scene_detail::read_mixed(top, s);
  return s;
}

Scene load_scene(const std::string& path) {
  auto unreadable = [&] { return SceneError(path, 0, "(file)", path, "a readable scene file"); };
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) throw unreadable();
  std::ifstream in(path, std::ios::binary);
  if (!in) throw unreadable();
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw unreadable();
  return parse_scene(text.str(), path);
}

}  // namespace wl
