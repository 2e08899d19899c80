// Fit of scene parameters to a recorded trajectory (docs/calibration.md §7):
// Ceres least squares on the observed point positions at the target's frames,
//   r = y_k(p) − y_k^target,  y_k = H_k q(t_k),
// with θ = log p bounded to [p₀/b, p₀·b] and Jacobians dr/dθ = H_k (∂q/∂p) p
// from the integrator's forward sensitivities (docs/models.md §9.2). H_k picks
// the model's node positions (yarn target, yarn model) or interpolates the
// continuum at each crossing's material point (yarn target, continuum model).
#pragma once
#include <functional>
#include <map>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "calibration/fit_stopping.h"
#include "models/core/types.h"
#include "models/scene/scene.h"

namespace wl {

// One target frame: the observed points at a time, with the crossings'
// material coordinates (needed to observe a continuum).
struct TargetFrame {
  double time = 0.0;
  Eigen::MatrixXd points;  // n × 3
  std::vector<Vec2> uv;    // per point; empty when unknown
};

struct TrajectoryFitOptions {
  std::string model;                    // "yarn", "knit" or "fem"; "" = the scene's yarn level
  std::string integrator;               // "" = the scene's; must offer sensitivities
  std::vector<std::string> free;        // scene keys (calibration/scene_parameters.h)
  std::map<std::string, double> start;  // start values; absent keys start at the scene's value
  double bound_factor = 100.0;
  int max_iterations = 50;  // per stage
  // Each stage also stops when its cost stops improving (fit_stopping.h); the
  // residual noise is measured at the stage's start, whatever this says.
  FlatCostRule flat_cost;  // window 0: no flat-cost rule (Ceres's tolerances alone)
  // Whether a stage holds the free keys its start's Jacobian does not tell
  // (TrajectoryFitStage::frozen). With this false and no flat-cost rule the start
  // is not probed: the fit is Ceres's plain Levenberg–Marquardt.
  bool hold_untold = true;
  // Growing window (frame continuation, docs/calibration.md §7.1): the first
  // window[0] frames are fitted, then the first window[1] from that result, …;
  // increasing, the last equal to the number of frames. Empty: one stage, all frames.
  std::vector<int> window;
  bool progress = false;
  // Asked after each accepted step of every simulation and after each Ceres
  // iteration: true ends the fit there, with what it reached so far
  // (TrajectoryFitResult::interrupted). The command line asks whether SIGINT or
  // SIGTERM arrived (driver/interrupt.h).
  std::function<bool()> stop_requested;
};

// One stage of a growing window (the whole fit when there is no window).
struct TrajectoryFitStage {
  int frames = 0;
  std::vector<double> start, value;  // per free key
  bool converged = false;
  std::string message;  // Ceres's termination message, or why the stage could not run
  int iterations = 0, simulations = 0;
  double wall_s = 0.0, cpu_s = 0.0;
  double start_rms = 0.0, final_rms = 0.0;  // largest per-frame RMS distance to the target [m] (NaN: no simulation)
  std::vector<double> cost_history;         // Ceres cost per iteration (iteration 0 = start)
  // Free keys held at their start for the stage: at the start the frames do not
  // depend on them, or only as a combination of the others (optimum_statistics.h).
  std::vector<std::string> frozen;
  double residual_noise = 0.0;  // σ measured at the start [m] (fit_stopping.h); 0 when not measured
  bool at_cap = false;          // stopped at max_iterations with the cost still improving
};

struct TrajectoryFitParameter {
  std::string key;
  double start = 0.0, value = 0.0;
  double std_error = 0.0;  // NaN when the covariance is unavailable
  double lower = 0.0, upper = 0.0;
  bool at_bound = false;
  bool identifiable = true;  // false: the trajectory does not tell it (optimum_statistics.h)
  bool frozen = false;       // held at its start in the last stage (TrajectoryFitStage::frozen)
};

struct TrajectoryFitResult {
  std::vector<TrajectoryFitParameter> parameters;
  std::vector<std::vector<double>> correlation;  // empty when unavailable
  std::string covariance_message;                // why it is unavailable
  // All from the last stage (values, standard errors, identifiability, convergence),
  // except each parameter's `start` (the first stage's) and the sums over the stages.
  bool converged = false;    // the last stage met a tolerance of Ceres or the flat-cost rule
  bool at_cap = false;       // the last stage stopped at max_iterations
  bool interrupted = false;  // stop_requested ended it
  std::string message;       // why the last stage stopped (with what to change when at its cap)
  int iterations = 0;        // summed over the stages, as the simulations and times
  int simulations = 0;
  double wall_s = 0.0, cpu_s = 0.0;
  std::vector<TrajectoryFitStage> stages;             // in order; one without a window
  int observed_points = 0;                            // per frame
  std::vector<double> times;                          // the last stage's frames
  std::vector<double> start_rms, final_rms;           // per frame of the last stage, RMS distance to the target [m],
  std::vector<Vec> start_positions, final_positions;  // and the observed points (x₀,y₀,z₀,x₁,…) [m], at its start
                                                      // and at its end
};

class TrajectoryFitError : public std::invalid_argument {  // bad input: exit 2
 public:
  using std::invalid_argument::invalid_argument;
};

// Fits opt.free to `target` (its frames at t > 0, in order), stage by stage
// when opt.window is set: stage k starts at stage k−1's values and is a plain
// fit of its frames within the bounds of the first start. Throws
// TrajectoryFitError for inputs that cannot be fitted (unknown or
// non-differentiable key, a target that does not match the scene, an
// integrator without sensitivities). A start that does not simulate is an
// outcome (message), not an exception.
TrajectoryFitResult fit_trajectory(const Scene& scene, const std::vector<TargetFrame>& target,
                                   const TrajectoryFitOptions& opt);

// Throws TrajectoryFitError unless `window` is a valid growing window over `frames` frames.
void check_window(const std::vector<int>& window, int frames);

// Independent fits (random starts), `threads` at a time, each with its own
// models and integrators: result k is bitwise fit_trajectory(scene, target,
// fits[k]) whatever the thread count. Their cpu_s is then the process's CPU
// time while each ran (shared with the others running at the same time).
std::vector<TrajectoryFitResult> fit_trajectories(const Scene& scene, const std::vector<TargetFrame>& target,
                                                  const std::vector<TrajectoryFitOptions>& fits, int threads);

}  // namespace wl
