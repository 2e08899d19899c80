// `weavelab fit` end to end: a run of a small scene fitted back from a wrong
// start, and bad input rejected with exit 2 and nothing written.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "tests/output/output_test_util.h"
#include "tests/support/test_scenes.h"

namespace wl {
namespace {

namespace fs = std::filesystem;

class FitCli : public ::testing::Test {
 protected:
  void SetUp() override {
    scene_ = dir_ / "small.toml";
    std::ofstream(scene_) << test::hanging_cloth_toml(5, 0.02, "be-newton");
    const auto r = cli("run " + test::shell_quote(scene_.string()) + " --error-estimate --quiet --out " +
                       test::shell_quote(target().string()));
    ASSERT_EQ(r.exit_code, 0) << r.output;
  }
  static test::CommandResult cli(const std::string& args) {
    return test::run_command(std::string(WEAVELAB_CLI) + " " + args);
  }
  fs::path target() const { return dir_ / "target"; }
  test::CommandResult fit(const std::string& args, const fs::path& out) {
    return cli("fit " + test::shell_quote(scene_.string()) + " --target " + test::shell_quote(target().string()) +
               " --quiet --out " + test::shell_quote(out.string()) + " " + args);
  }
  test::ScratchDir dir_;
  fs::path scene_;
};

// Through a growing window: the first frame, then both.
TEST_F(FitCli, RecoversTheShearModulusOfItsOwnRun) {
  const fs::path out = dir_ / "fit";
  const auto r = fit("--free contact.shear_modulus_Pa --start contact.shear_modulus_Pa=1500 --growing-window 1,2", out);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  for (const char* file : {"fit.json", "convergence.csv", "frames.csv"}) EXPECT_TRUE(fs::exists(out / file)) << file;
  std::stringstream json;
  json << std::ifstream(out / "fit.json").rdbuf();
  for (const char* field : {"\"parameters\"", "\"key\": \"contact.shear_modulus_Pa\"", "\"start\": 1500",
                            "\"std_error\"", "\"correlation\"", "\"simulations\"", "\"cpu_s\"", "\"git_revision\"",
                            "\"fitted_time_error\"", "\"method\": \"richardson\"", "\"target_time_error_mean_rms_m\": ",
                            // the fit recovers the target's own parameters: the distance is far below either time error
                            "\"verdict\": \"time error exceeds the distance\"",
                            // the stages, each with its frames
                            "\"stages\": [", "\"frames\": 1,", "\"frames\": 2,"})
    EXPECT_NE(json.str().find(field), std::string::npos) << field << "\n" << json.str();
  std::stringstream conv;
  conv << std::ifstream(out / "convergence.csv").rdbuf();
  EXPECT_EQ(conv.str().rfind("stage,frames,iteration,cost,rms_m\n1,1,0,", 0), 0u) << conv.str();
  EXPECT_NE(conv.str().find("\n2,2,0,"), std::string::npos) << conv.str();
  EXPECT_NE(r.output.find("contact.shear_modulus_Pa = 1000"), std::string::npos) << r.output;  // the scene default
}

// With --time-steps controlled both the target and the fitted runs are sdirk2
// under error control, with other steps than each other: the fit finds the
// shear modulus again to within what that tolerance allows.
TEST_F(FitCli, RecoversTheShearModulusWithControlledTimeSteps) {
  const fs::path target = dir_ / "controlled_target";
  const auto run = cli("run " + test::shell_quote(scene_.string()) + " --integrator sdirk2 --rtol 1e-6 --quiet --out " +
                       test::shell_quote(target.string()));
  ASSERT_EQ(run.exit_code, 0) << run.output;
  const fs::path out = dir_ / "controlled_fit";
  const auto r = cli("fit " + test::shell_quote(scene_.string()) + " --target " + test::shell_quote(target.string()) +
                     " --time-steps controlled --rtol 1e-6 --free contact.shear_modulus_Pa"
                     " --start contact.shear_modulus_Pa=1500 --quiet --out " +
                     test::shell_quote(out.string()));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  std::stringstream json;
  json << std::ifstream(out / "fit.json").rdbuf();
  EXPECT_NE(json.str().find("\"resolution\": \"sdirk2 under error control, rtol 1e-06"), std::string::npos)
      << json.str();
  const std::string key = "\"value\": ";
  const size_t at = json.str().find(key, json.str().find("\"key\": \"contact.shear_modulus_Pa\""));
  ASSERT_NE(at, std::string::npos);
  EXPECT_NEAR(std::stod(json.str().substr(at + key.size())), 1000.0, 10.0);  // 1 %, from 50 % off
}

// A start that does not simulate (a yarn a 10^294 times too stiff: the first
// step crosses sliding coordinates) is a numerical outcome, exit 1, with its
// record complete: frames.csv holds NaN where the start reached no frame.
TEST_F(FitCli, AStartThatDoesNotSimulateIsExit1WithACompleteRecord) {
  std::string stiff = test::read_text(fs::path(WEAVELAB_SOURCE_DIR) / "tests/fuzz/inputs/woven.toml");
  const std::string key = "stretch_modulus_Pa = ";
  const size_t at = stiff.find(key);
  ASSERT_NE(at, std::string::npos);
  stiff.replace(at + key.size(), stiff.find('\n', at) - at - key.size(), "1e300");
  const fs::path woven = dir_ / "woven.toml", stiff_scene = dir_ / "stiff.toml";
  std::ofstream(woven) << test::read_text(fs::path(WEAVELAB_SOURCE_DIR) / "tests/fuzz/inputs/woven.toml");
  std::ofstream(stiff_scene) << stiff;
  const auto target_run = cli("run " + test::shell_quote(woven.string()) + " --quiet --out " +
                              test::shell_quote((dir_ / "woven_target").string()));
  ASSERT_EQ(target_run.exit_code, 0) << target_run.output;
  const fs::path out = dir_ / "stiff_fit";
  const auto r = cli("fit " + test::shell_quote(stiff_scene.string()) + " --target " +
                     test::shell_quote((dir_ / "woven_target").string()) +
                     " --free contact.shear_modulus_Pa --frames 1 --max-iterations 1 --quiet --out " +
                     test::shell_quote(out.string()));
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_NE(r.output.find("the start does not simulate"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(out / "frames.csv.part"));
  const std::string frames = test::read_text(out / "frames.csv");
  EXPECT_NE(frames.find("\n"), std::string::npos);
  EXPECT_NE(frames.find(",nan,nan,"), std::string::npos) << frames;
}

TEST_F(FitCli, BadInputIsExit2AndWritesNothing) {
  const fs::path out = dir_ / "never";
  const struct {
    std::string args, says;
  } cases[] = {
      {"--free contact.no_such_key", "unknown parameter key 'contact.no_such_key'"},
      {"--free fem.shear_N_per_m", "does not depend on it"},
      {"--free contact.shear_modulus_Pa --frames 9", "--frames"},
      {"--free contact.shear_modulus_Pa --start contact.shear_modulus_Pa=-3", "--start"},
      {"--free contact.shear_modulus_Pa --start contact.friction_coefficient=0.3", "not among the fitted keys"},
      {"--free contact.shear_modulus_Pa --integrator ida", "offers no parameter sensitivities"},
      {"--free contact.shear_modulus_Pa --model fem", "does not depend on it"},
      {"--free contact.shear_modulus_Pa --time-steps controlled --integrator be-linear", "runs sdirk2"},
      {"--free contact.shear_modulus_Pa --time-steps fine", "--time-steps"},
      {"--free contact.shear_modulus_Pa --time-steps controlled --rtol 1e-13",
       "--rtol: got 1e-13, expected a tolerance ≥ 1e-12"},  // the floor of time.rtol
      {"--free contact.shear_modulus_Pa --start-set contact.shear_modulus_Pa=9e2,contact.friction_coefficient=0.3",
       "not among the fitted keys"},
      {"--free contact.shear_modulus_Pa --start-set contact.shear_modulus_Pa=x", "--start"},
      {"--free contact.shear_modulus_Pa --start-set contact.shear_modulus_Pa=900 --jobs 0", "--jobs"},
      {"--free contact.shear_modulus_Pa --growing-window 1,x", "--growing-window: got 'x'"},
      {"--free contact.shear_modulus_Pa --growing-window 1,1.5", "--growing-window: got '1,1.5'"},
      {"--free contact.shear_modulus_Pa --growing-window 2,2", "--growing-window: got 2,2"},
      {"--free contact.shear_modulus_Pa --growing-window 0,2", "--growing-window: got '0'"},
      {"--free contact.shear_modulus_Pa --growing-window 1,3", "--growing-window: got 1,3"},  // the target has 2
      {"--free contact.shear_modulus_Pa --frames 1 --growing-window 1,2", "--growing-window: got 1,2"},
      {"--free contact.shear_modulus_Pa --start-set contact.shear_modulus_Pa=900 --growing-window 2,1",
       "--growing-window: got 2,1"},
  };
  for (const auto& c : cases) {
    const auto r = fit(c.args, out);
    EXPECT_EQ(r.exit_code, 2) << c.args << "\n" << r.output;
    EXPECT_NE(r.output.find(c.says), std::string::npos) << c.args << "\n" << r.output;
    EXPECT_FALSE(fs::exists(out)) << c.args;
  }
  const auto r =
      cli("fit " + test::shell_quote(scene_.string()) + " --target " + test::shell_quote((dir_ / "nothing").string()) +
          " --free contact.shear_modulus_Pa --out " + test::shell_quote(out.string()));
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("nothing"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(out));
  // Self-contact assembles a bound of its stiffness, not the exact one the sensitivities need.
  const fs::path self = dir_ / "self.toml";
  std::ofstream(self) << test::hanging_cloth_toml(5, 0.02, "be-newton") << "\n[self_contact]\nenabled = true\n";
  const auto s = cli("fit " + test::shell_quote(self.string()) + " --target " + test::shell_quote(target().string()) +
                     " --free contact.shear_modulus_Pa --out " + test::shell_quote(out.string()));
  EXPECT_EQ(s.exit_code, 2) << s.output;
  EXPECT_NE(s.output.find("self.toml:"), std::string::npos) << s.output;
  EXPECT_NE(s.output.find("self_contact.enabled: fit"), std::string::npos) << s.output;
  EXPECT_FALSE(fs::exists(out));
}

// A knit hung from two contacts (docs/calibration.md §8.1): the parameters its relaxed rest shape
// depends on are refused, naming the parameter and why, with nothing written; the continuum
// observes the knit at its stitch contacts; the roll stiffness of its own run is found again
// from a start 50 % off.
class KnitFitCli : public FitCli {
 protected:
  void SetUp() override {
    scene_ = dir_ / "knit.toml";
    std::ofstream(scene_) << test::hanging_knit_toml(4, 3);
    const auto r =
        cli("run " + test::shell_quote(scene_.string()) + " --quiet --out " + test::shell_quote(target().string()));
    ASSERT_EQ(r.exit_code, 0) << r.output;
  }
};

TEST_F(KnitFitCli, RefusesWhatShapesTheRestAndObservesTheContactsWithTheContinuum) {
  const fs::path out = dir_ / "never";
  for (const char* key : {"yarn_types.default.stretch_modulus_Pa", "yarn_types.default.bending_modulus_Pa",
                          "knit.stitch_length_stiffness_N", "knit.compression_stiffness_N_per_m"}) {
    const auto r = fit(std::string("--free ") + key, out);
    EXPECT_EQ(r.exit_code, 2) << key << "\n" << r.output;
    EXPECT_NE(r.output.find(std::string("parameter '") + key + "'"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("relaxed rest shape"), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(out)) << key;
  }
  const auto r = fit("--free fem.weft_stretch_N_per_m --model fem", out);  // no calibrated stiffnesses
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("fem.warp_stretch_N_per_m"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(out));
  // With them the continuum observes the yarn-level run at its 2·3·5 stitch contacts (docs/models.md §11.9).
  std::ofstream(dir_ / "params.toml") << "warp_stretch_N_per_m = 40.0\nweft_stretch_N_per_m = 50.0\n"
                                         "shear_N_per_m = 2.0\nwarp_bending_N_m = 1e-6\nweft_bending_N_m = 2e-6\n";
  const fs::path fem = dir_ / "fem";
  const auto c = fit(
      "--free fem.weft_stretch_N_per_m --model fem --fem-params " + test::shell_quote((dir_ / "params.toml").string()),
      fem);
  EXPECT_NE(c.exit_code, 2) << c.output;
  std::stringstream json;
  json << std::ifstream(fem / "fit.json").rdbuf();
  EXPECT_NE(json.str().find("\"observed_points\": 30,"), std::string::npos) << json.str();
}

TEST_F(KnitFitCli, RecoversTheRollStiffnessOfItsOwnRun) {
  const fs::path out = dir_ / "fit";
  const auto r = fit("--free knit.roll_stiffness_N --start knit.roll_stiffness_N=1.5e-5", out);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  std::stringstream json;
  json << std::ifstream(out / "fit.json").rdbuf();
  const std::string key = "\"value\": ";
  const size_t at = json.str().find(key, json.str().find("\"key\": \"knit.roll_stiffness_N\""));
  ASSERT_NE(at, std::string::npos) << json.str();
  EXPECT_NEAR(std::stod(json.str().substr(at + key.size())), 1e-5, 1e-9);
}

}  // namespace
}  // namespace wl
