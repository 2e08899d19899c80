#include "models/model_factory.h"

#include <stdexcept>

#include "models/fem/fem_model.h"
#include "models/knit/knit_model.h"
#include "models/yarn/yarn_model.h"

namespace wl {

std::vector<std::string> model_names() { return {"yarn", "fem"}; }

std::unique_ptr<Model> make_model(const Scene& scene, const std::string& name) {
  if (name == "yarn" && scene.knit) return std::make_unique<KnitModel>(scene);
  if (name == "yarn") return std::make_unique<YarnModel>(scene);
  if (name == "fem") return std::make_unique<FemModel>(scene);
  throw std::invalid_argument("unknown model '" + name + "' (expected yarn or fem)");
}

}  // namespace wl
