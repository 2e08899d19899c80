// The global time error of a run, estimated frame by frame (docs/models.md §7.8):
//   richardson  a one-step method of order p (replays_steps): the run's own
//               step sequence is retaken with every step halved; the error of
//               the run is ‖x_h − x_{h/2}‖ · 2ᵖ/(2ᵖ − 1) per node;
//   halved_step a fixed-step library method: the run at dt/2, the same rule;
//   tolerance   an error-controlled library method (IDA, ARKODE): the run at
//               rtol/100 and atol/100; the error is ‖x_tol − x_tol/100‖, which
//               assumes the error follows the tolerance (then the tighter run's
//               own error is about 1 % of the estimate).
// Every variant costs one more run of the scene (two to three times the run).
// A fourth, looser_trial, is formed by `--accuracy` from its own trials
// (driver/accuracy.h); its "second run" is the looser trial.
#pragma once
#include <functional>
#include <string>
#include <vector>

#include "driver/recorded_run.h"
#include "output/json_writer.h"

namespace wl {

struct TimeErrorEstimate {
  std::string method;  // "richardson", "halved_step", "tolerance" (or "looser_trial", driver/accuracy.h)
  int order = 0;       // p of richardson and halved_step; 0 for tolerance
  std::vector<double> times;
  std::vector<double> rms, max;  // per frame over nodes [m]
  double mean_rms = 0.0;         // mean over frames of rms [m]
  double max_max = 0.0;          // largest over frames of max [m]
  double second_run_cpu_s = 0.0;
  long second_run_steps = 0;
  StepResult second_run;  // its outcome; when not ok no estimate was formed
  bool ok() const { return second_run.outcome == Outcome::ok; }
  Json to_json() const;
};

// Estimates the error of `run` (with step_ends recorded when the integrator
// replays steps), which ran `scene` with `model_name`, `integrator_name` and
// `options`. `progress` prints the second run's progress; `on_step` observes
// its accepted steps (the time reached). A SIGINT or SIGTERM recorded by
// driver/interrupt.h ends the second run after its current step: second_run
// is then `interrupted` and no estimate is formed.
TimeErrorEstimate estimate_time_error(const Scene& scene, const std::string& model_name,
                                      const std::string& integrator_name, const IntegratorOptions& options,
                                      const RecordedRun& run, bool progress = false,
                                      const std::function<void(double t)>& on_step = {});

// What a mean distance between two runs measures, given each run's estimate
// (the rule experiments/common/compare.py prints): "resolved" when both time errors
// are below a tenth of it, "time error above a tenth of the distance",
// "time error exceeds the distance", or "time error unknown".
std::string error_budget_verdict(double distance_m, const TimeErrorEstimate& a, const TimeErrorEstimate& b);

// Per-frame RMS and max over nodes of ‖a − b‖ · factor (same nodes and times).
void frame_distances(const Trajectory& a, const Trajectory& b, double factor, std::vector<double>& rms,
                     std::vector<double>& max);

}  // namespace wl
