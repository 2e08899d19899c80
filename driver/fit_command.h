// `weavelab fit`: scene parameters fitted to a recorded run's trajectory
// (calibration/trajectory_fit.h, docs/calibration.md §7). Writes into the output folder
//   params.toml     (continuum fits) the FEM parameter file, for `run --fem-params`
//   fit.json        parameters (key, start, value, std_error, bounds), correlations,
//                   iterations, simulations, wall and CPU time, git revision, and
//                   per stage of a growing window its frames, start, values and times
//   convergence.csv Ceres cost and RMS distance per stage and iteration
//   frames.csv      per fitted frame: RMS distance to the target at the start and
//                   at the fit, and the target, start and fitted position of the
//                   point that moves most
// (experiments/common/plot_fit.py draws the chart from these).
#pragma once
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "calibration/trajectory_fit.h"
#include "driver/time_steps.h"
#include "models/scene/scene.h"

namespace wl {

struct FitCommandConfig {
  std::filesystem::path scene_path, target_dir, out_dir;
  int frames = 0;          // the target's first N frames after t = 0; 0 = all
  std::string fem_params;  // replaces the scene's [fem] parameter_file when given
  // The simulations' time steps (docs/models.md §7.11): by default the scene's
  // integrator and step, as the published fit; controlled: sdirk2 under error control.
  TimeSteps time_steps{.scene = true};
  TrajectoryFitOptions fit;
  // With fit.window empty: the default growing window of a long fit
  // (calibration/fit_continuation.h) when true, one plain stage when false
  // (`--growing-window off`).
  bool default_window = true;
};

// Every input checked before anything runs: throws SceneError, RunReadError,
// ParameterKeyError or TrajectoryFitError (exit 2).
struct FitCommandPlan {
  Scene scene;
  std::vector<TargetFrame> target;
  std::string model;        // config.fit.model, or the scene's yarn level when that is empty
  std::vector<int> window;  // the growing window the fits run (empty: one plain stage)
  std::string window_rule;  // where it comes from: "given", "default", "off" or "short" (no window needed)
};
FitCommandPlan plan_fit(const FitCommandConfig& config);

TrajectoryFitResult run_fit(const FitCommandConfig& config, const FitCommandPlan& plan);
// Fits from several starts (configs that differ in fit.start and out_dir), `jobs`
// at a time (calibration/trajectory_fit.h: each as run_fit would give it).
std::vector<TrajectoryFitResult> run_fits(const std::vector<FitCommandConfig>& starts, const FitCommandPlan& plan,
                                          int jobs);
// Writes one fit's outputs into config.out_dir (config.fit.model as resolved in plan.model).
void write_fit(const FitCommandConfig& config, const FitCommandPlan& plan, const TrajectoryFitResult& result);

}  // namespace wl
