// `weavelab diagnose` end to end: a small scene writes every file and the
// chart; bad input is exit 2 with the option named and nothing written.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "tests/output/output_test_util.h"
#include "tests/support/test_scenes.h"

namespace {

namespace fs = std::filesystem;
using Result = wl::test::CommandResult;

class DiagnoseCli : public ::testing::Test {
 protected:
  void SetUp() override { std::ofstream(scene()) << wl::test::hanging_cloth_toml(5, 0.03); }
  fs::path scene() const { return dir_ / "tiny.toml"; }
  fs::path out() const { return dir_ / "out"; }
  Result diagnose(const std::string& options) {
    return wl::test::run_command(std::string(WEAVELAB_CLI) + " diagnose '" + scene().string() + "' --quiet --out '" +
                                 out().string() + "' " + options);
  }
  wl::test::ScratchDir dir_;
};

TEST_F(DiagnoseCli, WritesTheFilesAndTheChart) {
  const Result r = diagnose("");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("weavelab: diagnose: distance "), std::string::npos) << r.output;
  for (const char* f :
       {"energies.csv", "energy_directions.csv", "distance.csv", "rows.csv", "distance.pvd", "diagnosis.json"})
    EXPECT_TRUE(fs::exists(out() / f)) << f;
  const Result plot =
      wl::test::run_command(std::string(wl::test::python()) + " '" + WEAVELAB_SOURCE_DIR +
                            "/experiments/diagnosis/scripts/plot_diagnosis.py' '" + out().string() + "'");
  EXPECT_EQ(plot.exit_code, 0) << plot.output;
  EXPECT_GT(fs::file_size(out() / "diagnosis.png"), 1000u);
}

TEST_F(DiagnoseCli, BadInputIsExit2AndWritesNothing) {
  const struct {
    std::string args, says;
  } cases[] = {
      {"--time-steps fine", "--time-steps: got 'fine'"},
      {"--rtol -1", "--rtol"},
      {"--rtol 1e-13", "--rtol: got 1e-13, expected a tolerance ≥ 1e-12"},  // the floor of time.rtol
      {"--duration -0.1", "--duration"},
      {"--fem-params '" + (dir_ / "absent.toml").string() + "'", "absent.toml"},
  };
  for (const auto& c : cases) {
    const Result r = diagnose(c.args);
    EXPECT_EQ(r.exit_code, 2) << c.args << "\n" << r.output;
    EXPECT_NE(r.output.find(c.says), std::string::npos) << c.args << "\n" << r.output;
    EXPECT_FALSE(fs::exists(out())) << c.args;
  }
}

}  // namespace
