// The work-precision experiment end to end on a 5×5 cloth (driver/work_precision.h).
#include <gtest/gtest.h>

#include <filesystem>

#include "driver/work_precision.h"
#include "tests/driver/driver_test_data.h"
#include "tests/output/output_test_util.h"

namespace wl {
namespace {

using test::read_csv;
using test::ScratchDir;

TEST(WorkPrecisionSweep, TinySceneTwoIntegratorsEndToEnd) {
  ScratchDir dir;
  WorkPrecisionConfig c;
  test::use_tiny_scene(c);
  c.models = {"fem"};
  c.integrators = {"be-linear", "ida"};
  c.rtols = {1e-4, 1e-6};
  c.dt_max = 2e-3;
  c.dt_min = 5e-4;
  c.reference.cache_dir = dir / "reference";
  c.reference.rtols = {1e-9};
  c.reference.progress = false;
  c.out_dir = dir / "wp";
  c.progress = false;
  const WorkPrecisionResult r = run_work_precision(c);
  ASSERT_EQ(r.rows.size(), 5u);  // dt 2, 1, 0.5 ms; rtol 1e-4, 1e-6
  for (const auto& row : r.rows) {
    ASSERT_EQ(row.run.result.outcome, Outcome::ok) << row.integrator << ": " << row.run.result.message;
    EXPECT_GT(row.error.rms, 0.0);
    EXPECT_GE(row.error.max, row.error.rms);
    EXPECT_GT(row.run.cpu_s, 0.0);
  }
  // Backward Euler is first order: halving dt roughly halves the error.
  for (int k = 0; k < 2; ++k) {
    const double ratio = r.rows[k].error.rms / r.rows[k + 1].error.rms;
    EXPECT_GT(ratio, 1.6) << "dt " << r.rows[k].dt;
    EXPECT_LT(ratio, 2.5) << "dt " << r.rows[k].dt;
  }
  // IDA at rtol 1e-6 is far more accurate than backward Euler at 0.5 ms and
  // at least as accurate as at rtol 1e-4.
  EXPECT_LT(r.rows[4].error.rms, 1e-2 * r.rows[2].error.rms);
  EXPECT_LE(r.rows[4].error.rms, r.rows[3].error.rms);
  ASSERT_TRUE(r.references.count("fem"));
  EXPECT_EQ(r.references.at("fem").rtol, 1e-9);

  const auto csv = read_csv(c.out_dir / "work_precision.csv");
  ASSERT_EQ(csv.size(), 6u);
  EXPECT_EQ(csv[0], kWorkPrecisionColumns);
  EXPECT_EQ(csv[1][1], "be-linear");
  EXPECT_EQ(csv[5][1], "ida");
  const std::string json = test::read_text(c.out_dir / "work_precision.json");
  for (const char* key : {"\"git_revision\"", "\"machine\"", "\"text\"", "\"references\"", "\"rtols\""})
    EXPECT_NE(json.find(key), std::string::npos) << key;
  EXPECT_NE(json.find(r.references.at("fem").hash), std::string::npos);

  // The chart script reads these files.
  ASSERT_TRUE(test::python_with("numpy, matplotlib"));
  const auto out = test::run_chart_script("experiments/work_precision/scripts/plot_work_precision.py", c.out_dir);
  ASSERT_EQ(out.exit_code, 0) << out.output;
  EXPECT_TRUE(std::filesystem::exists(c.out_dir / "work_precision.png"));
  EXPECT_TRUE(std::filesystem::exists(c.out_dir / "work_precision.svg"));
  EXPECT_NE(test::read_text(c.out_dir / "slopes.csv").find("fem,be-linear,fixed,3,"), std::string::npos);
}

}  // namespace
}  // namespace wl
