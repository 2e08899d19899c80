#include "experiments/driver/model_factory.h"

#include <stdexcept>

#include "models/yarn/yarn_model.h"

namespace wl {

std::vector<std::string> model_names() { return {"yarn"}; }

std::unique_ptr<Model> make_model(const Scene& scene, const std::string& name) {
  if (name == "yarn") return std::make_unique<YarnModel>(scene);
  throw std::invalid_argument("unknown model '" + name + "' (expected yarn or fem)");
}

}  // namespace wl
