// The stability experiment end to end on a 5×5 cloth (driver/stability.h).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "driver/stability.h"
#include "tests/driver/driver_test_data.h"
#include "tests/output/output_test_util.h"

namespace wl {
namespace {

using test::read_csv;
using test::ScratchDir;

TEST(StabilitySweep, TinySceneExplicitLimitBelowImplicit) {
  ScratchDir dir;
  StabilityConfig c;
  test::use_tiny_scene(c);
  c.models = {"fem"};
  c.integrators = {"be-linear", "symplectic"};
  c.multipliers = {1.0};
  c.dt_min = 1e-6;
  c.dt_max = 1e-3;
  c.bisections = 4;
  c.out_dir = dir / "st";
  c.progress = false;
  const StabilityResult r = run_stability(c);
  ASSERT_EQ(r.rows.size(), 2u);
  const StabilityLimit& be = r.rows[0].limit;
  const StabilityLimit& se = r.rows[1].limit;
  EXPECT_EQ(be.largest_stable_dt, 1e-3);  // backward Euler: bounded at the largest step
  ASSERT_TRUE(std::isfinite(se.smallest_unstable_dt));
  EXPECT_LT(se.smallest_unstable_dt, 1e-3);  // symplectic Euler has a step limit
  EXPECT_FALSE(se.failure.bounded);
  const auto csv = read_csv(c.out_dir / "stability.csv");
  ASSERT_EQ(csv.size(), 3u);
  EXPECT_EQ(csv[2][1], "symplectic");
  EXPECT_EQ(csv[2][5], "runaway");  // failure_mode, from StepResult::cause
  EXPECT_TRUE(std::filesystem::exists(c.out_dir / "stability_probes.csv"));
  const std::string json = test::read_text(c.out_dir / "stability.json");
  EXPECT_NE(json.find("\"git_revision\""), std::string::npos);
  EXPECT_NE(json.find("\"speed_bound_m_per_s\""), std::string::npos);

  ASSERT_TRUE(test::python_with("numpy, matplotlib"));
  const auto out = test::run_chart_script("experiments/stability/scripts/plot_stability.py", c.out_dir);
  ASSERT_EQ(out.exit_code, 0) << out.output;
  EXPECT_TRUE(std::filesystem::exists(c.out_dir / "stability.png"));
  EXPECT_TRUE(std::filesystem::exists(c.out_dir / "stability.svg"));
}

}  // namespace
}  // namespace wl
