// Scene files: every shipped scene loads with the published numbers, absent
// keys take the defaults of scene.h, and each kind of bad scene is reported
// with file, line, key, value and expectation (never a crash, never a default).
#include "models/scene/scene.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

namespace wl {
namespace {

namespace fs = std::filesystem;

const fs::path kScenes = fs::path(WEAVELAB_SOURCE_DIR) / "experiments" / "scenes";

// Parses `text` expecting a SceneError; checks its fields and the what() format.
SceneError expect_error(const std::string& text, int line, const std::string& key, const std::string& expected_part,
                        const std::string& file = "bad.toml") {
  try {
    parse_scene(text, file);
  } catch (const SceneError& e) {
    EXPECT_EQ(e.file, file);
    EXPECT_EQ(e.line, line) << e.what();
    EXPECT_EQ(e.key, key) << e.what();
    EXPECT_NE(e.expected.find(expected_part), std::string::npos) << e.what();
    const std::string head = file + ":" + std::to_string(line) + ": key '" + key + "': got ";
    EXPECT_EQ(std::string(e.what()).rfind(head, 0), 0u) << e.what();
    EXPECT_NE(std::string(e.what()).find(", expected " + e.expected), std::string::npos) << e.what();
    return e;
  }
  ADD_FAILURE() << "no SceneError for:\n" << text;
  return SceneError("", 0, "", "", "");
}

TEST(SceneFiles, AllShippedScenesLoad) {
  int count = 0;
  for (const auto& entry : fs::directory_iterator(kScenes)) {
    if (entry.path().extension() != ".toml") continue;
    ++count;
    SCOPED_TRACE(entry.path().filename().string());
    EXPECT_NO_THROW({
      try {
        load_scene(entry.path().string());
      } catch (const SceneError& e) {
        ADD_FAILURE() << e.what();
        throw;
      }
    });
  }
  EXPECT_GE(count, 7);
}

// Numbers from docs/models.md §8 (the published scene, Table T1, the authors' code).
TEST(SceneFiles, HangingWindHasThePublishedNumbers) {
  const Scene s = load_scene((kScenes / "hanging_wind.toml").string());
  EXPECT_EQ(s.warps, 17);
  EXPECT_EQ(s.wefts, 17);
  EXPECT_DOUBLE_EQ(s.spacing_m, 0.001);
  EXPECT_DOUBLE_EQ(s.radius_m, 0.0005);
  EXPECT_EQ(s.pattern.kind, Pattern::Kind::plain);
  ASSERT_EQ(s.yarn_types.size(), 2u);
  EXPECT_DOUBLE_EQ(s.yarn_types.at("yarn1").density_kg_per_m, 0.0020);
  EXPECT_DOUBLE_EQ(s.yarn_types.at("yarn1").stretch_modulus_Pa, 500000.0);
  EXPECT_DOUBLE_EQ(s.yarn_types.at("yarn1").bending_modulus_Pa, 0.00014);
  EXPECT_DOUBLE_EQ(s.yarn_types.at("yarn2").density_kg_per_m, 0.0025);
  EXPECT_DOUBLE_EQ(s.yarn_types.at("yarn2").stretch_modulus_Pa, 170000.0);
  EXPECT_DOUBLE_EQ(s.yarn_types.at("yarn2").bending_modulus_Pa, 0.00011);
  // Hybrid: types alternate with yarn parity for warps and wefts.
  EXPECT_DOUBLE_EQ(s.warp_type(0).stretch_modulus_Pa, 500000.0);
  EXPECT_DOUBLE_EQ(s.warp_type(1).stretch_modulus_Pa, 170000.0);
  EXPECT_DOUBLE_EQ(s.weft_type(16).stretch_modulus_Pa, 500000.0);
  EXPECT_EQ(s.contact.shear_model, ContactParams::ShearModel::gong);
  EXPECT_EQ(s.contact.friction_model, ContactParams::FrictionModel::gong);
  EXPECT_DOUBLE_EQ(s.contact.shear_modulus_Pa, 1000.0);
  EXPECT_DOUBLE_EQ(s.contact.friction_coefficient, 0.5);
  EXPECT_DOUBLE_EQ(s.contact.friction_stiffness_N_per_m, 1000.0);
  EXPECT_DOUBLE_EQ(s.contact.friction_damping_Ns_per_m, 1000.0);
  EXPECT_DOUBLE_EQ(s.contact.tanh_sharpness_per_m, 10.0);
  EXPECT_DOUBLE_EQ(s.contact.parallel_stiffness_N_per_m2, 1.0);
  EXPECT_DOUBLE_EQ(s.contact.lock_exponent, 3.0);
  EXPECT_DOUBLE_EQ(s.contact.lock_sigma, 0.6);
  EXPECT_EQ(s.pose, Scene::Pose::upright);
  EXPECT_TRUE(s.pins.empty());
  ASSERT_EQ(s.handles.size(), 2u);
  EXPECT_EQ(s.handles[0].node.i, 0);
  EXPECT_EQ(s.handles[0].node.j, 0);
  EXPECT_EQ(s.handles[1].node.i, 16);
  EXPECT_EQ(s.handles[1].node.j, 0);
  EXPECT_DOUBLE_EQ(s.handles[1].stiffness_N_per_m, 1e4);
  EXPECT_EQ(s.gravity_m_per_s2, (std::array<double, 3>{0.0, 0.0, -9.8}));
  EXPECT_EQ(s.wind_velocity_m_per_s, (std::array<double, 3>{0.0, 5.0, 0.0}));
  EXPECT_DOUBLE_EQ(s.air_density_kg_per_m3, 2.0);
  EXPECT_DOUBLE_EQ(s.wind_drag_Ns_per_m3, 0.5);
  EXPECT_DOUBLE_EQ(s.dt_s, 0.001);
  EXPECT_NEAR(s.duration_s / s.dt_s, 500.0, 1e-9);
  EXPECT_DOUBLE_EQ(s.output_interval_s, 0.01);
  EXPECT_EQ(s.integrator, "be-linear");
  EXPECT_EQ(s.source, (kScenes / "hanging_wind.toml").string());
}

TEST(SceneFiles, VariantsDifferOnlyWhereNamed) {
  const Scene twill = load_scene((kScenes / "hanging_wind_twill.toml").string());
  EXPECT_EQ(twill.pattern.kind, Pattern::Kind::twill);
  EXPECT_EQ(twill.pattern.twill_over, 2);
  EXPECT_EQ(twill.pattern.twill_under, 2);
  EXPECT_EQ(twill.pattern.twill_shift, 1);
  const Scene satin = load_scene((kScenes / "hanging_wind_satin.toml").string());
  EXPECT_EQ(satin.pattern.kind, Pattern::Kind::satin);
  EXPECT_EQ(satin.pattern.satin_harness, 5);
  EXPECT_EQ(satin.pattern.satin_step, 2);
  const Scene p13 = load_scene((kScenes / "hanging_wind_plain_13.toml").string());
  EXPECT_DOUBLE_EQ(p13.warp_type(1).stretch_modulus_Pa, 120000.0);  // T1 Yarn3
  EXPECT_DOUBLE_EQ(p13.warp_type(0).stretch_modulus_Pa, 500000.0);  // T1 Yarn1
  const Scene p23 = load_scene((kScenes / "hanging_wind_plain_23.toml").string());
  EXPECT_DOUBLE_EQ(p23.weft_type(0).density_kg_per_m, 0.0025);     // T1 Yarn2
  EXPECT_DOUBLE_EQ(p23.weft_type(1).bending_modulus_Pa, 0.00009);  // T1 Yarn3
  for (int n : {65, 129}) {
    const Scene s = load_scene((kScenes / ("hanging_wind_" + std::to_string(n) + ".toml")).string());
    EXPECT_EQ(s.warps, n);
    EXPECT_EQ(s.wefts, n);
    ASSERT_EQ(s.handles.size(), 2u);
    EXPECT_EQ(s.handles[1].node.i, n - 1);  // top corners
    EXPECT_EQ(s.handles[1].node.j, 0);
    EXPECT_DOUBLE_EQ(s.contact.shear_modulus_Pa, 1000.0);
  }
}

TEST(SceneParse, EmptyFileGivesTheDefaults) {
  const Scene s = parse_scene("", "empty.toml");
  const Scene d;
  EXPECT_EQ(s.source, "empty.toml");
  EXPECT_EQ(s.warps, d.warps);
  EXPECT_EQ(s.wefts, d.wefts);
  EXPECT_EQ(s.spacing_m, d.spacing_m);
  EXPECT_EQ(s.radius_m, d.radius_m);
  EXPECT_EQ(s.sliding, d.sliding);
  EXPECT_EQ(s.pattern.kind, d.pattern.kind);
  EXPECT_EQ(s.warp_yarn_types, d.warp_yarn_types);
  ASSERT_EQ(s.yarn_types.size(), 1u);
  EXPECT_EQ(s.yarn_types.at("default").stretch_modulus_Pa, YarnType{}.stretch_modulus_Pa);
  EXPECT_EQ(s.contact.lock_sigma, d.contact.lock_sigma);
  EXPECT_EQ(s.pose, d.pose);
  EXPECT_EQ(s.gravity_m_per_s2, d.gravity_m_per_s2);
  EXPECT_EQ(s.dt_s, d.dt_s);
  EXPECT_EQ(s.integrator, d.integrator);
  EXPECT_EQ(s.fem.stride, 1);
  EXPECT_FALSE(s.fem.shear_N_per_m.has_value());
  EXPECT_TRUE(s.terms.friction);
}

TEST(SceneParse, AbsentKeysKeepDefaultsBesideGivenOnes) {
  const Scene s = parse_scene(
      "[cloth]\nwarps = 5\n[contact]\nfriction_coefficient = 0.3\nshear_model = \"cirio\"\n"
      "[terms]\nwind = false\n[fem]\nshear_N_per_m = 2\n[time]\ndt_s = 0.002\n",
      "partial.toml");
  const Scene d;
  EXPECT_EQ(s.warps, 5);
  EXPECT_EQ(s.wefts, d.wefts);
  EXPECT_EQ(s.contact.friction_coefficient, 0.3);
  EXPECT_EQ(s.contact.shear_model, ContactParams::ShearModel::cirio);
  EXPECT_EQ(s.contact.friction_model, d.contact.friction_model);
  EXPECT_EQ(s.contact.shear_modulus_Pa, d.contact.shear_modulus_Pa);
  EXPECT_FALSE(s.terms.wind);
  EXPECT_TRUE(s.terms.gravity);
  EXPECT_EQ(s.fem.shear_N_per_m, 2.0);  // an integer is accepted for a number
  EXPECT_FALSE(s.fem.warp_stretch_N_per_m.has_value());
  EXPECT_EQ(s.dt_s, 0.002);
  EXPECT_EQ(s.duration_s, d.duration_s);
}

TEST(SceneErrors, WhatReadsFileLineKeyValueExpected) {
  try {
    parse_scene("[cloth]\nspacing_m = 0.001\nradius_m = -0.5\n", "bad.toml");
    FAIL() << "no error";
  } catch (const SceneError& e) {
    EXPECT_STREQ(e.what(),
                 "bad.toml:3: key 'cloth.radius_m': got -0.5, expected a number > 0 and < cloth.spacing_m/√2 "
                 "(= 0.0007071067811865475), so that the shear lock angle 2·arcsin(R/L) stays below π/2");
    EXPECT_EQ(e.value, "-0.5");
  }
}

TEST(SceneErrors, SyntaxError) {
  const SceneError e = expect_error("[cloth]\nwarps = 17\nradius_m = = 3\n", 3, "(syntax)", "valid TOML");
  EXPECT_EQ(e.value, "radius_m = = 3");
}

TEST(SceneErrors, UnknownKeyIsNeverIgnored) {
  const SceneError e = expect_error("[cloth]\nwarps = 17\n\nradius_mm = 0.5\n", 4, "cloth.radius_mm", "radius_m");
  EXPECT_EQ(e.value, "0.5");
  expect_error("[[handles]]\nnode = [0, 0]\nstifness_N_per_m = 5.0\n", 3, "handles[0].stifness_N_per_m",
               "stiffness_N_per_m");
  expect_error("[yarn_types.a]\ndensity = 1.0\n[cloth]\nwarp_yarn_types = [\"a\"]\n", 2, "yarn_types.a.density",
               "density_kg_per_m");
}

TEST(SceneErrors, UnknownTable) {
  expect_error("[cloth]\nwarps = 5\n[clothes]\nwefts = 5\n", 3, "clothes", "cloth");
  expect_error("[cloth.patern]\nkind = \"plain\"\n", 1, "cloth.patern", "pattern");
  expect_error("gravity = [0.0, 0.0, -9.8]\n", 1, "gravity", "a table");
}

TEST(SceneErrors, WrongTypes) {
  SceneError e = expect_error("[cloth]\nspacing_m = \"1mm\"\n", 2, "cloth.spacing_m", "a number > 0");
  EXPECT_EQ(e.value, "\"1mm\"");
  e = expect_error("[cloth]\nwarps = 17.0\n", 2, "cloth.warps", "an integer");
  EXPECT_EQ(e.value, "17.0");
  expect_error("[cloth]\nsliding = 1\n", 2, "cloth.sliding", "true or false");
  expect_error("[wind]\nvelocity_m_per_s = [0.0, 5.0]\n", 2, "wind.velocity_m_per_s", "3 numbers");
  expect_error("[time]\nintegrator = 3\n", 2, "time.integrator", "integrator name");
  expect_error("[pose]\nkind = \"hanging\"\n", 2, "pose.kind", "\"flat\", \"upright\"");
  expect_error("[cloth]\nradius_m = nan\n", 2, "cloth.radius_m", "a number > 0");
}

TEST(SceneErrors, RadiusMustBePositiveAndBelowSpacing) {
  expect_error("[cloth]\nradius_m = -0.0005\n", 2, "cloth.radius_m", "a number > 0");
  expect_error("[cloth]\nspacing_m = 0.001\nradius_m = 0.001\n", 3, "cloth.radius_m",
               "< cloth.spacing_m/√2 (= 0.0007071067811865475)");
  // R/L = 0.75: the lock angle 2 arcsin(R/L) would pass π/2.
  expect_error("[cloth]\nspacing_m = 0.001\nradius_m = 0.00075\n", 3, "cloth.radius_m", "lock angle");
  // Spacing below √2 × the default radius: the spacing is at fault.
  expect_error("[cloth]\nspacing_m = 0.0006\n", 2, "cloth.spacing_m", "> √2·cloth.radius_m (= 0.0007071067811865476)");
}

TEST(SceneErrors, YarnTypeNamesMustExistAndBeUsed) {
  const std::string types = "[yarn_types.yarn1]\ndensity_kg_per_m = 0.002\n";
  SceneError e =
      expect_error(types + "[cloth]\nwarp_yarn_types = [\"yarn1\",\n  \"yarn2\"]\nweft_yarn_types = [\"yarn1\"]\n", 5,
                   "cloth.warp_yarn_types", "defined: yarn1");
  EXPECT_EQ(e.value, "\"yarn2\"");
  // A defined type that no yarn uses (e.g. lists forgotten) is an error, not silently ignored.
  expect_error(types, 1, "yarn_types.yarn1", "used by cloth.warp_yarn_types");
  expect_error("[yarn_types.a]\ndensity_kg_per_m = 0.0\n[cloth]\nwarp_yarn_types = [\"a\"]\n", 2,
               "yarn_types.a.density_kg_per_m", "> 0");
  expect_error("[cloth]\nweft_yarn_types = []\n", 2, "cloth.weft_yarn_types", "non-empty array");
}

TEST(SceneErrors, NodeRefsMustBeInsideTheGridAndUnique) {
  const std::string cloth = "[cloth]\nwarps = 5\nwefts = 7\n";
  expect_error(cloth + "[[handles]]\nnode = [0, 0]\n[[handles]]\nnode = [7, 0]\n", 7, "handles[1].node",
               "0 ≤ i < cloth.wefts (= 7)");
  expect_error(cloth + "[[pins]]\nnode = [0, 5]\n", 5, "pins[0].node", "0 ≤ j < cloth.warps (= 5)");
  expect_error(cloth + "[[pins]]\nnode = [-1, 0]\n", 5, "pins[0].node", "0 ≤ i");
  expect_error(cloth + "[[pins]]\nnode = [1.0, 0]\n", 5, "pins[0].node", "integers");
  SceneError e = expect_error(cloth + "[[pins]]\n\n[[pins]]\nnode = [1, 1]\n", 4, "pins[0].node", "[i, j]");
  EXPECT_EQ(e.value, "nothing (key missing)");
  expect_error(cloth + "[[pins]]\nnode = [1, 1]\n[[handles]]\nnode = [1, 1]\n", 7, "handles[0].node",
               "pins[0].node uses it");
}

// Prescribed handle motion (docs/models.md §3.10): a velocity, optionally
// timed; a static handle has no timing, and a stop must come after the start.
TEST(SceneParse, HandleMotion) {
  const std::string h = "[[handles]]\nnode = [0, 0]\n";
  const Scene moving =
      parse_scene(h + "velocity_m_per_s = [-0.5, 0, 0.25]\nstart_s = 0.002\nstop_s = 0.03\n", "m.toml");
  EXPECT_EQ(moving.handles[0].velocity_m_per_s, (std::array<double, 3>{-0.5, 0.0, 0.25}));
  EXPECT_EQ(moving.handles[0].start_s, 0.002);
  EXPECT_EQ(moving.handles[0].stop_s, 0.03);
  const Scene still = parse_scene(h, "s.toml");
  EXPECT_EQ(still.handles[0].velocity_m_per_s, (std::array<double, 3>{0.0, 0.0, 0.0}));
  EXPECT_EQ(still.handles[0].start_s, 0.0);
  EXPECT_TRUE(std::isinf(still.handles[0].stop_s));
}

TEST(SceneErrors, HandleMotionMustBeFiniteAndOrdered) {
  const std::string h = "[cloth]\nwarps = 5\n[[handles]]\nnode = [0, 0]\n";
  expect_error(h + "velocity_m_per_s = [0, nan, 0]\n", 5, "handles[0].velocity_m_per_s", "3 finite numbers");
  expect_error(h + "velocity_m_per_s = [1, 0]\n", 5, "handles[0].velocity_m_per_s", "3 finite numbers");
  const std::string v = h + "velocity_m_per_s = [0.1, 0, 0]\n";
  expect_error(v + "start_s = -0.01\n", 6, "handles[0].start_s", "≥ 0");
  expect_error(v + "stop_s = inf\n", 6, "handles[0].stop_s", "> start_s (= 0)");
  const SceneError e =
      expect_error(v + "start_s = 0.02\nstop_s = 0.01\n", 7, "handles[0].stop_s", "> start_s (= 0.02)");
  EXPECT_EQ(e.value, "0.01");
  expect_error(h + "stop_s = 0.01\n", 5, "handles[0].stop_s", "without velocity_m_per_s");
  expect_error(h + "start_s = 0.01\n", 5, "handles[0].start_s", "without velocity_m_per_s");
}

TEST(SceneErrors, PatternsMustMakeSense) {
  expect_error("[cloth.pattern]\nkind = \"plain\"\nover = 2\n", 3, "cloth.pattern.over", "kind");
  expect_error("[cloth.pattern]\nkind = \"twill\"\nover = 0\n", 3, "cloth.pattern.over", "≥ 1");
  expect_error("[cloth.pattern]\nkind = \"twill\"\nover = 2\nunder = 2\nshift = 4\n", 5, "cloth.pattern.shift",
               "0 < |shift| < over + under (= 4)");
  expect_error("[cloth]\nwarps = 5\n[cloth.pattern]\nkind = \"twill\"\nover = 3\nunder = 3\n", 6, "cloth.pattern.under",
               "≤ min(cloth.warps, cloth.wefts) (= 5)");
  expect_error("[cloth.pattern]\nkind = \"satin\"\nharness = 8\nstep = 2\n", 4, "cloth.pattern.step", "gcd");
  expect_error("[cloth.pattern]\nkind = \"satin\"\nharness = 4\n", 3, "cloth.pattern.harness", "≥ 5");
  // harness 7 with the default step 2 is valid; harness 6 has no valid step at all.
  EXPECT_NO_THROW(parse_scene("[cloth.pattern]\nkind = \"satin\"\nharness = 7\n", "ok.toml"));
  expect_error("[cloth.pattern]\nkind = \"satin\"\nharness = 6\n", 1, "cloth.pattern.step", "gcd");
}

// Knit patterns (docs/models.md §11): the counts a pattern's tile must cover,
// knit keys only on knit scenes, and the tables a knit scene does not take.
TEST(SceneParse, KnitPatternsAndTheirKeys) {
  const Scene s = parse_scene(
      "[cloth.pattern]\nkind = \"rib2x2\"\ncourses = 5\nwales = 8\n[knit]\nroll_stiffness_N = 2e-5\n", "ok.toml");
  ASSERT_TRUE(s.knit.has_value());
  EXPECT_EQ(s.knit->kind, KnitPattern::Kind::rib2x2);
  EXPECT_EQ(s.knit->courses, 5);
  EXPECT_EQ(s.knit->wales, 8);
  EXPECT_DOUBLE_EQ(s.knit->roll_stiffness_N, 2e-5);
  EXPECT_DOUBLE_EQ(s.knit->course_spacing_m, 0.8 * s.spacing_m);
  EXPECT_FALSE(parse_scene("[cloth.pattern]\nkind = \"plain\"\n", "ok.toml").knit.has_value());
  const Scene held = parse_scene(
      "[cloth.pattern]\nkind = \"stockinette\"\ncourses = 4\nwales = 3\n"
      "[[pins]]\nnode = [0, 5]\n[[handles]]\nnode = [4, 0]\nstiffness_N_per_m = 50\n",
      "ok.toml");
  ASSERT_EQ(held.pins.size(), 1u);
  EXPECT_EQ(held.pins[0].i, 0);
  EXPECT_EQ(held.pins[0].j, 5);
  ASSERT_EQ(held.handles.size(), 1u);
  EXPECT_EQ(held.handles[0].node.i, 4);
}

TEST(SceneErrors, KnitPatternsMustTileAndKnitKeysNeedAKnit) {
  struct Case {
    std::string text;
    int line;
    std::string key, expected;
  };
  const std::string pattern = "[cloth.pattern]\nkind = ";
  const std::vector<Case> cases = {
      {pattern + "\"jersey\"\n", 2, "cloth.pattern.kind", "stockinette"},
      {pattern + "\"garter\"\ncourses = 7\n", 3, "cloth.pattern.courses", "even"},
      {pattern + "\"rib2x2\"\nwales = 6\n", 3, "cloth.pattern.wales", "multiple of 4"},
      {pattern + "\"stockinette\"\ncourses = 1\n", 3, "cloth.pattern.courses", "≥ 2"},
      {pattern + "\"stockinette\"\nwales = 257\n", 3, "cloth.pattern.wales", "≤ 256"},
      {pattern + "\"plain\"\ncourses = 4\n", 3, "cloth.pattern.courses", "kind"},
      {pattern + "\"twill\"\n[knit]\nroll_stiffness_N = 1e-5\n", 4, "knit.roll_stiffness_N", "woven scene"},
      {pattern + "\"garter\"\n[knit]\nroll_stiffness_N = -1\n", 4, "knit.roll_stiffness_N", "≥ 0"},
      {pattern + "\"stockinette\"\n[wind]\nair_density_kg_per_m3 = 1\n", 3, "wind", "knit scene"},
      // Knit pins and handles name stitch contacts: row 0 … courses, column 0 … 2·wales − 1.
      {pattern + "\"stockinette\"\ncourses = 4\nwales = 3\n[[pins]]\nnode = [5, 0]\n", 6, "pins[0].node",
       "0 ≤ i ≤ cloth.pattern.courses (= 4)"},
      {pattern + "\"stockinette\"\ncourses = 4\nwales = 3\n[[handles]]\nnode = [0, 6]\n", 6, "handles[0].node",
       "0 ≤ j < 2·cloth.pattern.wales (= 6)"},
      {pattern + "\"garter\"\n[[pins]]\nnode = [0, 1]\n[[handles]]\nnode = [0, 1]\n", 6, "handles[0].node",
       "not already pinned"},
  };
  for (const Case& c : cases) expect_error(c.text, c.line, c.key, c.expected);
}

TEST(SceneErrors, CrossFieldTimeAndFemLimits) {
  expect_error("[time]\ndt_s = 0.01\noutput_interval_s = 0.005\n", 3, "time.output_interval_s", "≥ time.dt_s (= 0.01)");
  expect_error("[time]\ndt_s = 0.02\n", 2, "time.dt_s", "≤ time.output_interval_s");
  expect_error("[time]\nduration_s = 0.1\ndt_s = 0.2\noutput_interval_s = 0.2\n", 3, "time.dt_s", "≤ time.duration_s");
  expect_error("[fem]\nstride = 3\n", 2, "fem.stride", "dividing cloth.wefts − 1 (= 16)");
  expect_error("[fem]\nstride = 4\n[[pins]]\nnode = [2, 0]\n", 4, "pins[0].node", "multiples of fem.stride (= 4)");
  expect_error("[contact]\nlock_sigma = 0\n", 2, "contact.lock_sigma", "> 0");
  expect_error("[contact]\nfriction_coefficient = -0.1\n", 2, "contact.friction_coefficient", "≥ 0");
}

TEST(SceneErrors, MissingFile) {
  const std::string path = (fs::path(::testing::TempDir()) / "no_such_scene.toml").string();
  try {
    load_scene(path);
    FAIL() << "no error";
  } catch (const SceneError& e) {
    EXPECT_EQ(e.file, path);
    EXPECT_EQ(e.line, 0);
    EXPECT_EQ(e.key, "(file)");
    EXPECT_EQ(e.value, path);
    EXPECT_EQ(e.expected, "a readable scene file");
  }
}

TEST(SceneFiles, GridLineBendingNeedsTheGridMesh) {
  const fs::path dir = fs::path(::testing::TempDir()) / "scene_grid_lines";
  fs::create_directories(dir);
  std::ofstream(dir / "m.vtu") << "x";
  std::ofstream(dir / "g.toml") << "[fem]\ngrid_line_bending = true\ndiagonal_bending_N_m = 2e-8\n";
  std::ofstream(dir / "m.toml") << "[fem]\nmesh_file = \"m.vtu\"\ngrid_line_bending = true\n";
  const Scene s = load_scene((dir / "g.toml").string());
  EXPECT_TRUE(s.fem.grid_line_bending);
  EXPECT_EQ(*s.fem.diagonal_bending_N_m, 2e-8);
  EXPECT_FALSE(FemSettings{}.grid_line_bending);  // off by default
  try {
    load_scene((dir / "m.toml").string());
    FAIL() << "no error";
  } catch (const SceneError& e) {
    EXPECT_EQ(e.key, "fem.grid_line_bending");
    EXPECT_NE(e.expected.find("grid mesh only"), std::string::npos);
  }
  fs::remove_all(dir);
}

TEST(SceneText, YarnNodeMassNeedsAVertexAtEveryCrossing) {
  EXPECT_TRUE(parse_scene("[fem]\nyarn_node_mass = true\n", "y.toml").fem.yarn_node_mass);
  EXPECT_FALSE(FemSettings{}.yarn_node_mass);  // off by default
  try {
    parse_scene("[cloth]\nwarps = 5\nwefts = 5\n[fem]\nstride = 2\nyarn_node_mass = true\n", "y.toml");
    FAIL() << "no error";
  } catch (const SceneError& e) {
    EXPECT_EQ(e.key, "fem.yarn_node_mass");
    EXPECT_EQ(e.line, 6);
    EXPECT_NE(e.expected.find("stride = 1"), std::string::npos) << e.what();
  }
}

TEST(SceneFiles, FemPathsResolveAgainstTheSceneDirectory) {
  const fs::path dir = fs::path(::testing::TempDir()) / "scene_fem_paths";
  fs::create_directories(dir / "meshes");
  std::ofstream(dir / "meshes" / "m.vtu") << "x";
  std::ofstream(dir / "s.toml") << "[fem]\nmesh_file = \"meshes/m.vtu\"\n";
  std::ofstream(dir / "t.toml") << "[fem]\n\nparameter_file = \"params.json\"\n";
  const Scene s = load_scene((dir / "s.toml").string());
  EXPECT_TRUE(fs::equivalent(s.fem.mesh_file, dir / "meshes" / "m.vtu"));
  EXPECT_TRUE(s.fem.parameter_file.empty());
  try {
    load_scene((dir / "t.toml").string());
    FAIL() << "no error";
  } catch (const SceneError& e) {
    EXPECT_EQ(e.line, 3);
    EXPECT_EQ(e.key, "fem.parameter_file");
    EXPECT_EQ(e.value, "\"params.json\"");
    EXPECT_NE(e.expected.find("an existing file"), std::string::npos);
  }
  fs::remove_all(dir);
}

// Obstacles (docs/models.md §3.11): every key read, sizes positive and
// required by their shape, the shape known, the centre given.
TEST(SceneParse, ObstaclesAndTheirContact) {
  const Scene s = parse_scene(
      "[[obstacles]]\nshape = \"plane\"\ncenter_m = [0, 0, -0.01]\nrotation_deg = [10, 0, 0]\n"
      "friction_coefficient = 0.4\nvelocity_m_per_s = [0, 0, 0.1]\n"
      "[[obstacles]]\nshape = \"box\"\ncenter_m = [1, 2, 3]\nhalf_extents_m = [0.1, 0.2, 0.3]\n"
      "[[obstacles]]\nshape = \"disk\"\ncenter_m = [0, 0, 0]\nradius_m = 0.02\nthickness_m = 0.004\n"
      "[obstacle_contact]\nactivation_distance_m = 0.0002\nstiffness_N_per_m = 3.5\nfriction_speed_m_per_s = 0.01\n"
      "segment_edges = true\nstep_hessian = \"exact\"\n",
      "o.toml");
  ASSERT_EQ(s.obstacles.size(), 3u);
  EXPECT_EQ(s.obstacles[0].shape, ObstacleSpec::Shape::plane);
  EXPECT_EQ(s.obstacles[0].rotation_deg[0], 10.0);
  EXPECT_EQ(s.obstacles[0].friction_coefficient, 0.4);
  EXPECT_EQ(s.obstacles[0].velocity_m_per_s[2], 0.1);
  EXPECT_EQ(s.obstacles[0].line, 1);
  EXPECT_EQ(s.obstacles[1].half_extents_m[2], 0.3);
  EXPECT_EQ(s.obstacles[1].line, 7);
  EXPECT_EQ(s.obstacles[2].height_m, 0.004);
  EXPECT_EQ(*s.obstacle_contact.activation_distance_m, 0.0002);
  EXPECT_EQ(*s.obstacle_contact.stiffness_N_per_m, 3.5);
  EXPECT_EQ(s.obstacle_contact.friction_speed_m_per_s, 0.01);
  EXPECT_TRUE(s.obstacle_contact.segment_edges);
  EXPECT_FALSE(s.obstacle_contact.projected_step_hessian);
  const Scene plane = parse_scene("[[obstacles]]\nshape = \"plane\"\ncenter_m = [0, 0, 0]\n", "p.toml");
  EXPECT_FALSE(plane.obstacle_contact.segment_edges);
  EXPECT_TRUE(plane.obstacle_contact.projected_step_hessian);
}

TEST(SceneErrors, ObstacleShapeSizesAndRequiredKeys) {
  expect_error("[[obstacles]]\nshape = \"cone\"\ncenter_m = [0, 0, 0]\n", 2, "obstacles[0].shape", "\"sphere\"");
  expect_error("[[obstacles]]\ncenter_m = [0, 0, 0]\n", 1, "obstacles[0].shape", "\"plane\"");
  expect_error("[[obstacles]]\nshape = \"plane\"\n", 1, "obstacles[0].center_m", "3 numbers");
  expect_error("[[obstacles]]\nshape = \"sphere\"\ncenter_m = [0, 0, 0]\nradius_m = 0\n", 4, "obstacles[0].radius_m",
               "a number > 0");
  expect_error("[[obstacles]]\nshape = \"sphere\"\ncenter_m = [0, 0, 0]\n", 1, "obstacles[0].radius_m",
               "required for shape = \"sphere\"");
  expect_error("[[obstacles]]\nshape = \"cylinder\"\ncenter_m = [0, 0, 0]\nradius_m = 0.1\nheight_m = -1\n", 5,
               "obstacles[0].height_m", "a number > 0");
  expect_error("[[obstacles]]\nshape = \"disk\"\ncenter_m = [0, 0, 0]\nradius_m = 0.1\n", 1, "obstacles[0].thickness_m",
               "required for shape = \"disk\"");
  expect_error("[[obstacles]]\nshape = \"box\"\ncenter_m = [0, 0, 0]\nhalf_extents_m = [1, 0, 1]\n", 4,
               "obstacles[0].half_extents_m", "3 numbers > 0");
  expect_error("[[obstacles]]\nshape = \"plane\"\ncenter_m = [0, 0, 0]\nradius_m = 0.1\n", 4, "obstacles[0].radius_m",
               "for shape = \"plane\"");
  expect_error("[[obstacles]]\nshape = \"plane\"\ncenter_m = [0, 0, 0]\nfriction_coefficient = -0.1\n", 4,
               "obstacles[0].friction_coefficient", "a number ≥ 0");
  expect_error("[obstacle_contact]\nactivation_distance_m = 0\n", 2, "obstacle_contact.activation_distance_m",
               "a number > 0");
  expect_error("[obstacle_contact]\nstep_hessian = \"psd\"\n", 2, "obstacle_contact.step_hessian",
               "one of \"projected\", \"exact\"");
}

// Self-contact (docs/models.md §3.11.7): off by default, every key read,
// distances and stiffness positive, enabled a bool.
TEST(SceneParse, SelfContactKeys) {
  EXPECT_FALSE(parse_scene("", "o.toml").self_contact.enabled);
  const Scene s = parse_scene(
      "[cloth]\nwarps = 3\n[self_contact]\nenabled = true\nactivation_distance_m = 0.0002\nstiffness_N_per_m = 3.5\n",
      "o.toml");
  EXPECT_TRUE(s.self_contact.enabled);
  EXPECT_EQ(*s.self_contact.activation_distance_m, 0.0002);
  EXPECT_EQ(*s.self_contact.stiffness_N_per_m, 3.5);
  EXPECT_EQ(s.self_contact.line, 3);
  expect_error("[self_contact]\nenabled = true\nactivation_distance_m = 0\n", 3, "self_contact.activation_distance_m",
               "a number > 0");
  expect_error("[self_contact]\nstiffness_N_per_m = -2\n", 2, "self_contact.stiffness_N_per_m", "a number > 0");
  expect_error("[self_contact]\nenabled = 1\n", 2, "self_contact.enabled", "true or false");
  expect_error("[self_contact]\nenable = true\n", 2, "self_contact.enable", "");
}

}  // namespace
}  // namespace wl
