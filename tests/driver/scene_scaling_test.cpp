// The stretch-modulus multiplier (driver/scene_scaling.h).
#include <gtest/gtest.h>

#include "driver/scene_scaling.h"
#include "models/fem/fem_material.h"
#include "tests/driver/driver_test_data.h"

namespace wl {
namespace {

using test::tiny_scene_text;

TEST(ScaleStretch, ScalesYarnModuliAndFemStretchOnly) {
  const Scene s = parse_scene(tiny_scene_text(), "tiny.toml");
  const Scene x = scale_stretch(s, 100.0);
  for (const auto& [name, t] : s.yarn_types) {
    EXPECT_DOUBLE_EQ(x.yarn_types.at(name).stretch_modulus_Pa, 100.0 * t.stretch_modulus_Pa);
    EXPECT_DOUBLE_EQ(x.yarn_types.at(name).bending_modulus_Pa, t.bending_modulus_Pa);
  }
  const FemMaterial a = fem_material(s), b = fem_material(x);
  EXPECT_DOUBLE_EQ(b.warp_stretch_N_per_m, 100.0 * a.warp_stretch_N_per_m);
  EXPECT_DOUBLE_EQ(b.weft_stretch_N_per_m, 100.0 * a.weft_stretch_N_per_m);
  EXPECT_DOUBLE_EQ(b.shear_N_per_m, a.shear_N_per_m);
  EXPECT_DOUBLE_EQ(b.warp_bending_N_m, a.warp_bending_N_m);
  EXPECT_DOUBLE_EQ(b.areal_density_kg_per_m2, a.areal_density_kg_per_m2);
}

}  // namespace
}  // namespace wl
