// Scenes of the mixed-model tests (docs/models.md §12): the hanging cloth of
// tests/support/test_scenes.h with a [mixed] region, and flat patches.
#pragma once
#include <string>

#include "models/scene/scene.h"
#include "tests/support/test_scenes.h"

namespace wl::test {

// The n×n hanging cloth in wind (handles at (0, 0) and (n−1, 0), sliding, Gong shear and
// friction), `extra` tables after its [time], and the yarn level on `region` ("[[i0, j0, i1, j1]]").
inline Scene hanging_mixed_scene(const std::string& region, int n = 7, const std::string& extra = "") {
  return parse_scene(hanging_cloth_toml(n, 0.02) + extra + "[mixed]\nyarn_region = " + region + "\n", "mixed.toml");
}

}  // namespace wl::test
