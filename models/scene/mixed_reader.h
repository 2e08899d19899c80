// Reads the [mixed] table of a scene (internal to models/scene; docs/models.md
// §12.1, experiments/scenes/README.md). Runs after the cloth is read: the
// rectangles must lie inside its grid of crossings.
#pragma once
#include "models/scene/toml_reader.h"

namespace wl::scene_detail {

void read_mixed(TableReader& top, Scene& s);

}  // namespace wl::scene_detail
