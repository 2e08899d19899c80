// Reads the [[obstacles]] entries and the [obstacle_contact] table of a scene
// (internal to models/scene; docs/models.md §3.11, experiments/scenes/README.md).
#pragma once
#include "models/scene/toml_reader.h"

namespace wl::scene_detail {

void read_obstacles(TableReader& top, Scene& s);

}  // namespace wl::scene_detail
