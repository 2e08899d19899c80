// A validated scene in SI units (docs/design.md §4). Produced from a TOML
// file by load_scene(); every field has its unit in its name or comment.
#pragma once
#include <array>
#include <functional>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace wl {

struct YarnType {
  double density_kg_per_m = 0.002;     // linear density ρ
  double stretch_modulus_Pa = 5e5;     // Y, k_s = Y·πR² (docs/models.md §3.2)
  double bending_modulus_Pa = 1.4e-4;  // B, k_b = B·πR² (docs/models.md §3.3)
};

struct Pattern {
  enum class Kind { plain, twill, satin } kind = Kind::plain;
  int twill_over = 2, twill_under = 2, twill_shift = 1;  // n/m twill, shift per row
  int satin_harness = 5, satin_step = 2;                 // N-harness satin, step k
};

// A weft-knitted cloth (docs/models.md §11): courses of loops, one yarn per
// course, each loop (course r, wale c) pulled through the loop below it as a
// knit or a purl stitch.
struct KnitPattern {
  enum class Kind { stockinette, garter, rib2x2 } kind = Kind::stockinette;
  int courses = 8;                               // loop rows (yarns), ≥ 2; garter: even
  int wales = 8;                                 // loop columns, ≥ 2; rib2x2: a multiple of 4
  double course_spacing_m = 0.0;                 // C, loop height; 0: 0.8·cloth.spacing_m (the loop width W)
  double roll_stiffness_N = 1e-5;                // k_t, V ≈ ½ k_t L (ψ − ψ̄)² (docs/models.md §11.4.1)
  double stitch_length_stiffness_N = 0.1;        // k_l, V = ½ k_l L (Δu/L − 1)² (docs/models.md §11.4)
  double compression_stiffness_N_per_m = 100.0;  // κ, V = ½ κ (2R − d)² (docs/models.md §11.6)
};

struct ContactParams {
  enum class ShearModel { cirio, gong } shear_model = ShearModel::gong;
  enum class FrictionModel { gong, cirio } friction_model = FrictionModel::gong;
  double shear_modulus_Pa = 1000.0;            // S; Gong k_sh = S·πR²(1+F_n)·lock, Cirio k_x = S·πR²
  double friction_coefficient = 0.5;           // μ
  double friction_stiffness_N_per_m = 1000.0;  // k_f
  double friction_damping_Ns_per_m = 1000.0;   // d_f
  double tanh_sharpness_per_m = 10.0;          // p in K(x) = tanh(p x) (docs/models.md §5.1)
  double parallel_stiffness_N_per_m2 = 1.0;    // k_c, V = ½ k_c L ReLU(d − Δu)²
  double lock_exponent = 3.0;                  // c
  double lock_sigma = 0.6;                     // σ
};

struct NodeRef {
  int i = 0, j = 0;  // i along the warp (material u), j along the weft (material v)
};

// A handle spring (docs/models.md §3.10). Its target starts at the node's
// initial position and moves at velocity_m_per_s from start_s until stop_s
// (prescribed motion; zero velocity: static).
struct Handle {
  NodeRef node;
  double stiffness_N_per_m = 1e4;
  std::array<double, 3> velocity_m_per_s{0.0, 0.0, 0.0};
  double start_s = 0.0;
  double stop_s = std::numeric_limits<double>::infinity();  // ∞: moves until the run ends
};

// The [fem] key of the spline shear law's i-th knot value (0-based): "shear_knot<i+1>_N_per_m".
inline std::string shear_knot_key(int i) { return "shear_knot" + std::to_string(i + 1) + "_N_per_m"; }

