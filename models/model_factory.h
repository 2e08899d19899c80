// Builds a Model of a Scene by name ("yarn", "fem").
#pragma once
#include <memory>
#include <string>
#include <vector>

#include "models/core/model.h"
#include "models/scene/scene.h"

namespace wl {

std::vector<std::string> model_names();
// Throws std::invalid_argument for an unknown name.
std::unique_ptr<Model> make_model(const Scene& scene, const std::string& name);

}  // namespace wl
