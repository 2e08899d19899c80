#include "output/metrics_csv.h"

#include <gtest/gtest.h>

#include "tests/output/output_test_util.h"

namespace wl {
namespace {

TEST(MetricsCsv, WritesHeaderAndFullPrecisionRows) {
  test::ScratchDir dir;
  const auto path = dir / "metrics.csv";
  MetricsCsv csv(path, {"time_s", "kinetic_J"});
  csv.row({0.0, 1.0 / 3.0});
  csv.row({0.1, 1e23});
  EXPECT_EQ(csv.rows(), 2);
  EXPECT_FALSE(std::filesystem::exists(path));
  EXPECT_EQ(test::read_text(dir / "metrics.csv.part"),
            "time_s,kinetic_J\n0,0.33333333333333331\n0.10000000000000001,9.9999999999999992e+22\n");
  csv.commit();
  EXPECT_EQ(test::read_text(path),
            "time_s,kinetic_J\n0,0.33333333333333331\n0.10000000000000001,9.9999999999999992e+22\n");
  EXPECT_EQ(test::count_entries(dir.path()), 1);
}

TEST(MetricsCsv, InterruptedRunLeavesOnlyPartFile) {
  test::ScratchDir dir;
  {
    MetricsCsv csv(dir / "metrics.csv", {"a"});
    csv.row({1.0});
  }
  EXPECT_FALSE(std::filesystem::exists(dir / "metrics.csv"));
  EXPECT_EQ(test::read_text(dir / "metrics.csv.part"), "a\n1\n");
}

TEST(MetricsCsv, RejectsWrongRowLengthAndBadColumns) {
  test::ScratchDir dir;
  MetricsCsv csv(dir / "m.csv", {"a", "b"});
  EXPECT_THROW(csv.row({1.0}), std::invalid_argument);
  EXPECT_THROW(csv.row({1.0, 2.0, 3.0}), std::invalid_argument);
  EXPECT_THROW(MetricsCsv(dir / "n.csv", {"a,b"}), std::invalid_argument);
  EXPECT_THROW(MetricsCsv(dir / "n.csv", {}), std::invalid_argument);
  EXPECT_FALSE(std::filesystem::exists(dir / "n.csv.part"));  // nothing created for bad columns
}

}  // namespace
}  // namespace wl
