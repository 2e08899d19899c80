// A knit scene the knit model cannot take although every key is in range: its
// periodic rest tile does not relax (docs/models.md §11.3) or a stitch term's
// rest state degenerates (§11.4, §11.4.1). Only the model can tell, so the
// refusal is made here, located like the reader's: a SceneError at the
// scene's [cloth.pattern] (the line of its kind), naming every value the
// knit's rest shape depends on and what failed (the command line: exit 2).
#pragma once
#include <string>

#include "models/scene/scene.h"

namespace wl {

// The values of a knit scene that shape its loops and their rest, e.g.
// "cloth.spacing_m = 0.002, cloth.pattern.course_spacing_m = 1e-12, ...".
std::string knit_geometry_values(const Scene& scene);

// Throws SceneError(scene.source, line of cloth.pattern.kind, "cloth.pattern",
// knit_geometry_values(scene), expected + ": " + what_failed).
[[noreturn]] void refuse_knit_scene(const Scene& scene, const std::string& expected, const std::string& what_failed);

}  // namespace wl
