// Scenes made stiffer for the stability experiment.
#pragma once
#include "models/scene/scene.h"

namespace wl {

// The scene with every yarn type's stretch_modulus_Pa multiplied by `factor`,
// and the FEM stretch stiffnesses (warp/weft, N/m) set to `factor` × their
// values for the unscaled scene (fem_material: yarn-derived default, parameter
// file or [fem] table), so both models stiffen equally.
Scene scale_stretch(const Scene& scene, double factor);

}  // namespace wl
