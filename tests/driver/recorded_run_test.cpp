// The output times of a recorded run (driver/recorded_run.h).
#include <gtest/gtest.h>

#include "driver/recorded_run.h"

namespace wl {
namespace {

TEST(OutputTimes, MultiplesOfTheIntervalUpToTheDuration) {
  Scene s;
  s.duration_s = 0.01;
  s.output_interval_s = 0.004;
  const auto t = output_times(s);
  ASSERT_EQ(t.size(), 3u);
  EXPECT_DOUBLE_EQ(t[0], 0.004);
  EXPECT_DOUBLE_EQ(t[1], 0.008);
  EXPECT_DOUBLE_EQ(t[2], 0.01);
}

}  // namespace
}  // namespace wl
