// The time resolution at which the lab compares models (docs/models.md §7.11):
// by default every side of a comparison runs sdirk2 under error control, and
// each side's time error is estimated beside the distance (§7.8); `scene`
// keeps each scene's own integrator and step (the published 1 ms step).
#pragma once
#include <string>

#include "integrators/integrator.h"
#include "models/scene/scene.h"

namespace wl {

struct Resolution {
  bool scene = false;  // true: the scene's own integrator, step and tolerances
  double rtol = 1e-4;  // otherwise sdirk2 adaptive at this rtol, atol = 10⁻³ rtol [m]
  std::string describe() const;
};

// Parses the value of --resolution: "scene" or "controlled"; throws
// std::invalid_argument naming the option and what was expected.
Resolution parse_resolution(const std::string& option, const std::string& value, double rtol);

// `scene` with the integrator, step control and tolerances of `resolution`.
Scene at_resolution(const Scene& scene, const Resolution& resolution);

// The step, step control and tolerances a scene asks for.
IntegratorOptions scene_integrator_options(const Scene& scene);

}  // namespace wl