struct FemSettings {
  int stride = 1;              // vertices every `stride`-th crossing
  std::string mesh_file;       // optional VTU with per-vertex rest UV ("" = build from the grid)
  std::string parameter_file;  // optional calibrated parameters ("" = [fem] values / defaults)
  std::string tile_law;        // optional tile law of `weavelab tiles` (docs/models.md §6.9; "" = none)
  std::optional<double> areal_density_kg_per_m2;
  std::optional<double> warp_stretch_N_per_m, weft_stretch_N_per_m;  // per unit width
  std::optional<double> shear_N_per_m;
  std::optional<double> shear_lock_angle_rad;  // shear angle where stiffening starts
  std::optional<double> shear_lock_exponent;
  std::optional<double> warp_bending_N_m, weft_bending_N_m;  // per unit width
  std::optional<double> diagonal_bending_N_m;                // 45° hinges; absent: the mean of warp and weft
  // Stretch law (docs/models.md §6.3.1): warp–weft coupling and quartic stiffening; absent: off.
  std::optional<double> stretch_coupling_N_per_m;
  int stretch_coupling_line = 0;  // its line in the scene file (errors)
  std::optional<double> warp_stretch_quartic_N_per_m, weft_stretch_quartic_N_per_m, areal_stretch_quartic_N_per_m;
  // Shear law (docs/models.md §6.4): linear then lock, or a tangent stiffness interpolated between
  // knots before the lock (§6.4.1). The knot angles γ_1 < … < γ_n of the spline law and the tangent
  // stiffness at each (absent: shear_N_per_m).
  enum class ShearLaw { linear_lock, spline } shear_law = ShearLaw::linear_lock;
  static constexpr int kMaxShearKnots = 6;
  std::vector<double> shear_knots_rad;  // spline law only (the scene's default: 0.1, 0.2, 0.3, 0.4 rad)
  std::array<std::optional<double>, kMaxShearKnots> shear_knot_N_per_m;
  bool border_strip = false;       // bars for the border yarns' outer half spacing (terms/border_stretch.h)
  bool grid_line_bending = false;  // bending of the grid lines instead of hinges (terms/grid_line_bending.h)
  // Vertex masses in the proportions of the yarn level's node masses instead of a third of each
  // triangle's (docs/models.md §6.6); stride 1 on the grid mesh only.
  bool yarn_node_mass = false;
};

// A rigid obstacle (docs/models.md §3.11.1). Its body frame is placed at
// center_m and turned by rotation_deg (about the fixed x, then y, then z axis);
// the shape is given in that frame: plane z ≤ 0; sphere; box |x|,|y|,|z| ≤ half
// extents; cylinder and disk of radius_m about the local z axis, height_m high,
// centred on z = 0. It moves at a constant velocity (0: static).
// A triangle-mesh obstacle's surface as read from its file (obstacle_mesh.h).
struct ObstacleMesh;

struct ObstacleSpec {
  enum class Shape { plane, sphere, box, cylinder, disk, mesh } shape = Shape::plane;
  std::array<double, 3> center_m{0.0, 0.0, 0.0};
  std::array<double, 3> rotation_deg{0.0, 0.0, 0.0};
  std::array<double, 3> velocity_m_per_s{0.0, 0.0, 0.0};
  std::array<double, 3> half_extents_m{0.0, 0.0, 0.0};  // box
  double radius_m = 0.0;                                // sphere, cylinder, disk
  double height_m = 0.0;                                // cylinder (height_m), disk (thickness_m)
  double friction_coefficient = 0.0;                    // μ against the cloth
  // mesh: the file (resolved), the uniform scale applied to its coordinates,
  // and whether it bounds a solid (closed, signed distance) or is a two-sided
  // surface (unsigned distance), docs/models.md §3.11.9.
  std::string mesh_file;
  double scale = 1.0;
  enum class Side { outside, both } side = Side::outside;
  std::shared_ptr<const ObstacleMesh> mesh;  // read, scaled and checked at load
  int line = 0;                              // its [[obstacles]] entry in the scene file
};

// Node–obstacle contact (docs/models.md §3.11.2–§3.11.3); absent values follow
// the stated rules (activation distance ½ cloth.spacing_m; stiffness from the
// heaviest node's weight).
struct ObstacleContactParams {
  std::optional<double> activation_distance_m;  // d̂
  std::optional<double> stiffness_N_per_m;      // κ
  double friction_speed_m_per_s = 1e-3;         // ε_v of the smoothed Coulomb law
  bool segment_edges = false;                   // segments kept off sharp edges (§3.11.10)
  bool projected_step_hessian = true;           // step_hessian: "projected" (true) or "exact" (§3.11.2)
};

// Cloth–cloth contact (docs/models.md §3.11.7), off unless enabled; absent
// values follow the obstacles' rules.
struct SelfContactParams {
  bool enabled = false;
  std::optional<double> activation_distance_m;  // d̂
  std::optional<double> stiffness_N_per_m;      // κ
  int line = 0;                                 // the [self_contact] table in the scene file
};

