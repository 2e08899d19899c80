#include "driver/time_steps.h"

#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "models/scene/scene_limits.h"

namespace wl {

std::string TimeSteps::describe() const {
  if (scene) return "each scene's own integrator and step";
  char b[96];
  std::snprintf(b, sizeof b, "sdirk2 under error control, rtol %g, atol %g m", rtol, 1e-3 * rtol);
  return b;
}

void check_rtol(const std::string& option, double rtol) {
  // The floor of time.rtol (scene_limits.h), which also keeps atol = 1e-3·rtol > 0 (at_time_steps).
  if (rtol >= kMinRtol && rtol < 1.0) return;
  char got[32], floor[32];
  std::snprintf(got, sizeof got, "%g", rtol);
  std::snprintf(floor, sizeof floor, "%g", kMinRtol);
  throw std::invalid_argument(option + ": got " + got + ", expected a tolerance ≥ " + floor +
                              " and < 1 (smaller tolerances are below round-off)");
}

TimeSteps parse_time_steps(const std::string& option, const std::string& value, double rtol) {
  if (value != "scene" && value != "controlled")
    throw std::invalid_argument(option + ": got '" + value + "', expected 'controlled' or 'scene'");
  check_rtol("--rtol", rtol);
  return {value == "scene", rtol};
}

Scene at_time_steps(const Scene& scene, const TimeSteps& r) {
  Scene s = scene;
  if (r.scene) return s;
  s.integrator = "sdirk2";
  s.adaptive = true;
  s.rtol = r.rtol;
  s.atol = 1e-3 * r.rtol;
  return s;
}

IntegratorOptions scene_integrator_options(const Scene& s) {
  IntegratorOptions o;
  o.dt = s.dt_s;
  o.adaptive = s.adaptive;
  o.rtol = s.rtol;
  o.atol = s.atol;
  return o;
}

}  // namespace wl
