// `weavelab modes`: the lowest vibration modes of the yarn level and of the
// continuum, each linearized about its static hanging equilibrium in the same
// scene without wind, matched by shape (docs/models.md §10, docs/design.md §7.7).
// For each model: the equilibrium q* by Newton's method from the rest state
// (calibration/equilibrium.h; the yarn level's friction anchors stay at rest),
// or, when that fails, from the end of a backward-Euler run that settles the
// released cloth (numerical damping). A cloth held at its top corners hangs in
// its own plane, and that hang can be unstable (compression between the corners
// buckles it): then the cloth is leaned out of plane, settled and solved again,
// so that the modes are those of the stable hang next to it. Then
// K = −∂f/∂q at (q*, v = 0) (geometric stiffness included), its measured
// asymmetry ‖K − Kᵀ‖_F/‖K‖_F, and the lowest modes of (K + Kᵀ)/2 φ = ω² M(q*) φ
// on the free DoFs (integrators/modal_solver.h); the yarn level's sliding DoFs
// take part. The shapes are compared at the crossings both models carry (every
// crossing at stride 1; those on the stride lattice otherwise) over the position
// components only. The command writes into the output folder
//   modes.csv        per model and mode: frequency [Hz], ω² [1/s²], the mode of
//                    the other model it is paired with (largest MAC, one to one),
//                    that MAC and the frequency ratio continuum / yarn
//   mac.csv          the MAC matrix, a row per yarn mode, a column per continuum mode
//   modes_yarn.vtu, modes_fem.vtu   the equilibrium with each mode shape as point
//                    data "mode_NN" (largest crossing displacement 1; the continuum's
//                    sign follows its yarn partner), and the yarn level's sliding
//                    components "mode_NN_slide" (u, v), for ParaView
//   modes.json       scene, parameters, both equilibria (Newton iterations,
//                    residual), K's asymmetry, DoFs, frequencies and pairs
// (experiments/diagnosis/scripts/plot_modes.py draws the MAC matrix and the frequencies).
#pragma once
#include <cmath>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "calibration/equilibrium.h"
#include "driver/modal_match.h"
#include "integrators/modal_solver.h"
#include "models/core/model.h"
#include "models/scene/scene.h"

namespace wl {

// K by central differences of the full force (its frozen inputs recomputed at
// every state) against the assembled K, when asked for.
struct StiffnessCheck {
  double asymmetry = NAN;           // ‖K_fd − K_fdᵀ‖_F / ‖K_fd‖_F
  double difference = NAN;          // ‖K_fd − K‖_F / ‖K_fd‖_F on the pattern
  double outside_pattern = NAN;     // ‖K_fd off the pattern‖_F / ‖K_fd‖_F
  std::vector<double> eigenvalues;  // lowest ω² of (K_fd + K_fdᵀ)/2 with the same M [1/s²]
};

// One model linearized about its hanging equilibrium.
struct LinearizedModes {
  std::string model;
  EquilibriumResult equilibrium;
  std::string route;                // how the equilibrium was reached
  double unstable_planar_hz = NAN;  // lowest frequency of the unstable planar hang left for a leaning one
  Vec q;                            // the equilibrium q*
  double asymmetry = 0.0;           // ‖K − Kᵀ‖_F / ‖K‖_F of K = −∂f/∂q at q*
  ModalResult modes;                // of (K + Kᵀ)/2 and M(q*), shapes M-normalized
  StiffnessCheck fd;                // filled when asked for (fd_check)
  // Rows 3c … 3c+2: the position components at compared crossing c; a column per mode.
  Eigen::MatrixXd crossing_shapes;
};

// The scene of the modal analysis: `scene` with the wind off.
Scene modal_scene(const Scene& scene);
// The crossings compared between the models: those on the continuum's stride lattice.
std::vector<NodeRef> compared_crossings(const Scene& scene);
// Index of the first of the three position DoFs of crossing `node` in a yarn or fem model.
int crossing_position_dof(const Model& model, const NodeRef& node);

// Equilibrium, linearization and the lowest modes of `model`; a numerical
// failure is reported in equilibrium.message or modes.message (modes.ok false).
// When the hang in the cloth's plane is unstable (lowest ω² < 0) and lean_m > 0,
// the cloth is leaned out of plane by lean_m at its bottom row (in proportion
// to the row), settled by backward Euler and solved again by Newton.
// With fd_check, also K by central differences of the full force (StiffnessCheck).
// After a SIGINT or SIGTERM it throws Interrupted at its Newton iteration,
// settling step or finite-difference column.
LinearizedModes linearized_modes(Model& model, const std::vector<NodeRef>& crossings, const ModalOptions& options,
                                 double lean_m = 0.0, bool fd_check = false);

struct ModesConfig {
  std::filesystem::path scene_path;
  Scene scene;                                      // as loaded
  std::optional<std::filesystem::path> fem_params;  // the continuum's parameters (default: the scene's)
  int count = 12;                                   // modes per model
  double lean_m = 1e-3;                             // out-of-plane lean when the planar hang is unstable
  bool fd_check = false;                            // also K by central differences (StiffnessCheck)
  std::filesystem::path out_dir;
  bool progress = true;
};

struct ModesResult {
  LinearizedModes yarn, fem;
  Eigen::MatrixXd mac;  // yarn modes × continuum modes
  // Distance between the two equilibria over the compared crossings: RMS and max [m].
  double equilibrium_rms_m = 0.0, equilibrium_max_m = 0.0;
  std::vector<ModePair> pairs;
};

// Checks the inputs (count, a bad parameter file: FemParameterError, std::invalid_argument)
// before anything is written; an equilibrium or eigensolve that fails is a
// std::runtime_error after which nothing is written. A SIGINT or SIGTERM ends the
// Newton iteration, settling step or eigensolve under way: modes.json with outcome
// interrupted (driver/interrupted_record.h), then Interrupted.
ModesResult run_modes(const ModesConfig& config);

}  // namespace wl
