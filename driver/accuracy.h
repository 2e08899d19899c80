// Accuracy as an input (docs/models.md §7.9): the integrator and tolerance
// whose estimated time error (driver/time_error.h), mean over
// frames of the RMS over nodes, is at most a target. The method is sdirk2
// with error control; its tolerance is tightened from trial to trial in
// proportion to the measured estimate until the target is met, or until a
// tighter tolerance lowers the estimate by less than 20 % (a floor).
#pragma once
#include <string>
#include <vector>

#include "driver/time_error.h"
#include "models/scene/scene.h"

namespace wl {

struct AccuracyTrial {
  double rtol = 0.0;
  double estimate_m = 0.0;  // mean RMS estimate; NaN when the run or its estimate failed
  double cpu_s = 0.0;       // the run and its estimate
  std::string outcome;      // the run's outcome, or the estimate's
};

struct AccuracyChoice {
  double target_m = 0.0;
  std::string integrator = "sdirk2";
  double rtol = 0.0, atol = 0.0;  // of the chosen (last) trial
  bool reached = false;
  std::string note;  // why the trials stopped short of the target, when they did
  std::vector<AccuracyTrial> trials;
  TimeErrorEstimate estimate;  // of the chosen trial
  Json to_json() const;
};

// At most `max_trials` runs of `scene` with `model_name`, each with its estimate.
AccuracyChoice choose_for_accuracy(const Scene& scene, const std::string& model_name, double target_m, bool progress,
                                   int max_trials = 6);

}  // namespace wl
