// `weavelab modes` end to end: a small scene writes every file and the chart;
// bad input is exit 2 with the option named and nothing written.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "tests/output/output_test_util.h"
#include "tests/support/test_scenes.h"

namespace {

namespace fs = std::filesystem;
using Result = wl::test::CommandResult;

class ModesCli : public ::testing::Test {
 protected:
  void SetUp() override { std::ofstream(scene()) << wl::test::hanging_cloth_toml(5, 0.03); }
  fs::path scene() const { return dir_ / "tiny.toml"; }
  fs::path out() const { return dir_ / "out"; }
  Result modes(const std::string& options) {
    return wl::test::run_command(std::string(WEAVELAB_CLI) + " modes '" + scene().string() + "' --quiet --out '" +
                                 out().string() + "' " + options);
  }
  wl::test::ScratchDir dir_;
};

TEST_F(ModesCli, WritesTheFilesAndTheChart) {
  const Result r = modes("--count 4");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("weavelab: modes: equilibria "), std::string::npos) << r.output;
  for (const char* f : {"modes.csv", "mac.csv", "modes_yarn.vtu", "modes_fem.vtu", "modes.json"})
    EXPECT_TRUE(fs::exists(out() / f)) << f;
  std::ifstream vtu(out() / "modes_yarn.vtu");
  const std::string text((std::istreambuf_iterator<char>(vtu)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find("\"mode_03\""), std::string::npos);
  EXPECT_NE(text.find("\"mode_03_slide\""), std::string::npos);
  const Result plot =
      wl::test::run_command(std::string(wl::test::python()) + " '" + WEAVELAB_SOURCE_DIR +
                            "/experiments/diagnosis/scripts/plot_modes.py' '" + out().string() + "' --shapes 2");
  EXPECT_EQ(plot.exit_code, 0) << plot.output;
  EXPECT_GT(fs::file_size(out() / "modes.png"), 1000u);
  EXPECT_GT(fs::file_size(out() / "modes_shapes.png"), 1000u);
}

TEST_F(ModesCli, BadInputIsExit2AndWritesNothing) {
  const struct {
    std::string args, says;
  } cases[] = {
      {"--count 0", "--count: got 0"},
      {"--count 1000", "--count: got 1000"},
      {"--count many", "--count"},
      {"--fem-params '" + (dir_ / "absent.toml").string() + "'", "absent.toml"},
  };
  for (const auto& c : cases) {
    const Result r = modes(c.args);
    EXPECT_EQ(r.exit_code, 2) << c.args << "\n" << r.output;
    EXPECT_NE(r.output.find(c.says), std::string::npos) << c.args << "\n" << r.output;
    EXPECT_FALSE(fs::exists(out())) << c.args;
  }
}

}  // namespace