// What a run measures on its last output frame and writes into summary.json's
// "measures" (docs/models.md §3.11.6); nothing unless asked for.
struct MeasureSettings {
  // The drape coefficient and fold count of the cloth over its pedestal (the
  // first disk, cylinder or sphere obstacle), driver/drape_measure.h.
  bool drape = false;
  double drape_pixel_m = 1e-4;      // side of the raster's square pixels
  double fold_prominence_m = 5e-4;  // a fold's outer radius stands this far above the minima beside it
  int line = 0;                     // the [measures] table in the scene file
};

// [mixed] (docs/models.md §12.1): the crossings the mixed model simulates at yarn level, the
// continuum elsewhere. Only the model "mixed" reads it.
struct MixedSettings {
  bool present = false;                         // the scene has a [mixed] table
  std::vector<std::array<int, 4>> yarn_region;  // rectangles [i0, j0, i1, j1] of crossings, inclusive
  int line = 0;                                 // the [mixed] table in the scene file
};

struct TermSwitches {
  bool stretch = true, bending = true, shear = true, parallel_contact = true, friction = true;
  bool gravity = true, wind = true, handles = true, inertia = true;
  // stretch_step_hessian: "projected" (true) or "exact" (docs/models.md §3.2)
  bool stretch_projected_step_hessian = false;
};

// [compat]: switches to a convention of the authors' published code of Gong et al. 2022, one
// per difference (docs/published_code.md); every default is the lab's model (docs/models.md).
struct CompatSettings {
  // The stretch part of the contact normal force F_n evaluated on the actual centre lines and the
  // outer ring left uncrimped, bending alone on the crimped copies (docs/published_code.md rows 1–2);
  // false: stretch and bending on the crimped copies of every node (docs/models.md §3.6, §5.3).
  bool normal_force_on_centre_lines = false;
  // Wind triangles split each grid cell along (i, j)–(i+1, j+1) when i + j is even and along
  // (i+1, j)–(i, j+1) when it is odd (docs/published_code.md row 13); false: every cell along
  // (i, j)–(i+1, j+1) (docs/models.md §3.9).
  bool wind_alternating_diagonals = false;
  // F_u of bending k_b θ/U² instead of k_b θ²/U² (docs/published_code.md row 6).
  bool bending_sliding_theta = false;
  // Parallel contact F_u0 = +k_cL·ReLU(d − Δu), the negative of the penalty's gradient (row 12).
  bool parallel_contact_attractive = false;
  // Outer-ring crossings carry the over/under sign +1 whatever the pattern (row 22).
  bool ring_unsigned = false;
  // Gong's lock: γ and g at φ itself, not at the mirrored angle φ* (row 9).
  bool shear_lock_actual_angle = false;
  // Gong's lock: the published ∂k/∂x, with 1 − f²·g′ in place of (1 − f²)·g′ (row 8).
  bool shear_lock_published_derivative = false;
  // The bending part of F_n with the sliding coordinates at rest (docs/published_code.md row 24).
  bool normal_force_bending_at_rest = false;
  // Shear quadrants only around interior crossings, none centred on the outer ring (row 23).
  bool shear_interior_only = false;
};

struct Scene {
  std::string source;  // file it came from
  std::string text;    // its text, read once at load (what the run simulates)
  // Line of each key written in the file's [time] table ("time.dt_s" → 12) and
  // of the table itself ("time"), of the [cloth] size keys and cloth.pattern.kind, of the
  // [fem] table ("fem") and of damping.yarn_viscosity_Pa_s; absent keys are absent here.
  std::map<std::string, int> key_lines;

  // Woven cloth
  int warps = 17;           // warp yarns (each runs along u, j fixed)
  int wefts = 17;           // weft yarns (each runs along v, i fixed)
  double spacing_m = 1e-3;  // L
  double radius_m = 5e-4;   // R
  bool sliding = true;      // false: u, v frozen, 3 DoFs per node
  Pattern pattern;
  // Set when [cloth.pattern] names a knit: the cloth is knitted (models/knit);
  // warps, wefts and the woven pattern are then unused, and the courses take
  // their yarn types from warp_yarn_types (cycled over courses).
  std::optional<KnitPattern> knit;
  // Yarn types by name; a scene file holds exactly the types its cloth uses
  // ("default" = YarnType{} when referenced but not defined).
  std::map<std::string, YarnType> yarn_types{{"default", YarnType{}}};
  std::vector<std::string> warp_yarn_types{"default"};  // cycled over warps
  std::vector<std::string> weft_yarn_types{"default"};  // cycled over wefts
  ContactParams contact;

