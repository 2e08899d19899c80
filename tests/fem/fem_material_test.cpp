#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <numbers>

#include "models/fem/fem_material.h"
#include "models/fem/tension_map.h"
#include "tests/fem/fem_test_scene.h"

namespace wl {
namespace {

TEST(FemMaterial, DefaultsFromYarnParameters) {
  Scene s = test::fem_scene(4, 4);
  s.yarn_types["stiff"] = YarnType{0.004, 1e6, 3e-4};
  s.warp_yarn_types = {"default", "stiff"};  // warps alternate: means over 4 warps = half each
  const double A = std::numbers::pi * 4e-4 * 4e-4, L = 1e-3;
  const FemMaterial m = default_fem_material(s);
  EXPECT_NEAR(m.warp_stretch_N_per_m, 0.5 * (5e5 + 1e6) * A / L, 1e-9);
  EXPECT_NEAR(m.weft_stretch_N_per_m, 5e5 * A / L, 1e-9);
  EXPECT_NEAR(m.warp_bending_N_m, 0.5 * (1.4e-4 + 3e-4) * A / L, 1e-15);
  EXPECT_NEAR(m.weft_bending_N_m, 1.4e-4 * A / L, 1e-15);
  EXPECT_NEAR(m.areal_density_kg_per_m2, (0.003 + 0.002) / L, 1e-12);
  EXPECT_NEAR(m.shear_N_per_m, 1000.0 * A / L, 1e-12);
  EXPECT_NEAR(m.shear_lock_angle_rad, std::numbers::pi / 2 - 2 * std::asin(0.4), 1e-12);
  EXPECT_DOUBLE_EQ(m.shear_lock_exponent, 3.0);
}

TEST(FemMaterial, SceneTableOverridesDefaults) {
  Scene s = test::fem_scene(3, 3);
  s.fem.warp_stretch_N_per_m = 123.0;
  s.fem.shear_lock_exponent = 2.0;
  const FemMaterial m = fem_material(s);
  EXPECT_DOUBLE_EQ(m.warp_stretch_N_per_m, 123.0);
  EXPECT_DOUBLE_EQ(m.shear_lock_exponent, 2.0);
  EXPECT_DOUBLE_EQ(m.weft_stretch_N_per_m, default_fem_material(s).weft_stretch_N_per_m);
}

std::string error_of(const std::string& text);

TEST(FemMaterial, ParameterFileOverridesAndRoundTrips) {
  FemMaterial base;
  base.shear_N_per_m = 5.0;
  const FemMaterial m = parse_fem_parameters(
      "warp_stretch_N_per_m = 612.5\nweft_bending_N_m = 2e-6\n[provenance]\nfit = \"biaxial\"\n", "p.toml", base);
  EXPECT_DOUBLE_EQ(m.warp_stretch_N_per_m, 612.5);
  EXPECT_DOUBLE_EQ(m.weft_bending_N_m, 2e-6);
  EXPECT_DOUBLE_EQ(m.shear_N_per_m, 5.0);

  FemMaterial all = default_fem_material(test::fem_scene(3, 3));
  EXPECT_EQ(all.diagonal_bending_N_m, 0.0);  // the diagonal stiffness is off by default
  all.diagonal_bending_N_m = 4e-8;
  const std::string path =
      (std::filesystem::temp_directory_path() / ("wl_fem_params_" + std::to_string(::getpid()) + ".toml")).string();
  write_fem_parameter_file(path, all, {{"note", "unit test"}});
  const FemMaterial back = read_fem_parameter_file(path, FemMaterial{});
  std::remove(path.c_str());
  EXPECT_DOUBLE_EQ(back.warp_stretch_N_per_m, all.warp_stretch_N_per_m);
  EXPECT_DOUBLE_EQ(back.weft_bending_N_m, all.weft_bending_N_m);
  EXPECT_DOUBLE_EQ(back.shear_lock_angle_rad, all.shear_lock_angle_rad);
  EXPECT_DOUBLE_EQ(back.areal_density_kg_per_m2, all.areal_density_kg_per_m2);
  EXPECT_DOUBLE_EQ(back.diagonal_bending_N_m, 4e-8);
  EXPECT_NE(error_of("diagonal_bending_N_m = -1\n").find("key 'diagonal_bending_N_m': got -1, expected a number > 0"),
            std::string::npos);
}

std::string error_of(const std::string& text) {
  try {
    parse_fem_parameters(text, "cal.toml", FemMaterial{});
  } catch (const FemParameterError& e) {
    return e.what();
  }
  return "no error";
}

TEST(FemMaterial, ParameterFileErrorsNameFileLineKeyValue) {
  EXPECT_EQ(error_of("shear_N_per_m = 1\nwarp_strech_N_per_m = 3\n")
                .rfind("cal.toml:2: key 'warp_strech_N_per_m': got an unknown key, expected one of", 0),
            0u)
      << error_of("warp_strech_N_per_m = 3");
  EXPECT_EQ(error_of("\nshear_N_per_m = -2.5\n"),
            "cal.toml:2: key 'shear_N_per_m': got -2.5, expected a number > 0 (N/m)");
  EXPECT_EQ(error_of("shear_N_per_m = \"x\"\n"),
            "cal.toml:1: key 'shear_N_per_m': got 'x', expected a number > 0 (N/m)");
  EXPECT_NE(error_of("shear_lock_angle_rad = 2.0").find("expected a shear angle in (0, π/2) rad"), std::string::npos);
  EXPECT_NE(error_of("a = = 1").find("cal.toml:1: key '(syntax)'"), std::string::npos);
  try {
    read_fem_parameter_file("/nonexistent/cal.toml", FemMaterial{});
    FAIL();
  } catch (const FemParameterError& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/cal.toml:0"), std::string::npos);
  }
}

TEST(FaceTension, SeedWorkedExample) {
  // Optitex note worked example: w_u = (1.1,0,0), w_v = (0,1,0), rest 1, 1 → tension 0.1·k_x
  const FaceTension t = face_tension(Vec3(1.1, 0, 0), Vec3(0, 1, 0), 1.0, 1.0, 300.0, 700.0);
  EXPECT_NEAR(t.lu, 1.1, 1e-15);
  EXPECT_NEAR(t.lv, 1.0, 1e-15);
  EXPECT_NEAR(t.tension, 0.1 * 300.0, 1e-12);
}

TEST(FaceTension, ClipsStiffnessIgnoresCompressionAndCombines) {
  // clipped stiffness 5e4
  EXPECT_NEAR(face_tension(Vec3(1.1, 0, 0), Vec3(0, 1, 0), 1, 1, 1e6, 1e6).tension, 0.1 * 5e4, 1e-9);
  // compression ignored
  EXPECT_NEAR(face_tension(Vec3(0.8, 0, 0), Vec3(0, 0.9, 0), 1, 1, 100, 100).tension, 0.0, 1e-15);
  // both stretched, at 60°: √(a² + b² + 2ab|cos α|)
  const double c = std::cos(M_PI / 3), sn = std::sin(M_PI / 3);
  const double a = 0.2 * 100, b = 0.1 * 50;
  const double expect = std::sqrt(a * a + b * b + 2 * a * b * c);
  EXPECT_NEAR(face_tension(Vec3(1.2, 0, 0), 1.1 * Vec3(c, sn, 0), 1, 1, 100, 50).tension, expect, 1e-12);
  // obtuse angle: wu − wv, same closed form with |cos|
  EXPECT_NEAR(face_tension(Vec3(1.2, 0, 0), 1.1 * Vec3(-c, sn, 0), 1, 1, 100, 50).tension, expect, 1e-12);
}

}  // namespace
}  // namespace wl

namespace wl {
namespace {

TEST(FemMaterial, PrecedenceDefaultsThenParameterFileThenSceneTable) {
  Scene s = test::fem_scene(3, 3);
  const std::string path =
      (std::filesystem::temp_directory_path() / ("wl_fem_prec_" + std::to_string(::getpid()) + ".toml")).string();
  FemMaterial file;
  file.warp_stretch_N_per_m = 77.0;
  file.shear_N_per_m = 9.0;
  write_fem_parameter_file(path, file);
  s.fem.parameter_file = path;
  s.fem.shear_N_per_m = 4.0;
  const FemMaterial m = fem_material(s);
  std::remove(path.c_str());
  EXPECT_DOUBLE_EQ(m.warp_stretch_N_per_m, 77.0);  // from the file
  EXPECT_DOUBLE_EQ(m.shear_N_per_m, 4.0);          // the scene's explicit value wins
  EXPECT_DOUBLE_EQ(m.weft_stretch_N_per_m, default_fem_material(s).weft_stretch_N_per_m);  // default
}

}  // namespace
}  // namespace wl
