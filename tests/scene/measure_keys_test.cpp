// The [measures] table (models/scene/measure_reader.cpp): values read, every
// bad value or unknown key reported with file, line and key.
#include <gtest/gtest.h>

#include "models/scene/scene.h"

namespace wl {
namespace {

const std::string kCloth = "[cloth]\nwarps = 9\nwefts = 9\nspacing_m = 0.001\nradius_m = 0.0005\n";  // lines 1–5
const std::string kPedestal =
    "[[obstacles]]\nshape = \"disk\"\ncenter_m = [0.004, 0.004, -0.001]\nradius_m = 0.002\nthickness_m = "
    "0.002\n";  // 6–10

SceneError expect_error(const std::string& text, int line, const std::string& key, const std::string& expected_part) {
  try {
    parse_scene(text, "m.toml");
  } catch (const SceneError& e) {
    EXPECT_EQ(e.line, line) << e.what();
    EXPECT_EQ(e.key, key) << e.what();
    EXPECT_NE(e.expected.find(expected_part), std::string::npos) << e.what();
    return e;
  }
  ADD_FAILURE() << "no SceneError for:\n" << text;
  return SceneError("", 0, "", "", "");
}

TEST(MeasureKeys, AbsentMeansNothingMeasured) {
  const Scene s = parse_scene(kCloth + kPedestal, "m.toml");
  EXPECT_FALSE(s.measures.drape);
}

TEST(MeasureKeys, DrapeValuesAreRead) {
  const Scene s = parse_scene(
      kCloth + kPedestal + "[measures]\ndrape = true\ndrape_pixel_m = 0.0002\nfold_prominence_m = 0.001\n", "m.toml");
  EXPECT_TRUE(s.measures.drape);
  EXPECT_EQ(s.measures.drape_pixel_m, 0.0002);
  EXPECT_EQ(s.measures.fold_prominence_m, 0.001);
  EXPECT_EQ(s.measures.line, 11);
  const Scene d = parse_scene(kCloth + kPedestal + "[measures]\ndrape = true\n", "m.toml");
  EXPECT_EQ(d.measures.drape_pixel_m, 1e-4);
  EXPECT_EQ(d.measures.fold_prominence_m, 5e-4);
}

TEST(MeasureKeys, UnknownKeysAndBadValuesAreLocated) {
  const std::string head = kCloth + kPedestal + "[measures]\n";  // [measures] on line 11
  expect_error(head + "drape = true\ndrape_coeficient = true\n", 13, "measures.drape_coeficient", "drape");
  expect_error(head + "drape = \"yes\"\n", 12, "measures.drape", "true or false");
  expect_error(head + "drape = true\ndrape_pixel_m = 0\n", 13, "measures.drape_pixel_m", "cloth side / 8192");
  expect_error(head + "drape = true\ndrape_pixel_m = 0.002\n", 13, "measures.drape_pixel_m", "cloth.spacing_m");
  expect_error(head + "drape = true\nfold_prominence_m = -1\n", 13, "measures.fold_prominence_m", "> 0");
  expect_error(head + "drape = true\nfold_prominence_m = nan\n", 13, "measures.fold_prominence_m", "> 0");
  expect_error(head + "drape_pixel_m = 0.0002\n", 12, "measures.drape_pixel_m", "without drape = true");
  expect_error(kCloth + kPedestal + "[measures.drape]\n", 11, "measures.drape", "true or false");
}

TEST(MeasureKeys, DrapeNeedsAPedestalUnderAWovenCloth) {
  expect_error(kCloth + "[measures]\ndrape = true\n", 7, "measures.drape", "without a pedestal");
  const std::string turned = kPedestal + "rotation_deg = [90, 0, 0]\n";  // line 11
  expect_error(kCloth + turned + "[measures]\ndrape = true\n", 13, "measures.drape", "turned about x or y");
  const Scene about_z =
      parse_scene(kCloth + kPedestal + "rotation_deg = [0, 0, 30]\n[measures]\ndrape = true\n", "m.toml");
  EXPECT_TRUE(about_z.measures.drape);
  // A cloth the default pixel cannot fit: 16384 yarns of 1 mm need pixels ≥ 2 mm (16.383 m / 8192).
  expect_error(
      "[cloth]\nwarps = 16384\nspacing_m = 0.001\nradius_m = 0.0005\n" + kPedestal + "[measures]\ndrape = true\n", 10,
      "measures.drape_pixel_m", "cloth side / 8192");
}

}  // namespace
}  // namespace wl
