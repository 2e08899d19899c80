#include "driver/scene_scaling.h"

#include "models/fem/fem_material.h"

namespace wl {

Scene scale_stretch(const Scene& scene, double factor) {
  Scene s = scene;
  const FemMaterial base = fem_material(scene);
  for (auto& [name, type] : s.yarn_types) type.stretch_modulus_Pa *= factor;
  s.fem.warp_stretch_N_per_m = factor * base.warp_stretch_N_per_m;
  s.fem.weft_stretch_N_per_m = factor * base.weft_stretch_N_per_m;
  return s;
}

}  // namespace wl
