// The largest stable step: bisection on log(dt) over a probe that says
// whether a run with that step stays bounded (the stability experiment).
#pragma once
#include <functional>
#include <limits>
#include <utility>
#include <vector>

#include "integrators/integrator.h"

namespace wl {

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

}  // namespace wl
