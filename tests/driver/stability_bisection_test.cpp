// The stability bisection on synthetic probes (driver/stability_bisection.h).
#include <gtest/gtest.h>

#include <cmath>

#include "driver/stability_bisection.h"

namespace wl {
namespace {

StabilityProbe synthetic(double dt, double threshold) {
  StabilityProbe p;
  p.bounded = dt < threshold;
  if (!p.bounded) p.result = {Outcome::diverged, "runaway state"};
  return p;
}

TEST(StabilityBisection, BracketsTheThresholdOfAMonotonePredicate) {
  const double threshold = 3.7e-4;
  const StabilityLimit lim = find_stability_limit([&](double dt) { return synthetic(dt, threshold); }, 1e-6, 1e-2, 8);
  ASSERT_TRUE(std::isfinite(lim.largest_stable_dt));
  ASSERT_TRUE(std::isfinite(lim.smallest_unstable_dt));
  EXPECT_LT(lim.largest_stable_dt, threshold);
  EXPECT_GE(lim.smallest_unstable_dt, threshold);
  // 8 bisections of a factor 1e4 in log space leave a factor 1e4^(1/256).
  EXPECT_NEAR(std::log(lim.smallest_unstable_dt / lim.largest_stable_dt), std::log(1e4) / 256, 1e-9);
  EXPECT_EQ(lim.probes.size(), 9u);  // dt_max + 8 midpoints
  EXPECT_EQ(lim.failure.result.outcome, Outcome::diverged);
}

TEST(StabilityBisection, AlwaysBoundedStopsAtDtMax) {
  const StabilityLimit lim = find_stability_limit([](double dt) { return synthetic(dt, 1.0); }, 1e-6, 1e-2, 8);
  EXPECT_EQ(lim.largest_stable_dt, 1e-2);
  EXPECT_TRUE(std::isnan(lim.smallest_unstable_dt));
  EXPECT_EQ(lim.probes.size(), 1u);
}

TEST(StabilityBisection, NeverBoundedEndsAtDtMin) {
  const StabilityLimit lim = find_stability_limit([](double dt) { return synthetic(dt, 1e-9); }, 1e-6, 1e-2, 8);
  EXPECT_TRUE(std::isnan(lim.largest_stable_dt));
  EXPECT_EQ(lim.smallest_unstable_dt, 1e-6);
  EXPECT_EQ(lim.probes.size(), 10u);  // dt_max, 8 midpoints, dt_min
}

TEST(StabilityBisection, BadBoundsAreRejected) {
  auto p = [](double dt) { return synthetic(dt, 1.0); };
  EXPECT_THROW(find_stability_limit(p, 0.0, 1e-2, 8), std::invalid_argument);
  EXPECT_THROW(find_stability_limit(p, 1e-2, 1e-3, 8), std::invalid_argument);
}

}  // namespace
}  // namespace wl
