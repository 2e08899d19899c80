// `weavelab fit` on a target folder no run writes: a non-finite coordinate, a
// point count beyond the file, a frame that is a device, times out of order.
// Each is exit 2 naming where, before anything runs, with nothing written.
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <sstream>
#include <vector>

#include "tests/output/output_test_util.h"
#include "tests/support/test_scenes.h"

namespace wl {
namespace {

namespace fs = std::filesystem;

class FitTargetCli : public ::testing::Test {
 protected:
  void SetUp() override {
    scene_ = dir_ / "small.toml";
    std::ofstream(scene_) << test::hanging_cloth_toml(5, 0.02, "be-newton");
    const auto r =
        cli("run " + test::shell_quote(scene_.string()) + " --quiet --out " + test::shell_quote(target().string()));
    ASSERT_EQ(r.exit_code, 0) << r.output;
    for (const auto& e : fs::directory_iterator(target() / "frames"))
      if (e.path().extension() == ".vtu") frames_.push_back(e.path());
    std::sort(frames_.begin(), frames_.end());
    ASSERT_EQ(frames_.size(), 3u);  // t = 0, 0.01, 0.02 s
  }
  static test::CommandResult cli(const std::string& args) {
    return test::run_command(std::string(WEAVELAB_CLI) + " " + args);
  }
  fs::path target() const { return dir_ / "target"; }
  // Replaces the first `from` in `file` by `to`.
  static void edit(const fs::path& file, const std::string& from, const std::string& to) {
    std::string text = test::read_text(file);
    const size_t at = text.find(from);
    ASSERT_NE(at, std::string::npos) << from;
    text.replace(at, from.size(), to);
    std::ofstream(file, std::ios::binary | std::ios::trunc) << text;
  }
  // The fit refuses the target with exit 2, its message holding `says`, writing nothing.
  void refused(const std::string& says) {
    const fs::path out = dir_ / "never";
    const auto r =
        cli("fit " + test::shell_quote(scene_.string()) + " --target " + test::shell_quote(target().string()) +
            " --free contact.shear_modulus_Pa --quiet --out " + test::shell_quote(out.string()));
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find(says), std::string::npos) << says << "\n" << r.output;
    EXPECT_EQ(r.output.find("Ceres"), std::string::npos) << r.output;  // refused before the solver ran
    EXPECT_FALSE(fs::exists(out));
  }
  test::ScratchDir dir_;
  fs::path scene_;
  std::vector<fs::path> frames_;
};

TEST_F(FitTargetCli, ANonFiniteCoordinateIsRefusedNamingFileFrameAndPoint) {
  const std::string points = "Name=\"Points\" NumberOfComponents=\"3\" format=\"ascii\">\n          ";
  const std::string text = test::read_text(frames_[1]);
  const size_t first = text.find(points) + points.size();
  const std::string x = text.substr(first, text.find(' ', first) - first);
  edit(frames_[1], points + x, points + "nan");
  refused(frames_[1].string() + ":");
  refused(": frame 1 (t = 0.01 s), point 0: array 'Points' coordinate x: got nan, expected a finite number");
}

TEST_F(FitTargetCli, APointCountBeyondWhatTheFileHoldsIsRefused) {
  edit(frames_[1], "NumberOfPoints=\"25\"", "NumberOfPoints=\"2000000000\"");
  refused(frames_[1].string() + ":");
  refused("NumberOfPoints '2000000000', expected an integer from 1 to ");
  edit(frames_[1], "NumberOfPoints=\"2000000000\"", "NumberOfPoints=\"9223372036854775807\"");
  refused("NumberOfPoints '9223372036854775807'");
}

TEST_F(FitTargetCli, AFrameThatIsADeviceIsRefused) {
  edit(target() / "run.pvd", frames_[1].lexically_relative(target()).string(), "/dev/zero");
  refused("/dev/zero: not a regular file");
}

TEST_F(FitTargetCli, TimesOutOfOrderAreRefused) {
  edit(target() / "run.pvd", "timestep=\"0.01\"", "timestep=\"0.03\"");
  refused((target() / "run.pvd").string() +
          ":6: timestep 0.02, expected a finite time after the previous frame's (0.03 s)");
}

}  // namespace
}  // namespace wl
