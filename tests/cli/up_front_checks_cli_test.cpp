// Input every subcommand checks before any work, as `run` does: a knit
// without [fem] stiffnesses, an --out naming a file, adaptive steps asked of
// an integrator without error control, a cloth too large for memory, a node
// starting inside an obstacle. Each is exit 2 with a message naming it and
// nothing written; and the messages of refusals and fallbacks say what is so.
#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "driver/memory_estimate.h"
#include "models/scene/scene.h"
#include "tests/output/output_test_util.h"
#include "tests/support/test_scenes.h"

namespace {

namespace fs = std::filesystem;
using Result = wl::test::CommandResult;
using wl::test::shell_quote;

class UpFrontChecks : public ::testing::Test {
 protected:
  void SetUp() override { std::ofstream(tiny()) << wl::test::hanging_cloth_toml(5, 0.02, "be-newton"); }
  fs::path tiny() const { return dir_ / "tiny.toml"; }
  fs::path out() const { return dir_ / "out"; }
  fs::path write(const std::string& name, const std::string& text) const {
    std::ofstream(dir_ / name) << text;
    return dir_ / name;
  }
  static Result cli(const std::string& args) { return wl::test::run_command(std::string(WEAVELAB_CLI) + " " + args); }
  // `subcommand` on `scene` with --quiet (`pull` has none) and --out `out`, then `options`.
  static Result command(const std::string& subcommand, const fs::path& scene, const fs::path& out,
                        const std::string& options = "") {
    return cli(subcommand + " " + shell_quote(scene.string()) + (subcommand == "pull" ? "" : " --quiet") + " --out " +
               shell_quote(out.string()) + " " + options);
  }
  static bool has(const Result& r, const std::string& text) { return r.output.find(text) != std::string::npos; }
  wl::test::ScratchDir dir_;
};

std::string text_of(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// A knit's continuum takes its stiffnesses from a calibration (docs/models.md
// §11.9): without them, diagnose and modes refuse it as `run --model fem` does.
TEST_F(UpFrontChecks, AKnitWithoutFemStiffnessesIsExit2ForEveryComparison) {
  const fs::path knit = write("knit.toml", wl::test::hanging_knit_toml(4, 3));
  const Result run = command("run", knit, out(), "--model fem");
  ASSERT_EQ(run.exit_code, 2) << run.output;
  ASSERT_TRUE(has(run, "a calibrated value > 0")) << run.output;
  EXPECT_FALSE(fs::exists(out()));
  for (const char* subcommand : {"diagnose", "modes"}) {
    const Result r = command(subcommand, knit, out());
    EXPECT_EQ(r.exit_code, 2) << subcommand << "\n" << r.output;
    EXPECT_TRUE(has(r, "knit.toml:")) << subcommand << "\n" << r.output;
    EXPECT_TRUE(has(r, "a calibrated value > 0")) << subcommand << "\n" << r.output;
    EXPECT_FALSE(fs::exists(out())) << subcommand;
  }
}

// An --out that names an existing file is refused before any work by every
// subcommand that writes a folder, and the file is left as it was.
TEST_F(UpFrontChecks, AnOutNamingAFileIsExit2BeforeAnyWork) {
  const fs::path target = dir_ / "target";
  const Result made = command("run", tiny(), target);
  ASSERT_EQ(made.exit_code, 0) << made.output;
  const fs::path taken = write("taken", "not a folder\n");
  const std::string target_option = "--target " + shell_quote(target.string());
  const struct {
    std::string subcommand, options;
  } cases[] = {
      {"run", ""},
      {"diagnose", ""},
      {"modes", ""},
      {"fidelity", ""},
      {"calibrate", "--tests shear"},
      {"fit", target_option + " --free contact.shear_modulus_Pa"},
      {"pull", ""},
      {"work-precision", ""},
      {"stability", ""},
  };
  for (const auto& c : cases) {
    const auto start = std::chrono::steady_clock::now();
    const Result r = command(c.subcommand, tiny(), taken, c.options);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    EXPECT_EQ(r.exit_code, 2) << c.subcommand << "\n" << r.output;
    EXPECT_TRUE(has(r, "'--out'") && has(r, taken.string()) && has(r, "existing file")) << c.subcommand << "\n"
                                                                                        << r.output;
    EXPECT_LT(seconds, 5.0) << c.subcommand << ": refused only after the work";
    EXPECT_EQ(text_of(taken), "not a folder\n") << c.subcommand;
  }
}

// be-linear has no error control (IntegratorCapabilities::controls_error):
// --rtol or --adaptive would run its fixed steps while the record said adaptive.
TEST_F(UpFrontChecks, AdaptiveStepsOfAnIntegratorWithoutErrorControlAreExit2) {
  for (const std::string options : {"--integrator be-linear --rtol 1e-3", "--integrator be-linear --adaptive"}) {
    const Result r = command("run", tiny(), out(), options);
    EXPECT_EQ(r.exit_code, 2) << options << "\n" << r.output;
    EXPECT_TRUE(has(r, options.find("rtol") != std::string::npos ? "'--rtol'" : "'--adaptive'")) << options << "\n"
                                                                                                 << r.output;
    EXPECT_TRUE(has(r, "be-linear has none")) << options << "\n" << r.output;
    EXPECT_TRUE(has(r, "sdirk2")) << options << "\n" << r.output;  // one that has it
    EXPECT_FALSE(fs::exists(out())) << options;
  }
  const Result controlled = command("run", tiny(), out(), "--integrator sdirk2 --rtol 1e-3");
  EXPECT_EQ(controlled.exit_code, 0) << controlled.output;
}

// The same asked by the scene file ([time] adaptive = true under be-linear): refused at
// the key's line by run and by fit (whose simulations would run fixed steps too).
TEST_F(UpFrontChecks, SceneAdaptiveStepsWithoutErrorControlAreExit2Located) {
  const fs::path target = dir_ / "target";
  ASSERT_EQ(command("run", tiny(), target).exit_code, 0);
  const fs::path adaptive =
      write("adaptive.toml", wl::test::hanging_cloth_toml(5, 0.02, "be-linear") + "adaptive = true\n");
  const std::string fit_options = "--target " + shell_quote(target.string()) + " --free contact.shear_modulus_Pa";
  for (const auto& [subcommand, options] : {std::pair{"run", ""}, std::pair{"fit", fit_options.c_str()}}) {
    const Result r = command(subcommand, adaptive, out(), options);
    EXPECT_EQ(r.exit_code, 2) << subcommand << "\n" << r.output;
    EXPECT_TRUE(has(r, "adaptive.toml:") && has(r, "time.adaptive") && has(r, "be-linear")) << subcommand << "\n"
                                                                                            << r.output;
    EXPECT_FALSE(fs::exists(out())) << subcommand;
  }
  // fit's own bad values, each named and refused before anything is written.
  for (const std::string options : {"--frames 0", "--bound-factor 1", "--growing-window 1,1", "--growing-window of"}) {
    const Result r = command("fit", tiny(), out(), fit_options + " " + options);
    EXPECT_EQ(r.exit_code, 2) << options << "\n" << r.output;
    EXPECT_TRUE(has(r, options.substr(0, options.find(' ')) + ": got")) << options << "\n" << r.output;
    EXPECT_FALSE(fs::exists(out())) << options;
  }
}

// A cloth that cannot fit in memory: every comparison refuses it at once, as
// run does, with the estimate, instead of allocating until std::bad_alloc.
TEST_F(UpFrontChecks, AClothTooLargeForMemoryIsExit2AtOnce) {
  const fs::path huge = write("huge.toml", "[cloth]\nwarps = 16384\nwefts = 16384\n");
  for (const char* subcommand : {"run", "diagnose", "modes", "fidelity"}) {
    const auto start = std::chrono::steady_clock::now();
    const Result r = command(subcommand, huge, out());
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    EXPECT_EQ(r.exit_code, 2) << subcommand << "\n" << r.output;
    EXPECT_TRUE(has(r, "huge.toml:") && has(r, "cloth.warps") && has(r, "fits in memory")) << subcommand << "\n"
                                                                                           << r.output;
    EXPECT_LT(seconds, 5.0) << subcommand;
    EXPECT_FALSE(fs::exists(out())) << subcommand;
  }
  const Result r = command("calibrate", tiny(), out(), "--patch 100000");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_TRUE(has(r, "'--patch': got 100000") && has(r, "fits in memory")) << r.output;
  EXPECT_FALSE(fs::exists(out()));
}

// The largest knit the scene format takes (256 × 256 loops, about 1.3 million
// DoFs): sized by its own loops, not by the woven cloth's default warps.
TEST_F(UpFrontChecks, AKnitTooLargeForMemoryIsExit2AtOnce) {
  const std::string text =
      "[cloth]\nspacing_m = 0.002\nradius_m = 0.0002\n[cloth.pattern]\nkind = \"stockinette\"\ncourses = 256\n"
      "wales = 256\n[time]\nduration_s = 0.01\ndt_s = 0.001\noutput_interval_s = 0.01\n";
  if (wl::estimate_run_memory(wl::parse_scene(text, "huge_knit.toml"), "knit").bytes <= wl::available_memory_bytes())
    GTEST_SKIP() << "this machine has the memory for the largest knit";
  const fs::path huge = write("huge_knit.toml", text);
  for (const char* subcommand : {"run", "diagnose", "modes", "fidelity"}) {
    const auto start = std::chrono::steady_clock::now();
    const Result r = command(subcommand, huge, out());
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    EXPECT_EQ(r.exit_code, 2) << subcommand << "\n" << r.output;
    EXPECT_TRUE(has(r, "huge_knit.toml:6: key 'cloth.pattern.courses': got 256 (× 256 wales)") &&
                has(r, "fits in memory"))
        << subcommand << "\n"
        << r.output;
    EXPECT_LT(seconds, 5.0) << subcommand;
    EXPECT_FALSE(fs::exists(out())) << subcommand;
  }
  const fs::path knit = write("knit.toml", wl::test::hanging_knit_toml(4, 4));
  const Result r = command("calibrate", knit, out(), "--patch 100000");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_TRUE(has(r, "'--patch': got 100000") && has(r, "fits in memory")) << r.output;
  EXPECT_FALSE(fs::exists(out()));
}

// A node that starts inside an obstacle: the comparisons check the scene's
// initial state before writing, as run does, and leave no partial file.
TEST_F(UpFrontChecks, ANodeStartingInsideAnObstacleWritesNothing) {
  const std::string flat = "[cloth]\nwarps = 5\nwefts = 5\n[pose]\nkind = \"flat\"\n",
                    time = "[time]\nduration_s = 0.004\noutput_interval_s = 0.002\n";
  const fs::path inside =
      write("inside.toml",
            flat + "[[obstacles]]\nshape = \"sphere\"\ncenter_m = [0.002, 0.002, 0]\nradius_m = 0.0015\n" + time);
  const Result run = command("run", inside, out());
  ASSERT_EQ(run.exit_code, 2) << run.output;
  ASSERT_TRUE(has(run, "inside.toml:6: obstacles[0]")) << run.output;
  const Result diagnose = command("diagnose", inside, out());
  EXPECT_EQ(diagnose.exit_code, 2) << diagnose.output;
  EXPECT_TRUE(has(diagnose, "inside.toml:6: obstacles[0]") && has(diagnose, "starts inside")) << diagnose.output;
  EXPECT_FALSE(fs::exists(out()));
  const fs::path plain = write("flat.toml", flat + time);
  const Result calibrate =
      command("calibrate", plain, out(), "--tests shear --validate " + shell_quote(inside.string()));
  EXPECT_EQ(calibrate.exit_code, 2) << calibrate.output;
  EXPECT_TRUE(has(calibrate, "inside.toml:6: obstacles[0]")) << calibrate.output;
  EXPECT_FALSE(fs::exists(out()));
}

// An integrator that cannot keep a model's admissible states names what the
// scene has: here self-contact, no obstacle.
TEST_F(UpFrontChecks, ARefusedIntegratorNamesTheScenesOwnConstraint) {
  const fs::path self = write("self.toml", text_of(tiny()) + "\n[self_contact]\nenabled = true\n");
  const Result r = command("run", self, out(), "--integrator ida");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_TRUE(has(r, "not offered for a model with admissible states (self-contact)")) << r.output;
  EXPECT_FALSE(has(r, "obstacle")) << r.output;
}

}  // namespace
