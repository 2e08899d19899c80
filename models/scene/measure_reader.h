// Reads the [measures] table of a scene (internal to models/scene;
// docs/models.md §3.11.6, experiments/scenes/README.md). Runs after the
// cloth and the obstacles are read: a drape needs a woven cloth and a pedestal.
#pragma once
#include "models/scene/toml_reader.h"

namespace wl::scene_detail {

void read_measures(TableReader& top, Scene& s);

}  // namespace wl::scene_detail
