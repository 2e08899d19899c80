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
#include <tuple>

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

// A loop height below the yarn's diameter: consecutive courses' loop heads,
// side by side C apart, would overlap (docs/models.md §11.2); refused by the
// reader at the key before any subcommand builds the crushed knit.
TEST_F(UpFrontChecks, AKnitLoopHeightBelowTheYarnDiameterIsRefusedAtTheKey) {
  const std::string knit = wl::test::hanging_knit_toml(3, 3);
  const fs::path scene =
      write("squashed.toml", std::string(knit).insert(knit.find("courses = "), "course_spacing_m = 1e-12\n"));
  for (const char* subcommand : {"run", "info", "calibrate"}) {
    const Result r = std::string(subcommand) == "info" ? cli("info " + shell_quote(scene.string()))
                                                       : command(subcommand, scene, out());
    EXPECT_EQ(r.exit_code, 2) << subcommand << "\n" << r.output;
    EXPECT_TRUE(has(r,
                    "squashed.toml:7: key 'cloth.pattern.course_spacing_m': got 1e-12, expected a loop height ≥ "
                    "2·cloth.radius_m (= 0.0004)"))
        << subcommand << "\n"
        << r.output;
    EXPECT_FALSE(fs::exists(out())) << subcommand;
  }
}

// A knit whose keys are each in range but whose periodic rest tile does not
// relax (a stitch-length stiffness 10¹⁰ times the yarn's k_s): only the model
// can tell, and every subcommand that builds it refuses the scene as the
// reader would, located at its [cloth.pattern] with the values the rest
// depends on, exit 2, nothing written.
TEST_F(UpFrontChecks, AKnitWhoseRestTileDoesNotRelaxIsExit2LocatedFromEverySubcommand) {
  std::string text = wl::test::hanging_knit_toml(3, 3);
  text.replace(text.find("sliding = false"), 15, "sliding = true");  // the stitch-length penalty acts on sliding
  text.insert(text.find("roll_stiffness_N"), "stitch_length_stiffness_N = 1e9\n");
  const fs::path scene = write("stiff.toml", text);
  for (const char* subcommand : {"run", "info", "diagnose", "modes", "fidelity", "stability", "work-precision"}) {
    const Result r = std::string(subcommand) == "info" ? cli("info " + shell_quote(scene.string()))
                                                       : command(subcommand, scene, out());
    EXPECT_EQ(r.exit_code, 2) << subcommand << "\n" << r.output;
    EXPECT_TRUE(has(r, "stiff.toml:6: key 'cloth.pattern': got ") && has(r, "knit.stitch_length_stiffness_N = 1e+09") &&
                has(r, "expected a knit whose periodic rest tile relaxes to static equilibrium") &&
                has(r, "did not converge"))
        << subcommand << "\n"
        << r.output;
    EXPECT_FALSE(fs::exists(out())) << subcommand;
  }
}

// A stitch whose rest length is below the resolution of the yarn's arc length
// (a 1e-20 m yarn in 2e-20 m high loops 2 mm wide): the stitch-length term's
// refusal names the scene, its [cloth.pattern] and the stitch, exit 2.
TEST_F(UpFrontChecks, AStitchTermsRefusalIsLocatedInTheScene) {
  std::string text = wl::test::hanging_knit_toml(3, 3);
  text.replace(text.find("sliding = false"), 15, "sliding = true");
  text.replace(text.find("radius_m = 2e-4"), 15, "radius_m = 1e-20");
  text.insert(text.find("courses = "), "course_spacing_m = 2e-20\n");
  const fs::path scene = write("thin.toml", text);
  for (const char* subcommand : {"run", "diagnose"}) {
    const Result r = command(subcommand, scene, out());
    EXPECT_EQ(r.exit_code, 2) << subcommand << "\n" << r.output;
    EXPECT_TRUE(has(r, "thin.toml:6: key 'cloth.pattern': got ") && has(r, "cloth.radius_m = 1e-20") &&
                has(r, "expected a knit whose stitches have a non-degenerate rest state") &&
                has(r, "StitchLengthTerm") && has(r, "at the stitch contact of courses"))
        << subcommand << "\n"
        << r.output;
    EXPECT_FALSE(fs::exists(out())) << subcommand;
  }
}

// The floor of time.rtol holds for work-precision's ladders as for every --rtol
// (check_rtol, driver/time_steps.h): exit 2 before any run, nothing written.
TEST_F(UpFrontChecks, WorkPrecisionTolerancesBelowTheRtolFloorAreExit2) {
  for (const auto& [options, says] :
       {std::pair{"--rtols 1e-4,1e-13", "--rtols: got 1e-13, expected a tolerance ≥ 1e-12"},
        std::pair{"--reference-rtols 1e-13", "--reference-rtols: got 1e-13, expected a tolerance ≥ 1e-12"}}) {
    const Result r = command("work-precision", tiny(), out(), options);
    EXPECT_EQ(r.exit_code, 2) << options << "\n" << r.output;
    EXPECT_TRUE(has(r, says)) << options << "\n" << r.output;
    EXPECT_FALSE(fs::exists(out())) << options;
  }
}
