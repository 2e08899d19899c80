// Accuracy as an input (docs/models.md §7.9): sdirk2 under error control at
// a tolerance whose time error, mean over frames of the RMS over nodes, is
// bounded by a target. The trials tighten rtol (atol = 1e-3 rtol m) as
// driver/accuracy_search.h decides, each at least ten times tighter than the
// one before, and measure each other: no trial pays for a second run of its own.
//
// The estimate (method "looser_trial"): the distance of the last trial to the
// one before it, per frame the RMS and max over nodes. It bounds the last
// trial's error when the two trials' errors are independent (the distance is
// then √(e_loose² + e_tight²)), and when they share one pattern scaled by the
// tolerance as rᵅ with 10ᵅ ≥ 2 (the distance is then e_loose − e_tight ≥
// e_tight). On the hanging cloth the bound was checked against a converged
// reference and against Richardson's estimate (§7.8) by the measurement the
// docs link to.
#pragma once
#include <functional>
#include <string>
#include <vector>

#include "driver/accuracy_search.h"
#include "driver/time_error.h"
#include "models/scene/scene.h"

namespace wl {

struct AccuracyTrial {
  double rtol = 0.0;
  double estimate_m = 0.0;  // its distance to the next trial that ran: its error, measured; NaN until then
  double cpu_s = 0.0;       // the trial's run
  std::string outcome;      // the run's outcome
};

struct AccuracyChoice {
  double target_m = 0.0;
  std::string integrator = "sdirk2";
  double rtol = 0.0, atol = 0.0;  // of the chosen (last) trial
  bool reached = false;
  std::string verdict;  // to_string(SearchVerdict), or "interrupted"
  std::string note;     // why the trials stopped short of the target, when they did
  std::vector<AccuracyTrial> trials;
  TimeErrorEstimate estimate;  // of the chosen trial (method "looser_trial"); not ok when it has no looser trial
  double trials_cpu_s() const;
  Json to_json() const;
};

// What one trial delivers to the search.
struct TrialRun {
  StepResult result;
  Trajectory trajectory;  // node positions at the output times after t = 0
  double cpu_s = 0.0;
};

// The estimate of `tight` from `loose` (method "looser_trial", above).
TimeErrorEstimate estimate_from_looser_trial(const Trajectory& loose, const Trajectory& tight, double loose_cpu_s);

// The search: `run_trial(rtol, k)` runs trial k (1, 2, …) of sdirk2 at rtol; a
// trial that ends `interrupted` ends the search at once (verdict "interrupted").
AccuracyChoice search_accuracy(double target_m, const std::function<TrialRun(double rtol, int trial)>& run_trial,
                               bool progress, const SearchLimits& limits = {});

// The search with trials run in memory (run_recorded) on `scene` with `model_name`.
AccuracyChoice choose_for_accuracy(const Scene& scene, const std::string& model_name, double target_m, bool progress,
                                   const SearchLimits& limits = {});

}  // namespace wl
