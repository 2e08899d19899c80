// Builds a Model of a Scene by name: "yarn" (woven yarn level), "knit" (knitted
// yarn level, docs/models.md §11), "fem" (the continuum) or "mixed" (the yarn level on
// the scene's [mixed] region, the continuum elsewhere, docs/models.md §12).
#pragma once
#include <memory>
#include <string>
#include <vector>

#include "models/core/model.h"
#include "models/scene/scene.h"

namespace wl {

std::vector<std::string> model_names();

// The scene's yarn-level model: "knit" when cloth.pattern.kind names a knit,
// else "yarn". Every caller that builds "the yarn level of this scene" (runs
// without --model, fidelity ladders, calibration, diagnose, modes, pull) asks
// here.
std::string yarn_level_model(const Scene& scene);

// Throws std::invalid_argument for an unknown name, and for a yarn-level model
// the scene's cloth is not ("yarn" on a knit, "knit" on a woven cloth), naming
// the scene file, the line of cloth.pattern.kind and the model expected.
void check_model_for_scene(const Scene& scene, const std::string& name);

// Throws as check_model_for_scene.
std::unique_ptr<Model> make_model(const Scene& scene, const std::string& name);

}  // namespace wl
