// The time steps at which the lab compares models (docs/models.md §7.11), the
// value of --time-steps: by default (`controlled`) every side of a comparison
// runs sdirk2 under error control, and each side's time error is estimated
// beside the distance (§7.8); `scene` keeps each scene's own integrator and
// fixed step (the published 1 ms step).
#pragma once
#include <string>

#include "integrators/integrator.h"
#include "models/scene/scene.h"

namespace wl {

struct TimeSteps {
  bool scene = false;  // true: the scene's own integrator, step and tolerances
  double rtol = 1e-4;  // otherwise sdirk2 adaptive at this rtol, atol = 10⁻³ rtol [m]
  std::string describe() const;
};

// The rule of every relative tolerance a command line gives (--rtol, --rtols):
// kMinRtol ≤ rtol < 1, as the scene's time.rtol (scene_limits.h); throws
// std::invalid_argument naming `option`, the value and the rule.
void check_rtol(const std::string& option, double rtol);

// Parses the value of --time-steps: "scene" or "controlled", and its --rtol
// (check_rtol); throws std::invalid_argument naming the option and what was expected.
TimeSteps parse_time_steps(const std::string& option, const std::string& value, double rtol);

// `scene` with the integrator, step control and tolerances of `time_steps`.
Scene at_time_steps(const Scene& scene, const TimeSteps& time_steps);

// The step, step control and tolerances a scene asks for.
IntegratorOptions scene_integrator_options(const Scene& scene);

}  // namespace wl
