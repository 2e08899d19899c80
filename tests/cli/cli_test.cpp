// The command line on bad input: a clear message, exit code 2 and nothing written.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <sys/wait.h>

namespace {

namespace fs = std::filesystem;

struct Result {
  int code;
  std::string output;
};

Result run_cli(const std::string& args, const fs::path& dir) {
  const fs::path log = dir / "cli.log";
  const std::string cmd = std::string(WEAVELAB_CLI) + " " + args + " > '" + log.string() + "' 2>&1";
  const int status = std::system(cmd.c_str());
  std::ifstream in(log);
  std::stringstream ss;
  ss << in.rdbuf();
  fs::remove(log);
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, ss.str()};
}

class Cli : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("weavelab_cli_" + std::to_string(::getpid()) + "_" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path write_scene(const std::string& text) {
    const fs::path p = dir_ / "bad.toml";
    std::ofstream(p) << text;
    return p;
  }
  // Runs `run` on a bad scene: expects exit 2, the given fragments in the message, no output folder.
  void expect_rejected(const std::string& scene_text, std::vector<std::string> fragments) {
    const fs::path scene = write_scene(scene_text);
    const fs::path out = dir_ / "out";
    Result r = run_cli("run '" + scene.string() + "' --out '" + out.string() + "'", dir_);
    EXPECT_EQ(r.code, 2) << r.output;
    for (const auto& f : fragments) EXPECT_NE(r.output.find(f), std::string::npos) << "missing '" << f << "' in: " << r.output;
    EXPECT_FALSE(fs::exists(out)) << "output written for a bad scene";
  }
  fs::path dir_;
};

TEST_F(Cli, SyntaxErrorIsRejected) { expect_rejected("[cloth\nwarps = 3\n", {"bad.toml:", "syntax"}); }

TEST_F(Cli, UnknownKeyIsRejected) {
  expect_rejected("[cloth]\nwarps = 5\nradius_mm = 0.5\n", {"bad.toml:3", "cloth.radius_mm"});
}

TEST_F(Cli, WrongTypeIsRejected) { expect_rejected("[cloth]\nwarps = \"many\"\n", {"bad.toml:2", "cloth.warps"}); }

TEST_F(Cli, NegativeRadiusIsRejected) {
  expect_rejected("[cloth]\nradius_m = -0.5\n", {"bad.toml:2", "cloth.radius_m", "-0.5"});
}

TEST_F(Cli, MissingFileIsRejected) {
  const fs::path out = dir_ / "out";
  Result r = run_cli("run '" + (dir_ / "nope.toml").string() + "' --out '" + out.string() + "'", dir_);
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_NE(r.output.find("nope.toml"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(out));
}

TEST_F(Cli, UnknownIntegratorIsRejected) {
  const fs::path out = dir_ / "out";
  Result r = run_cli(std::string("run '") + WEAVELAB_SOURCE_DIR + "/experiments/scenes/hanging_wind.toml' --integrator rk99 --out '" +
                         out.string() + "'",
                     dir_);
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_NE(r.output.find("rk99"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(out));
}

TEST_F(Cli, InfoReportsDofs) {
  Result r = run_cli(std::string("info '") + WEAVELAB_SOURCE_DIR + "/experiments/scenes/hanging_wind.toml'", dir_);
  EXPECT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("dofs: 1317"), std::string::npos) << r.output;
}

TEST_F(Cli, ShortRunWritesFramesMetricsAndSummary) {
  const fs::path out = dir_ / "out";
  Result r = run_cli(std::string("run '") + WEAVELAB_SOURCE_DIR +
                         "/experiments/scenes/hanging_wind.toml' --duration 0.02 --quiet --out '" + out.string() + "'",
                     dir_);
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_TRUE(fs::exists(out / "run.pvd"));
  EXPECT_TRUE(fs::exists(out / "metrics.csv"));
  EXPECT_TRUE(fs::exists(out / "summary.json"));
  EXPECT_TRUE(fs::exists(out / "frames"));
}

}  // namespace

// ---- calibrate and --fem-params ---------------------------------------------

const std::string kHangingWind = WEAVELAB_SOURCE_DIR "/experiments/scenes/hanging_wind.toml";

TEST_F(Cli, CalibrateRejectsBadTestsLaddersAndPatchesBeforeWriting) {
  const fs::path out = dir_ / "cal";
  const std::vector<std::pair<std::string, std::string>> cases{
      {"--tests uniaxial-warp,twist", "unknown test 'twist'"},
      {"--ladder shear=", "--ladder shear: empty list"},
      {"--ladder shear=0.1,-0.2", "expected a comma-separated list of numbers > 0"},
      {"--ladder shear=0.2,0.1", "expected increasing finite loads > 0"},
      {"--ladder shear=0.1", "need at least 2 loads"},
      {"--tests shear --ladder biaxial=0.01,0.02", "the test is not among --tests"},
      {"--patch 4", "too small for the plain pattern: need at least 6"},
      {"--free shear_N_per_m,color", "unknown FEM parameter 'color'"},
      {"--starts 0", "--starts: need at least 1"},
      {"--validate missing.toml", "missing.toml"},
  };
  for (const auto& [args, fragment] : cases) {
    Result r = run_cli("calibrate '" + kHangingWind + "' " + args + " --out '" + out.string() + "'", dir_);
    EXPECT_EQ(r.code, 2) << args << ": " << r.output;
    EXPECT_NE(r.output.find(fragment), std::string::npos) << args << ": missing '" << fragment << "' in " << r.output;
    EXPECT_FALSE(fs::exists(out)) << args;
  }
}

TEST_F(Cli, CalibrateWritesAParameterFileThatRunReads) {
  const fs::path out = dir_ / "cal";
  Result r = run_cli("calibrate '" + kHangingWind + "' --tests uniaxial-warp,bending-warp --patch 7 --starts 1 --quiet"
                     " --out '" + out.string() + "'", dir_);
  ASSERT_EQ(r.code, 0) << r.output;
  for (const char* f : {"params.toml", "calibration.json", "curves.csv"}) EXPECT_TRUE(fs::exists(out / f)) << f;
  const fs::path run = dir_ / "run";
  r = run_cli("run '" + kHangingWind + "' --model fem --duration 0.01 --quiet --fem-params '" +
                  (out / "params.toml").string() + "' --out '" + run.string() + "'", dir_);
  ASSERT_EQ(r.code, 0) << r.output;
  std::ifstream in(run / "summary.json");
  std::stringstream summary;
  summary << in.rdbuf();
  EXPECT_NE(summary.str().find("fem.parameter_file"), std::string::npos);
}

TEST_F(Cli, RunRejectsABadFemParameterFile) {
  const fs::path params = dir_ / "params.toml";
  std::ofstream(params) << "warp_stretch_N_per_m = 300.0\ncolour = 2.0\n";
  const fs::path out = dir_ / "run";
  Result r = run_cli("run '" + kHangingWind + "' --model fem --fem-params '" + params.string() + "' --out '" +
                         out.string() + "'",
                     dir_);
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_NE(r.output.find(params.string() + ":2: key 'colour'"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(out));
}
