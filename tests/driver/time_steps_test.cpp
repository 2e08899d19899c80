// The relative tolerance a command line gives (--rtol of calibrate, fidelity,
// diagnose, fit; --rtols of work-precision): the floor of the scene's
// time.rtol (kMinRtol, scene_limits.h), refused with the value as given.
#include <gtest/gtest.h>

#include <stdexcept>

#include "driver/time_steps.h"
#include "models/scene/scene.h"

namespace wl {
namespace {

std::string refusal(double rtol) {
  try {
    parse_time_steps("--time-steps", "controlled", rtol);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "(accepted)";
}

TEST(TimeSteps, RefusesAnRtolBelowTheFloorOfTheScenesTimeRtolStatingItsValue) {
  const std::string rule = ", expected a tolerance ≥ 1e-12 and < 1 (smaller tolerances are below round-off)";
  EXPECT_EQ(refusal(1e-7), "(accepted)");
  EXPECT_EQ(refusal(1e-12), "(accepted)");
  EXPECT_EQ(refusal(9.9e-13), "--rtol: got 9.9e-13" + rule);
  EXPECT_EQ(refusal(1e-300), "--rtol: got 1e-300" + rule);
  EXPECT_EQ(refusal(5e-324), "--rtol: got 4.94066e-324" + rule);  // its atol 1e-3·rtol would be 0
  EXPECT_EQ(refusal(0.0), "--rtol: got 0" + rule);
  EXPECT_EQ(refusal(1.0), "--rtol: got 1" + rule);
  EXPECT_EQ(refusal(std::nan("")), "--rtol: got nan" + rule);
}

// One rule: the command line's floor is the scene reader's.
TEST(TimeSteps, TheFloorIsTheScenesTimeRtolFloor) {
  EXPECT_NO_THROW(parse_scene("[time]\nrtol = 1e-12\n", "floor.toml"));
  EXPECT_THROW(parse_scene("[time]\nrtol = 9.9e-13\n", "floor.toml"), SceneError);
  EXPECT_NO_THROW(check_rtol("--rtols", 1e-12));
  EXPECT_THROW(check_rtol("--rtols", 9.9e-13), std::invalid_argument);
}

}  // namespace
}  // namespace wl
