// The spline shear law's keys (docs/models.md §6.4.1, experiments/scenes/README.md): read from the
// scene and the parameter file, and every bad value a located error.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "models/fem/fem_material.h"
#include "models/scene/scene.h"

namespace wl {
namespace {

SceneError scene_error(const std::string& text) {
  try {
    parse_scene(text, "s.toml");
  } catch (const SceneError& e) {
    return e;
  }
  ADD_FAILURE() << "no error for\n" << text;
  return SceneError("", 0, "", "", "");
}

TEST(ShearLawKeys, SplineLawWithItsKnotsAndValues) {
  const Scene d = parse_scene("[fem]\nshear_law = \"spline\"\n", "s.toml");
  EXPECT_EQ(d.fem.shear_law, FemSettings::ShearLaw::spline);
  EXPECT_EQ(d.fem.shear_knots_rad, (std::vector<double>{0.1, 0.2, 0.3, 0.4}));  // the default knots
  const Scene s = parse_scene(
      "[fem]\nshear_law = \"spline\"\nshear_knots_rad = [0.15, 0.3]\nshear_knot2_N_per_m = 0.8\nshear_N_per_m = 3\n",
      "s.toml");
  EXPECT_EQ(s.fem.shear_knots_rad, (std::vector<double>{0.15, 0.3}));
  EXPECT_FALSE(s.fem.shear_knot_N_per_m[0]);
  EXPECT_EQ(*s.fem.shear_knot_N_per_m[1], 0.8);
  const FemMaterial m = fem_material(s);
  EXPECT_EQ(m.shear_knots_rad, s.fem.shear_knots_rad);
  EXPECT_EQ(m.shear_knot_N_per_m[0], 3.0);  // absent: shear_N_per_m
  EXPECT_EQ(m.shear_knot_N_per_m[1], 0.8);
  EXPECT_EQ(m.shear_knot_N_per_m[2], 0.0);                                                 // no third knot
  EXPECT_EQ(parse_scene("", "s.toml").fem.shear_law, FemSettings::ShearLaw::linear_lock);  // the default
  EXPECT_TRUE(fem_material(parse_scene("", "s.toml")).shear_knots_rad.empty());
}

TEST(ShearLawKeys, BadValuesNameLineKeyAndWhatWasExpected) {
  SceneError e = scene_error("[fem]\nshear_law = \"cubic\"\n");
  EXPECT_EQ(e.key, "fem.shear_law");
  EXPECT_EQ(e.line, 2);
  e = scene_error("[fem]\nshear_knots_rad = [0.1, 0.2]\n");  // knots without the spline law
  EXPECT_EQ(e.key, "fem.shear_knots_rad");
  EXPECT_NE(e.expected.find("shear_law = \"spline\""), std::string::npos) << e.what();
  for (const char* knots :
       {"[0.2, 0.1]", "[]", "[0.1, 1.6]", "[-0.1]", "[0.1, \"x\"]", "[0.1,0.2,0.3,0.4,0.5,0.6,0.7]"}) {
    e = scene_error(std::string("[fem]\nshear_law = \"spline\"\n\nshear_knots_rad = ") + knots + "\n");
    EXPECT_EQ(e.key, "fem.shear_knots_rad") << knots;
    EXPECT_EQ(e.line, 4) << knots;
    EXPECT_NE(e.expected.find("increasing shear angles"), std::string::npos) << e.what();
  }
  e = scene_error("[fem]\nshear_law = \"spline\"\nshear_knots_rad = [0.1, 0.2]\nshear_knot3_N_per_m = 1\n");
  EXPECT_EQ(e.key, "fem.shear_knot3_N_per_m");  // beyond the knots
  EXPECT_EQ(e.line, 4);
  e = scene_error("[fem]\nshear_knot1_N_per_m = 1\n");  // the linear law has no knots
  EXPECT_EQ(e.key, "fem.shear_knot1_N_per_m");
  e = scene_error("[fem]\nshear_law = \"spline\"\nshear_knot1_N_per_m = 0\n");
  EXPECT_EQ(e.key, "fem.shear_knot1_N_per_m");
  EXPECT_EQ(e.value, "0");
  e = scene_error("[fem]\nshear_law = \"spline\"\nshear_knot7_N_per_m = 1\n");  // not a key at all
  EXPECT_EQ(e.key, "fem.shear_knot7_N_per_m");
}

TEST(ShearLawKeys, ParameterFileKnotValuesMustFitTheScenesLaw) {
  FemMaterial spline;
  spline.shear_knots_rad = {0.1, 0.2};
  const FemMaterial m = parse_fem_parameters("shear_knot2_N_per_m = 1.5\n", "cal.toml", spline);
  EXPECT_EQ(m.shear_knot_N_per_m[1], 1.5);
  for (const auto& [text, base] : {std::pair{std::string("\nshear_knot3_N_per_m = 1\n"), spline},
                                   std::pair{std::string("\nshear_knot1_N_per_m = 1\n"), FemMaterial{}}}) {
    try {
      parse_fem_parameters(text, "cal.toml", base);
      ADD_FAILURE() << "no error for " << text;
    } catch (const FemParameterError& e) {
      EXPECT_EQ(std::string(e.what()).rfind("cal.toml:2: key 'shear_knot", 0), 0u) << e.what();
      EXPECT_NE(std::string(e.what()).find("shear_law = \"spline\""), std::string::npos) << e.what();
    }
  }
  // Written by calibration and read back into a scene with the same law.
  FemMaterial all = spline;
  all.shear_N_per_m = 3.0;
  all.shear_knot_N_per_m = {2.0, 0.7};
  const std::string path = (std::filesystem::path(::testing::TempDir()) / "spline_params.toml").string();
  write_fem_parameter_file(path, all);
  const FemMaterial back = read_fem_parameter_file(path, spline);
  EXPECT_EQ(back.shear_knot_N_per_m[0], 2.0);
  EXPECT_EQ(back.shear_knot_N_per_m[1], 0.7);
  std::filesystem::remove(path);
}

}  // namespace
}  // namespace wl
