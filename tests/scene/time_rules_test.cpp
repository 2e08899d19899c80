// The time rules shared by scene files and command-line overrides.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "models/scene/scene.h"

namespace wl {
namespace {

int none(const std::string&) { return 0; }

std::string violated_key(const Scene& s, const std::function<int(const std::string&)>& rank = none) {
  const auto v = time_settings_violation(s, rank);
  return v ? v->key : "";
}

TEST(TimeRules, DefaultsAndShippedValuesPass) {
  EXPECT_FALSE(time_settings_violation(Scene{}, none)) << time_settings_violation(Scene{}, none)->expected;
}

TEST(TimeRules, EveryValueFiniteAndPositive) {
  const double bad[] = {0.0, -1e-3, std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()};
  for (double x : bad) {
    for (auto [key, field] : {std::pair{"time.duration_s", &Scene::duration_s}, std::pair{"time.dt_s", &Scene::dt_s},
                              std::pair{"time.output_interval_s", &Scene::output_interval_s}}) {
      Scene s;
      s.*field = x;
      const auto v = time_settings_violation(s, none);
      ASSERT_TRUE(v) << key << " = " << x;
      EXPECT_EQ(v->key, key);
      EXPECT_NE(v->expected.find("finite number > 0"), std::string::npos) << v->expected;
    }
    Scene s;
    s.atol = x;
    EXPECT_EQ(violated_key(s), "time.atol") << x;
    s = Scene{};
    s.rtol = x == 0.0 ? 1.0 : x;
    EXPECT_EQ(violated_key(s), "time.rtol") << x;
  }
}

// A tolerance below round-off is refused; the floor itself is accepted.
TEST(TimeRules, RtolHasAFloorNearRoundOff) {
  Scene s;
  for (double x : {1e-16, 9.99e-13, 5e-324}) {
    s.rtol = x;
    EXPECT_EQ(violated_key(s), "time.rtol") << x;
  }
  s.rtol = 1e-12;
  s.atol = 1e-15;
  EXPECT_FALSE(time_settings_violation(s, none)) << "rtol 1e-12";
}

TEST(TimeRules, StepWithinIntervalWithinDuration) {
  Scene s;
  s.dt_s = 2 * s.output_interval_s;
  EXPECT_EQ(violated_key(s), "time.output_interval_s");  // a tie blames the interval
  // The stated side of a conflict is blamed.
  EXPECT_EQ(violated_key(s, [](const std::string& k) { return k == "time.dt_s" ? 2 : 0; }), "time.dt_s");
  s = Scene{};
  s.output_interval_s = 2 * s.duration_s;
  EXPECT_EQ(violated_key(s), "time.output_interval_s");
  const auto v = time_settings_violation(s, [](const std::string& k) { return k == "time.duration_s" ? 2 : 1; });
  ASSERT_TRUE(v);
  EXPECT_EQ(v->key, "time.duration_s");
  EXPECT_NE(v->expected.find("≥ time.output_interval_s"), std::string::npos) << v->expected;
  s = Scene{};
  s.dt_s = s.duration_s * 3;
  s.output_interval_s = s.dt_s;
  EXPECT_EQ(violated_key(s), "time.dt_s");
}

TEST(TimeRules, StepAndFrameCountsAreBounded) {
  Scene s;
  s.output_interval_s = s.duration_s;
  s.dt_s = s.duration_s / (kMaxSteps * 2);
  EXPECT_EQ(violated_key(s), "time.dt_s");
  s.dt_s = s.duration_s / (kMaxSteps / 2);
  EXPECT_EQ(violated_key(s), "");
  s.adaptive = true;  // dt is then only the first step
  s.dt_s = s.duration_s / (kMaxSteps * 2);
  EXPECT_EQ(violated_key(s), "");
  s = Scene{};
  s.duration_s = 1.0;
  s.dt_s = s.output_interval_s = s.duration_s / (kMaxFrames * 2);
  s.adaptive = true;
  EXPECT_EQ(violated_key(s), "time.output_interval_s");
}

TEST(TimeRules, SceneReaderLocatesViolations) {
  const std::string text = "[cloth]\nwarps = 5\n\n[time]\nduration_s = 0.005\ndt_s = 0.001\n";
  try {
    parse_scene(text, "s.toml");
    FAIL() << "output_interval_s (default 0.01) > duration_s accepted";
  } catch (const SceneError& e) {
    EXPECT_EQ(e.line, 5) << e.what();  // the stated duration, not the default interval
    EXPECT_EQ(e.key, "time.duration_s");
  }
  const Scene s = parse_scene(text + "output_interval_s = 0.005\n", "s.toml");
  EXPECT_EQ(s.key_lines.at("time.dt_s"), 6);
  EXPECT_EQ(s.key_lines.at("time.output_interval_s"), 7);
  EXPECT_EQ(s.key_lines.at("time"), 4);
  EXPECT_FALSE(s.key_lines.count("time.integrator"));
  EXPECT_EQ(s.text, text + "output_interval_s = 0.005\n");  // the text as read, kept for the record
  try {
    parse_scene("[time]\ndt_s = 1e-9\n", "s.toml");
    FAIL() << "5e8 steps accepted";
  } catch (const SceneError& e) {
    EXPECT_EQ(e.line, 2);
    EXPECT_EQ(e.key, "time.dt_s");
  }
}

TEST(TimeRules, LockExponentMustBePositive) {
  // The Gong shear term divides by nothing but rejects c = 0: the scene says so first, located.
  try {
    parse_scene("[contact]\nshear_model = \"gong\"\nlock_exponent = 0\n", "s.toml");
    FAIL() << "lock_exponent = 0 accepted";
  } catch (const SceneError& e) {
    EXPECT_EQ(e.line, 3);
    EXPECT_EQ(e.key, "contact.lock_exponent");
  }
}

// The settling phase (docs/models.md §3.11.6): fixed steps only, a step within
// the frame interval, starting before the end.
TEST(TimeRules, SettlingPhaseNeedsFixedStepsWithinTheRun) {
  Scene s;
  s.settle_after_s = 0.2;
  s.settle_dt_s = s.output_interval_s;
  EXPECT_FALSE(time_settings_violation(s, none));
  for (auto flag : {&Scene::adaptive, &Scene::error_estimate}) {
    Scene a = s;
    a.*flag = true;
    EXPECT_EQ(violated_key(a), "time.settle_dt_s");
  }
  Scene a = s;
  a.accuracy_m = 1e-4;
  EXPECT_EQ(violated_key(a), "time.settle_dt_s");
  a = s;
  a.settle_dt_s = 2 * s.output_interval_s;
  EXPECT_EQ(violated_key(a), "time.settle_dt_s");
  a = s;
  a.settle_after_s = s.duration_s;
  EXPECT_EQ(violated_key(a), "time.settle_after_s");
}

}  // namespace
}  // namespace wl
