#include "models/model_factory.h"

#include <stdexcept>

#include "models/fem/fem_model.h"
#include "models/knit/knit_model.h"
#include "models/mixed/mixed_model.h"
#include "models/yarn/yarn_model.h"

namespace wl {
namespace {

std::string pattern_kind(const Scene& scene) {
  if (scene.knit) {
    switch (scene.knit->kind) {
      case KnitPattern::Kind::stockinette: return "stockinette";
      case KnitPattern::Kind::garter: return "garter";
      case KnitPattern::Kind::rib2x2: return "rib2x2";
    }
  }
  switch (scene.pattern.kind) {
    case Pattern::Kind::plain: return "plain";
    case Pattern::Kind::twill: return "twill";
    case Pattern::Kind::satin: return "satin";
  }
  return "plain";
}

// "<file>:<line>: key 'cloth.pattern.kind'" where the key is written, else "<file>: no key 'cloth.pattern.kind'".
std::string pattern_kind_location(const Scene& scene) {
  const auto it = scene.key_lines.find("cloth.pattern.kind");
  if (it == scene.key_lines.end())
    return scene.source + ": no key 'cloth.pattern.kind' (a woven plain cloth, no [knit] pattern)";
  return scene.source + ":" + std::to_string(it->second) + ": key 'cloth.pattern.kind' = \"" + pattern_kind(scene) +
         "\"";
}

}  // namespace

std::vector<std::string> model_names() { return {"yarn", "knit", "fem", "mixed"}; }

std::string yarn_level_model(const Scene& scene) { return scene.knit ? "knit" : "yarn"; }

void check_model_for_scene(const Scene& scene, const std::string& name) {
  if (name == "yarn" && scene.knit)
    throw std::invalid_argument("model 'yarn' is the woven yarn level, and the scene is knitted (" +
                                pattern_kind_location(scene) + "): expected model 'knit' or 'fem'");
  if (name == "knit" && !scene.knit)
    throw std::invalid_argument("model 'knit' is the knitted yarn level, and the scene is woven (" +
                                pattern_kind_location(scene) + "): expected model 'yarn' or 'fem'");
  if (name != "yarn" && name != "knit" && name != "fem" && name != "mixed")
    throw std::invalid_argument("unknown model '" + name + "' (expected yarn, knit, fem or mixed)");
  if (name == "mixed" && !scene.mixed.present)
    throw std::invalid_argument("model 'mixed' needs the scene's yarn-level region, and " + scene.source +
                                " has no [mixed] table (yarn_region = [[i0, j0, i1, j1], ...], docs/models.md §12.1)");
}

std::unique_ptr<Model> make_model(const Scene& scene, const std::string& name) {
  check_model_for_scene(scene, name);
  if (name == "knit") return std::make_unique<KnitModel>(scene);
  if (name == "yarn") return std::make_unique<YarnModel>(scene);
  if (name == "mixed") return std::make_unique<MixedModel>(scene);
  return std::make_unique<FemModel>(scene);
}

}  // namespace wl
