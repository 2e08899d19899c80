// In-process runs for the integrator experiments: a
// scene run with one model and integrator, recording node positions at the
// output times (no VTU output); the error of a run against a reference
// trajectory; the reference itself (IDA at the tightest tolerance that
// converges, cached under results/reference/); the stability bisection; and
// the stretch-modulus multiplier of the stability experiment.
//
// Uses only the Model and Integrator interfaces (models/core/model.h,
// integrators/integrator.h), never integrator internals.
#pragma once
#include <filesystem>
#include <functional>
#include <limits>
#include <map>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "integrators/integrator.h"
#include "models/scene/scene.h"

namespace wl {

// Node positions (Model::frame(...).points, i.e. the x DoFs of every node) at
// the output times t_k = k·output_interval_s, k = 1 … ⌊duration/interval⌉ (the
// last one clamped to the duration; t = 0 is left out, it is the same for all
// runs). positions.col(k) = (x₀, y₀, z₀, x₁, …) at times[k].
struct Trajectory {
  std::vector<double> times;
  Eigen::MatrixXd positions;  // 3·nodes × times
  int nodes() const { return static_cast<int>(positions.rows() / 3); }
};

// The output times of a scene (see Trajectory).
std::vector<double> output_times(const Scene& scene);

struct RecordedRun {
  StepResult result;            // outcome, message and, for a SUNDIALS failure, its flag
  IntegratorStats stats;        // the integrator's own statistics
  double cpu_s = 0.0;           // process CPU time of initialize + advance_to (all threads), frames excluded
  double wall_s = 0.0;          // wall time of the same
  double end_time = 0.0;        // time reached
  double max_node_speed = 0.0;  // largest Model::max_node_speed over all accepted steps [m/s]
  int dofs = 0;
  Trajectory trajectory;  // the output times reached
  // Kinetic ½vᵀM(q)v and potential energy at the output times reached, when
  // RecordOptions::energies (outside the timed sections) [J].
  std::vector<double> kinetic_J, potential_J;
  double initial_energy_J = 0.0;  // T + V at t = 0, when RecordOptions::energies [J]
};

struct RecordOptions {
  // A run whose max node speed exceeds this stops with Outcome::diverged (it is
  // also passed as IntegratorOptions::runaway_speed when smaller) [m/s].
  double speed_bound = std::numeric_limits<double>::infinity();
  bool progress = false;  // a line on stderr every few seconds
  std::string label;      // prefix of the progress lines
  // Called with every recorded output frame (after the trajectory column is stored).
  std::function<void(const Frame&)> on_frame;
  bool energies = false;  // fill RecordedRun::kinetic_J and potential_J
};

// Runs `scene` with `model_name` ("yarn", "fem") and `integrator_name` to the
// scene's duration. A numerical failure is an outcome, not an exception;
// std::invalid_argument for an unknown model or integrator.
RecordedRun run_recorded(const Scene& scene, const std::string& model_name, const std::string& integrator_name,
                         const IntegratorOptions& options, const RecordOptions& record = {});

// Error of a run against a reference: over all nodes n and output times k,
//   rms = sqrt( mean_{n,k} ‖x_run(n,k) − x_ref(n,k)‖² ),  max = max_{n,k} ‖…‖  [m].
// Throws std::invalid_argument when the node counts or output times differ.
struct ErrorNorms {
  double rms = 0.0;
  double max = 0.0;
};
ErrorNorms trajectory_error(const Trajectory& run, const Trajectory& reference);

// ---- Reference trajectories ----------------------------------------------

struct ReferenceOptions {
  std::filesystem::path cache_dir = "results/reference";
  std::string integrator = "ida";
  std::vector<double> rtols = {1e-10, 1e-9};       // tried in order; the first that converges is used
  double required_rtol = 1e-9;                     // a reference looser than this is reported (and flagged)
  double atol_per_rtol = 1e-3;                     // atol = rtol × this [m, m/s]
  double initial_dt = 1e-6;                        // initial step hint [s]
  long max_steps = IntegratorOptions{}.max_steps;  // per attempt; beyond it the attempt fails (max_steps)
  bool progress = true;
};

struct Reference {
  Trajectory trajectory;
  std::string hash;            // 16 hex digits
  std::filesystem::path file;  // <cache_dir>/<hash>.bin
  bool from_cache = false;
  double rtol = 0.0, atol = 0.0;      // the tolerances that converged
  double cpu_s = 0.0;                 // CPU time of the run that produced it (also when read from the cache)
  std::vector<std::string> attempts;  // "rtol=1e-10: ok" / "rtol=1e-10: step_too_small: …" (this call only)
  bool meets_requirement() const { return rtol > 0 && rtol <= 1.0000001 * required_rtol; }
  double required_rtol = 1e-9;
};

// The cache key: scene file text, model, overrides (sorted key=value lines)
// and the reference integrator; hash = FNV-1a 64 of the key.
std::string reference_key(const std::string& scene_text, const std::string& model_name,
                          const std::map<std::string, std::string>& overrides, const ReferenceOptions& options);
std::string reference_hash(const std::string& key);

// Reads <cache_dir>/<hash>.bin when it exists and holds the same key and output
// times; otherwise runs `options.integrator` at each rtol in turn until one
// ends ok, and writes the file atomically. Throws std::runtime_error when no
// tolerance converges (naming every attempt). `scene` must be the scene the
// text and overrides describe.
Reference load_or_compute_reference(const Scene& scene, const std::string& scene_text, const std::string& model_name,
                                    const std::map<std::string, std::string>& overrides,
                                    const ReferenceOptions& options = {});

// Cache file format (little-endian, as written on this machine):
//   char[8] "WLREF01\0"; u64 key length; key bytes; f64 rtol, atol, cpu_s;
//   u64 times, u64 rows (3·nodes); f64 times[times]; f64 positions[rows × times] (column-major).
void write_reference_file(const std::filesystem::path& path, const std::string& key, const Reference& ref);
// Returns false when the file is absent, unreadable, malformed or holds another key.
bool read_reference_file(const std::filesystem::path& path, const std::string& key, Reference& ref);

// ---- Stability ------------------------------------------------------------

struct StabilityProbe {
  bool bounded = false;
  StepResult result;       // outcome of the run (ok when bounded)
  double max_speed = 0.0;  // [m/s]
};

struct StabilityLimit {
  // Largest step found bounded (NaN when none ≥ dt_min) and smallest found
  // unbounded (NaN when dt_max is bounded: the limit is ≥ dt_max).
  double largest_stable_dt = std::numeric_limits<double>::quiet_NaN();
  double smallest_unstable_dt = std::numeric_limits<double>::quiet_NaN();
  StabilityProbe failure;                                 // the probe at smallest_unstable_dt
  std::vector<std::pair<double, StabilityProbe>> probes;  // in the order run
};

// Bisection on log(dt) in [dt_min, dt_max]: dt_max is probed first (bounded →
// done); otherwise `bisections` geometric midpoints narrow [lo, hi] with lo
// assumed bounded; when no probe was bounded, dt_min itself is probed. Assumes
// the predicate is monotone (bounded below a threshold).
StabilityLimit find_stability_limit(const std::function<StabilityProbe(double dt)>& probe, double dt_min, double dt_max,
                                    int bisections);

// The scene with every yarn type's stretch_modulus_Pa multiplied by `factor`,
// and the FEM stretch stiffnesses (warp/weft, N/m) set to `factor` × their
// values for the unscaled scene (fem_material: yarn-derived default, parameter
// file or [fem] table), so both models stiffen equally.
Scene scale_stretch(const Scene& scene, double factor);

// Reads a whole text file; throws std::runtime_error naming the path.
std::string read_text_file(const std::filesystem::path& path);

}  // namespace wl