  // Pose and boundary
  enum class Pose { flat, upright } pose = Pose::upright;
  double height_m = 0.0;  // z of the top row (upright) or of the sheet (flat)
  std::vector<NodeRef> pins;
  std::vector<Handle> handles;

  // Loads
  std::array<double, 3> gravity_m_per_s2{0.0, 0.0, -9.81};
  std::array<double, 3> wind_velocity_m_per_s{0.0, 0.0, 0.0};
  double air_density_kg_per_m3 = 0.0;  // ρ_w (normal pressure)
  double wind_drag_Ns_per_m3 = 0.0;    // d_w (tangential drag per area)
  // Yarn-internal stretch damping, a Kelvin–Voigt viscosity η (docs/models.md
  // §3.12); 0, the sources' model, adds no term.
  double yarn_viscosity_Pa_s = 0.0;

  // Time
  double duration_s = 0.5;
  double dt_s = 1e-3;
  double output_interval_s = 0.01;
  std::string integrator = "be-linear";
  std::string linear_solver = "auto";  // step matrix solver (integrators/sparse_solver.h); the run checks the name
  bool adaptive = false;
  double rtol = 1e-6, atol = 1e-9;
  // From settle_after_s on, fixed steps of settle_dt_s (0: none): a drape that
  // has fallen settles under backward Euler's numerical damping (docs/models.md §3.11.6).
  double settle_after_s = 0.0, settle_dt_s = 0.0;
  // Estimate the run's global time error (driver/time_error.h).
  bool error_estimate = false;
  // Target of the run's time error, mean over frames of the RMS over nodes [m];
  // 0: none. When set the run chooses its integrator and tolerance (docs/models.md §7.9).
  double accuracy_m = 0.0;
  // Chain the exact derivatives of the contact normal force F_n and friction's
  // F_u into the Jacobians and parameter derivatives (docs/models.md §3.6.1);
  // false: they are frozen inputs (§5.4).
  bool exact_contact_jacobian = false;

  TermSwitches terms;
  CompatSettings compat;
  FemSettings fem;
  std::vector<ObstacleSpec> obstacles;
  ObstacleContactParams obstacle_contact;
  SelfContactParams self_contact;
  MeasureSettings measures;
  MixedSettings mixed;

  int nodes_u() const { return wefts; }  // nodes along a warp = number of wefts
  int nodes_v() const { return warps; }
  const YarnType& warp_type(int j) const { return yarn_types.at(warp_yarn_types[j % warp_yarn_types.size()]); }
  const YarnType& weft_type(int i) const { return yarn_types.at(weft_yarn_types[i % weft_yarn_types.size()]); }
};

// A scene that fails validation. what() reads
//   "<file>:<line>: key '<key>': got <value>, expected <expected>".
class SceneError : public std::runtime_error {
 public:
  SceneError(std::string file, int line, std::string key, std::string value, std::string expected);
  std::string file, key, value, expected;
  int line;
};

// The rules of a run's time settings, shared by the scene reader and the
// command-line overrides: duration_s, dt_s, output_interval_s finite and > 0
// with dt_s ≤ output_interval_s ≤ duration_s; at most kMaxSteps fixed steps
// (duration_s / dt_s, fixed-step runs) and kMaxFrames output frames; rtol in
// (0, 1), atol finite and > 0.
inline constexpr double kMaxSteps = 1e7;
inline constexpr double kMaxFrames = 1e5;
struct SettingViolation {
  std::string key;       // "time.dt_s"
  std::string value;     // the value, shortest round-trip form
  std::string expected;  // what the rule wants
};
// The first violated rule, or nothing. `rank(key)` says where a key's value
// came from (0 default, 1 scene file, 2 command line); a rule between two keys
// blames the one with the higher rank (the first one on a tie).
std::optional<SettingViolation> time_settings_violation(const Scene& scene,
                                                        const std::function<int(const std::string&)>& rank);

// Reads and validates a scene; throws SceneError (missing file: line 0).
// The format is documented in scene.cpp and experiments/scenes/README.md.
Scene load_scene(const std::string& path);
// Same, from text; `source_name` names the file in errors, and relative
// [fem] paths are resolved against its directory.
Scene parse_scene(const std::string& toml_text, const std::string& source_name);

}  // namespace wl
