// The command line on bad input: a clear message, exit code 2 and nothing written.
#include <gtest/gtest.h>

#include <stdlib.h>
#include <sys/wait.h>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "tests/output/output_test_util.h"
#include "tests/support/test_scenes.h"

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
    for (const auto& f : fragments)
      EXPECT_NE(r.output.find(f), std::string::npos) << "missing '" << f << "' in: " << r.output;
    EXPECT_FALSE(fs::exists(out)) << "output written for a bad scene";
  }
  // `calibrate SCENE ARGS` for each case: exit 2, the fragment in the message, no output folder.
  void expect_calibrate_rejected(const std::string& scene,
                                 const std::vector<std::pair<std::string, std::string>>& cases) {
    const fs::path out = dir_ / "cal";
    for (const auto& [args, fragment] : cases) {
      Result r = run_cli("calibrate '" + scene + "' " + args + " --out '" + out.string() + "'", dir_);
      EXPECT_EQ(r.code, 2) << args << ": " << r.output;
      EXPECT_NE(r.output.find(fragment), std::string::npos) << args << ": missing '" << fragment << "' in " << r.output;
      EXPECT_FALSE(fs::exists(out)) << args;
    }
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

TEST_F(Cli, HandleStoppingBeforeItStartsIsRejected) {
  expect_rejected(
      "[cloth]\nwarps = 5\n[[handles]]\nnode = [0, 0]\nvelocity_m_per_s = [0.1, 0, 0]\n"
      "start_s = 0.02\nstop_s = 0.01\n",
      {"bad.toml:7", "handles[0].stop_s", "0.01", "> start_s (= 0.02)"});
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
  Result r = run_cli(std::string("run '") + WEAVELAB_SOURCE_DIR +
                         "/experiments/scenes/hanging_wind.toml' --integrator rk99 --out '" + out.string() + "'",
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

TEST_F(Cli, InfoReportsTheParametersOfAFemParameterFile) {
  const fs::path params = dir_ / "params.toml";
  std::ofstream(params) << "warp_bending_N_m = 3.5e-07\n";
  const std::string info = std::string("info '") + WEAVELAB_SOURCE_DIR +
                           "/experiments/scenes/hanging_wind.toml' --model fem --fem-params '" + params.string() + "'";
  Result r = run_cli(info, dir_);
  EXPECT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("warp_bending_N_m=3.5e-07"), std::string::npos) << r.output;
  std::ofstream(params) << "colour = 2.0\n";
  r = run_cli(info, dir_);
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_NE(r.output.find("key 'colour'"), std::string::npos) << r.output;
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

std::string file_text(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// --error-estimate and --accuracy record their estimate in the summary; a
// --duration below the scene's output interval is forgiven with a notice.
TEST_F(Cli, TimeErrorEstimateAndAccuracyAreRecorded) {
  const std::string scene = std::string(WEAVELAB_SOURCE_DIR) + "/experiments/scenes/hanging_wind_frozen.toml";
  const fs::path est = dir_ / "estimate", acc = dir_ / "accuracy";
  Result r = run_cli("run '" + scene + "' --duration 0.004 --error-estimate --out '" + est.string() + "'", dir_);
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("note: --duration 0.004 s is shorter than the scene's output interval"), std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find("time error (richardson)"), std::string::npos) << r.output;
  const std::string summary = file_text(est / "summary.json");
  EXPECT_NE(summary.find("\"time_error\""), std::string::npos);
  EXPECT_NE(summary.find("\"mean_rms_m\""), std::string::npos);
  r = run_cli("run '" + scene + "' --duration 0.004 --accuracy 1e-7 --quiet --out '" + acc.string() + "'", dir_);
  ASSERT_EQ(r.code, 0) << r.output;
  const std::string chosen = file_text(acc / "summary.json");
  EXPECT_NE(chosen.find("\"reached\": true"), std::string::npos) << chosen;
  EXPECT_NE(chosen.find("\"name\": \"sdirk2\""), std::string::npos);
}

// README: reproducibility. Runs under different OpenMP thread counts, and with
// OpenBLAS left to its default or set to one thread, write the same bits; the
// summary records the thread counts in force.
TEST_F(Cli, RunsAreBitwiseIdenticalAcrossThreadCounts) {
  const std::vector<std::pair<const char*, const char*>> settings = {{nullptr, nullptr}, {"1", "1"}, {"2", nullptr}};
  for (size_t k = 0; k < settings.size(); ++k) {
    auto set = [](const char* name, const char* value) { value ? ::setenv(name, value, 1) : ::unsetenv(name); };
    set("OMP_NUM_THREADS", settings[k].first);
    set("OPENBLAS_NUM_THREADS", settings[k].second);
    const Result r = run_cli(std::string("run '") + WEAVELAB_SOURCE_DIR +
                                 "/experiments/scenes/hanging_wind.toml' --duration 0.02 --quiet --out '" +
                                 (dir_ / ("run" + std::to_string(k))).string() + "'",
                             dir_);
    ::unsetenv("OMP_NUM_THREADS");
    ::unsetenv("OPENBLAS_NUM_THREADS");
    ASSERT_EQ(r.code, 0) << r.output;
  }
  const std::string summary = file_text(dir_ / "run0" / "summary.json");
  EXPECT_NE(summary.find("\"openblas\": 1"), std::string::npos) << summary;
  for (size_t k = 1; k < settings.size(); ++k)
    for (const char* frame : {"frames/run_00001.vtu", "frames/run_00002.vtu"})
      EXPECT_EQ(file_text(dir_ / ("run" + std::to_string(k)) / frame), file_text(dir_ / "run0" / frame))
          << frame << " of setting " << k;
}

// Obstacles (docs/models.md §3.11): a bad shape, size or missing key, and a
// node that starts inside an obstacle, are located exit-2 errors writing nothing.
TEST_F(Cli, BadObstaclesAreLocatedExit2) {
  const std::string cloth = "[cloth]\nwarps = 5\nwefts = 5\n[pose]\nkind = \"flat\"\n";
  expect_rejected(cloth + "[[obstacles]]\nshape = \"torus\"\ncenter_m = [0, 0, -1]\n",
                  {"bad.toml:7", "obstacles[0].shape", "\"cylinder\""});
  expect_rejected(cloth + "[[obstacles]]\nshape = \"sphere\"\ncenter_m = [0, 0, -1]\nradius_m = -0.5\n",
                  {"bad.toml:9", "obstacles[0].radius_m", "a number > 0"});
  expect_rejected(cloth + "[[obstacles]]\nshape = \"plane\"\n", {"bad.toml:6", "obstacles[0].center_m"});
  expect_rejected(cloth + "[[obstacles]]\nshape = \"sphere\"\ncenter_m = [0.002, 0.002, 0]\nradius_m = 0.0015\n",
                  {"bad.toml:6", "obstacles[0]", "inside"});
}

// Knit scenes (docs/models.md §11): a knit key on a woven scene, a pattern
// whose tile does not cover the counts, an unknown kind: exit 2, located,
// nothing written; `info` describes a knit.
TEST_F(Cli, BadKnitScenesAreLocatedExit2) {
  expect_rejected("[cloth.pattern]\nkind = \"plain\"\n[knit]\nstitch_length_stiffness_N = 1\n",
                  {"bad.toml:4", "knit.stitch_length_stiffness_N", "woven scene"});
  expect_rejected("[cloth.pattern]\nkind = \"rib2x2\"\nwales = 10\n", {"bad.toml:3", "cloth.pattern.wales", "4"});
  expect_rejected("[cloth.pattern]\nkind = \"seed\"\n", {"bad.toml:2", "cloth.pattern.kind", "garter"});
}

// The yarn level has a model per cloth (models/model_factory.h): `yarn` woven, `knit` knitted.
// Without --model a run takes the scene's; the other one is refused, located at the scene's
// cloth.pattern.kind (or its absence), exit 2, nothing written.
TEST_F(Cli, YarnModelOnAKnitIsRefusedExit2) {
  const std::string knit = WEAVELAB_SOURCE_DIR "/experiments/scenes/knit_stockinette.toml";
  const fs::path out = dir_ / "out";
  const Result r = run_cli("run '" + knit + "' --model yarn --quiet --out '" + out.string() + "'", dir_);
  EXPECT_EQ(r.code, 2) << r.output;
  for (const char* f : {"knit_stockinette.toml:12: key 'cloth.pattern.kind' = \"stockinette\"", "model 'yarn'",
                        "expected model 'knit' or 'fem'"})
    EXPECT_NE(r.output.find(f), std::string::npos) << "missing '" << f << "' in: " << r.output;
  EXPECT_FALSE(fs::exists(out));
}

TEST_F(Cli, KnitModelOnAWovenSceneIsRefusedExit2) {
  const fs::path out = dir_ / "out";
  const std::string woven = WEAVELAB_SOURCE_DIR "/experiments/scenes/hanging_wind.toml";
  Result r = run_cli("run '" + woven + "' --model knit --quiet --out '" + out.string() + "'", dir_);
  EXPECT_EQ(r.code, 2) << r.output;
  for (const char* f :
       {"hanging_wind.toml:15: key 'cloth.pattern.kind' = \"plain\"", "model 'knit'", "expected model 'yarn' or 'fem'"})
    EXPECT_NE(r.output.find(f), std::string::npos) << "missing '" << f << "' in: " << r.output;
  EXPECT_FALSE(fs::exists(out));
  // A scene without the key is a plain weave: the message says the key is absent.
  const fs::path plain = write_scene(wl::test::hanging_cloth_toml(3, 0.01));
  r = run_cli("info '" + plain.string() + "' --model knit", dir_);
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_NE(r.output.find("bad.toml: no key 'cloth.pattern.kind'"), std::string::npos) << r.output;
  r = run_cli("work-precision '" + plain.string() + "' --models fem,knit --out '" + out.string() + "'", dir_);
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_NE(r.output.find("model 'knit'"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(out));
}

TEST_F(Cli, RunWithoutModelTakesTheScenesYarnLevel) {
  const fs::path knit = dir_ / "knit.toml", out = dir_ / "out";
  std::ofstream(knit) << wl::test::hanging_knit_toml(4, 3);
  Result r = run_cli("run '" + knit.string() + "' --quiet --out '" + out.string() + "'", dir_);
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_NE(file_text(out / "summary.json").find("\"name\": \"knit\""), std::string::npos);
  r = run_cli("info '" + knit.string() + "' --model knit", dir_);
  EXPECT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("pattern: stockinette"), std::string::npos) << r.output;
}

TEST_F(Cli, InfoDescribesAKnit) {
  Result r = run_cli(std::string("info '") + WEAVELAB_SOURCE_DIR + "/experiments/scenes/knit_garter.toml'", dir_);
  EXPECT_EQ(r.code, 0) << r.output;
  for (const char* f : {"pattern: garter", "stitch_contacts: 480", "stitch_roll", "rest_shape: 2 x 1 tile"})
    EXPECT_NE(r.output.find(f), std::string::npos) << "missing '" << f << "' in: " << r.output;
}

// A state the model cannot represent is a named numerical outcome (exit 1) with
// a complete record, not NaN or a runaway: without friction or parallel contact,
// a strong pull along the yarns slides crossing (1, 1) past (2, 1) in one step.
TEST_F(Cli, SlidingCoordinatesThatCrossEndInOutcomeInvalidState) {
  const fs::path scene = write_scene(
      "[cloth]\nwarps = 5\nwefts = 5\n[pose]\nkind = \"upright\"\n[[handles]]\nnode = [0, 0]\n"
      "stiffness_N_per_m = 10000.0\n[[handles]]\nnode = [4, 0]\nstiffness_N_per_m = 10000.0\n"
      "[gravity]\nacceleration_m_per_s2 = [0.0, 0.0, -10000.0]\n[time]\nduration_s = 0.02\n"
      "[terms]\nfriction = false\nparallel_contact = false\n");
  const fs::path out = dir_ / "out";
  const Result r = run_cli("run '" + scene.string() + "' --quiet --out '" + out.string() + "'", dir_);
  EXPECT_EQ(r.code, 1) << r.output;
  EXPECT_NE(r.output.find("'invalid_state'"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("on warp 1 between crossings (1, 1) and (2, 1)"), std::string::npos) << r.output;
  EXPECT_NE(file_text(out / "summary.json").find("\"invalid_state\""), std::string::npos);
  EXPECT_TRUE(fs::exists(out / "metrics.csv"));
}

// The settling phase (docs/models.md §3.11.6): steps of 1 ms to 0.02 s, then of
// 5 ms, and the end state's balance in summary.json.
TEST_F(Cli, ASettlingPhaseTakesItsStepsAndReportsTheBalance) {
  const fs::path scene = dir_ / "settle.toml", out = dir_ / "out";
  std::ofstream(scene) << "[cloth]\nwarps = 5\nwefts = 5\n[time]\nduration_s = 0.05\ndt_s = 0.001\n"
                          "output_interval_s = 0.01\nsettle_after_s = 0.02\nsettle_dt_s = 0.005\n";
  const Result r = run_cli("run '" + scene.string() + "' --quiet --out '" + out.string() + "'", dir_);
  ASSERT_EQ(r.code, 0) << r.output;
  std::ifstream metrics(out / "metrics.csv");
  std::string line;
  std::getline(metrics, line);
  std::vector<double> t;
  while (std::getline(metrics, line)) t.push_back(std::stod(line));
  ASSERT_EQ(t.size(), 1u + 20u + 6u);
  EXPECT_NEAR(t[20], 0.02, 1e-12);
  for (size_t k = 1; k < t.size(); ++k) EXPECT_NEAR(t[k] - t[k - 1], k <= 20 ? 0.001 : 0.005, 1e-12) << k;
  const std::string summary = file_text(out / "summary.json");
  for (const char* key : {"\"settle\"", "\"max_free_dof_force_N\"", "\"kinetic_J\""})
    EXPECT_NE(summary.find(key), std::string::npos) << key << "\n" << summary;
}

const std::string kMeshObstacle = "[[obstacles]]\nshape = \"mesh\"\ncenter_m = [0, 0, -1]\n";

// A mesh obstacle is written into the obstacles series with the cloth: the
// shipped icosphere's 642 vertices and 1280 triangles (docs/models.md §3.11.5).
TEST_F(Cli, AMeshObstacleIsWrittenWithTheCloth) {
  const fs::path out = dir_ / "out";
  const Result r =
      run_cli(std::string("run '") + WEAVELAB_SOURCE_DIR +
                  "/experiments/scenes/mesh_sphere_drape.toml' --duration 0.002 --quiet --out '" + out.string() + "'",
              dir_);
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_TRUE(fs::exists(out / "obstacles.pvd"));
  const std::string vtu = file_text(out / "frames" / "obstacles_00000.vtu");
  EXPECT_NE(vtu.find("NumberOfPoints=\"642\" NumberOfCells=\"1280\""), std::string::npos) << vtu.substr(0, 600);
  // meshio reads the file, and its triangles are the OBJ's faces, scaled by 4 mm
  // and moved to the scene's centre (the obstacle does not move).
  ASSERT_TRUE(wl::test::python_with("numpy, meshio"));
  const std::string script = R"(
import sys, numpy as np, meshio
m = meshio.read(sys.argv[1])
tri = np.vstack([c.data for c in m.cells if c.type == "triangle"])
v, f = [], []
for line in open(sys.argv[2]):
    w = line.split()
    if w and w[0] == "v": v.append([float(x) for x in w[1:4]])
    if w and w[0] == "f": f.append([int(x.split("/")[0]) - 1 for x in w[1:4]])
v = np.array(v) * 0.004 + np.array([0.008, 0.008, -0.004])
near = [int(np.argmin(np.linalg.norm(v - p, axis=1))) for p in m.points]
gap = max(np.linalg.norm(v[near] - m.points, axis=1))
got = {frozenset(near[i] for i in t) for t in tri}
want = {frozenset(t) for t in f}
print(len(tri), len(f), gap, got == want)
sys.exit(0 if len(tri) == len(f) and gap < 1e-12 and got == want else 1)
)";
  const wl::test::CommandResult py = wl::test::run_python_script(
      dir_, script,
      wl::test::shell_quote((out / "frames" / "obstacles_00000.vtu").string()) + " " +
          wl::test::shell_quote(std::string(WEAVELAB_SOURCE_DIR) + "/experiments/scenes/meshes/icosphere.obj"));
  EXPECT_EQ(py.exit_code, 0) << py.output;
}

// Bad inputs of every kind: each is exit 2 with a located message (the scene,
// mesh or parameter file with its line, or the option) and writes nothing.
TEST_F(Cli, EveryBadInputIsALocatedExit2) {
  const std::string good = "[cloth]\nwarps = 5\nwefts = 5\n[time]\nduration_s = 0.02\n";
  std::ofstream(dir_ / "good.toml") << good;
  const std::string mesh_head =
      "<VTKFile type=\"UnstructuredGrid\">\n<UnstructuredGrid>\n<Piece NumberOfPoints=\"3\" NumberOfCells=\"1\">\n";
  auto mesh = [&](const std::string& points, const std::string& conn, const std::string& type, const std::string& uv) {
    return mesh_head + "<Points>\n<DataArray Name=\"Points\" NumberOfComponents=\"3\" format=\"ascii\">\n" + points +
           "\n</DataArray>\n</Points>\n<Cells>\n<DataArray Name=\"connectivity\" format=\"ascii\">\n" + conn +
           "\n</DataArray>\n<DataArray Name=\"offsets\" format=\"ascii\">\n3\n</DataArray>\n"
           "<DataArray Name=\"types\" format=\"ascii\">\n" +
           type +
           "\n</DataArray>\n</Cells>\n<PointData>\n"
           "<DataArray Name=\"uv\" NumberOfComponents=\"2\" format=\"ascii\">\n" +
           uv + "\n</DataArray>\n</PointData>\n</Piece>\n</UnstructuredGrid>\n</VTKFile>\n";
  };
  const std::string pts = "0 0 0 0.004 0 0 0 0.004 0", conn = "0 1 2", uv = "0 0 0.004 0 0 0.004";
  struct Case {
    std::string args;           // after `run SCENE`
    std::string scene;          // scene text ("" = good.toml)
    std::string file, content;  // an extra input file the scene names
    std::string where;          // expected in the message: "<file>:<line>" or the option
  };
  const std::vector<Case> cases = {
      {"--dt 1e8", "", "", "", "'--dt'"},
      {"--dt inf", "", "", "", "'--dt'"},
      {"--dt nan", "", "", "", "'--dt'"},
      {"--dt -1", "", "", "", "--dt"},
      {"--dt 1e-12", "", "", "", "'--dt'"},
      {"--dt 1 --duration 0.01", "", "", "", "'--dt'"},
      {"--dt 0.05 --duration 1 --output-interval 0.01", "", "", "", "'--output-interval'"},
      {"--accuracy 0", "", "", "", "'--accuracy'"},
      {"--accuracy nan", "", "", "", "'--accuracy'"},
      {"--accuracy 1e-4 --dt 0.001", "", "", "", "'--accuracy'"},
      {"", "[time]\naccuracy_m = -1\n", "", "", "bad.toml:2"},
      {"--duration nan", "", "", "", "'--duration'"},
      {"--duration inf", "", "", "", "'--duration'"},
      {"--duration 0", "", "", "", "'--duration'"},
      {"--duration 1e9", "", "", "", "'--duration'"},
      {"--output-interval 1", "", "", "", "'--output-interval'"},
      {"--rtol 2", "", "", "", "'--rtol'"},
      {"--rtol nan", "", "", "", "'--rtol'"},
      {"--integrator foo", "", "", "", "'--integrator'"},
      {"--integrator ''", "", "", "", "'--integrator'"},
      {"--linear-solver lu", "", "", "", "'--linear-solver'"},
      {"--linear-solver cholmod", "", "", "", "'--linear-solver'"},           // the yarn step matrix is not symmetric
      {"", "[cloth]\nwarps = 16384\nwefts = 16384\n", "", "", "bad.toml:2"},  // cannot fit in memory
      {"--out ''", "", "", "", "'--out'"},
      {"--model cloth", "", "", "", "cloth"},
      {"--dt abc", "", "", "", "--dt"},
      {"", "[time]\nintegrator = \"foo\"\n", "", "", "bad.toml:2"},
      {"--integrator arkode-dirk", "[time]\nduration_s = 0.02\nsettle_after_s = 0.01\nsettle_dt_s = 0.005\n", "", "",
       "bad.toml:4"},  // the library's steps are not ours to change
      {"", "[time]\ndt_s = 0.5\n", "", "", "bad.toml:2"},
      {"", "[time]\nduration_s = 0.001\n", "", "", "bad.toml:2"},
      {"", "[time]\ndt_s = 1e-10\n", "", "", "bad.toml:2"},
      {"", "[time]\nduration_s = nan\n", "", "", "bad.toml:2"},
      {"", "[contact]\nlock_exponent = 0\n", "", "", "bad.toml:2"},
      {"", "[cloth]\nradius_m = 0.0008\n", "", "", "bad.toml:2"},
      {"--model fem --fem-params ''", "", "", "", "'--fem-params'"},
      {"--model fem --fem-params '" + (dir_ / "missing.toml").string() + "'", "", "", "", "'--fem-params'"},
      {"--model fem --fem-params '" + (dir_ / "p.toml").string() + "'", "", "p.toml", "shear_N_per_m = nan\n",
       "p.toml:1"},
      {"", "[cloth]\nwarps = 2\n", "", "", "bad.toml:2"},
      {"--model fem", "[cloth]\nwarps = 3\nwefts = 3\n[fem]\nmesh_file = \"m.vtu\"\n", "m.vtu", "", "m.vtu:1"},
      {"--model fem", "[cloth]\nwarps = 3\nwefts = 3\n[fem]\nmesh_file = \"m.vtu\"\n", "m.vtu",
       mesh("0 nan 0 0.004 0 0 0 0.004 0", conn, "5", uv), "m.vtu:5"},
      {"--model fem", "[cloth]\nwarps = 3\nwefts = 3\n[fem]\nmesh_file = \"m.vtu\"\n", "m.vtu",
       mesh(pts, conn, "9", uv), "m.vtu:"},
      {"--model fem", "[cloth]\nwarps = 3\nwefts = 3\n[fem]\nmesh_file = \"m.vtu\"\n", "m.vtu",
       mesh(pts, "0 1 5", "5", uv), "m.vtu:"},
      {"--model fem", "[cloth]\nwarps = 3\nwefts = 3\n[fem]\nmesh_file = \"m.vtu\"\n", "m.vtu",
       mesh(pts, "0 1 1", "5", uv), "m.vtu:"},
      {"--model fem", "[cloth]\nwarps = 3\nwefts = 3\n[fem]\nmesh_file = \"m.vtu\"\n", "m.vtu",
       mesh_head + "<Points>\n<DataArray Name=\"Points\" NumberOfComponents=\"3\" format=\"binary\">\n", "m.vtu:5"},
      {"--model fem", "[cloth]\nwarps = 3\nwefts = 3\n[fem]\nparameter_file = \"p.toml\"\n", "p.toml",
       "shear_N_per_m = -1\n", "p.toml:1"},
      {"--model fem", "[cloth]\nwarps = 3\nwefts = 3\n[fem]\nparameter_file = \"p.toml\"\n", "p.toml",
       "\nshear_modulus = 1\n", "p.toml:2"},
      {"--model fem", "[cloth]\nwarps = 3\nwefts = 3\n[fem]\nparameter_file = \"p.toml\"\n", "p.toml", "x = [",
       "p.toml:1"},
      // mesh obstacles (docs/models.md §3.11.9): a missing, garbled, degenerate or open mesh, a scale ≤ 0
      {"", kMeshObstacle + "file = \"nope.obj\"\n", "", "", "bad.toml:4"},
      {"", kMeshObstacle + "file = \"m.obj\"\n", "m.obj", "v 0 0 0\nv 1 0 zz\n", "m.obj:2"},
      {"", kMeshObstacle + "file = \"m.obj\"\nside = \"both\"\n", "m.obj", "v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\n",
       "m.obj:4"},
      {"", kMeshObstacle + "file = \"m.obj\"\n", "m.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", "m.obj:4"},
      {"", kMeshObstacle + "file = \"m.obj\"\nscale = 0\n", "m.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n",
       "bad.toml:5"},
  };
  int rejected = 0, located = 0, written = 0;
  for (const Case& c : cases) {
    if (!c.file.empty()) std::ofstream(dir_ / c.file) << c.content;
    const fs::path scene = c.scene.empty() ? dir_ / "good.toml" : write_scene(c.scene);
    const fs::path out = dir_ / "out";
    const std::string out_arg = c.args.find("--out") == std::string::npos ? " --out '" + out.string() + "'" : "";
    const Result r = run_cli("run '" + scene.string() + "' --quiet " + c.args + out_arg, dir_);
    EXPECT_EQ(r.code, 2) << c.args << "\n" << c.scene << "\n" << r.output;
    EXPECT_NE(r.output.find(c.where), std::string::npos) << "missing '" << c.where << "' in: " << r.output;
    rejected += r.code == 2;
    located += r.output.find(c.where) != std::string::npos;
    if (fs::exists(out)) {
      ++written;
      ADD_FAILURE() << "output written for: " << c.args << "\n" << c.scene;
      fs::remove_all(out);
    }
    if (!c.file.empty()) fs::remove(dir_ / c.file);
  }
  std::cout << "bad inputs tried " << cases.size() << ", rejected with exit 2 " << rejected << ", located " << located
            << ", output folders written " << written << "\n";
}

}  // namespace

// ---- calibrate and --fem-params ---------------------------------------------

const std::string kHangingWind = WEAVELAB_SOURCE_DIR "/experiments/scenes/hanging_wind.toml";

TEST_F(Cli, CalibrateRejectsBadTestsLaddersAndPatchesBeforeWriting) {
  const std::vector<std::pair<std::string, std::string>> cases{
      {"--tests uniaxial-warp,twist", "unknown test 'twist'"},
      {"--tests shear,rotated-twist", "unknown test 'twist'"},
      {"--tests shear,bending-diagonal,shear", "'shear' is listed twice"},
      {"--ladder shear=", "--ladder shear: empty list"},
      {"--ladder shear=0.1,-0.2", "expected a comma-separated list of numbers > 0"},
      {"--ladder shear=0.2,0.1", "expected increasing finite loads > 0"},
      {"--ladder shear=0.1", "need at least 2 loads"},
      {"--tests shear --ladder biaxial=0.01,0.02", "the test is not among --tests"},
      {"--patch 4", "too small for the plain pattern: need at least 6"},
      {"--free shear_N_per_m,color", "unknown FEM parameter 'color'"},
      {"--starts 0", "--starts: need at least 1"},
      {"--loss weird", "--loss: got 'weird'"},
      {"--validate missing.toml", "missing.toml"},
      {"--time-steps coarse", "--time-steps: got 'coarse', expected 'controlled' or 'scene'"},
      {"--resolution coarse", "--resolution: got 'coarse', expected 'controlled' or 'scene'"},  // the old name
      {"--time-steps scene --resolution scene", "expected only one of the two"},
      {"--rtol 2", "--rtol: got 2"},
      {"--rtol 1e-13", "--rtol: got 1e-13, expected a tolerance ≥ 1e-12"},  // the floor of time.rtol
  };
  expect_calibrate_rejected(kHangingWind, cases);
}

TEST_F(Cli, CalibrateRefusesWhatAKnitPatchDoesNotOffer) {
  // docs/calibration.md §8: each unsupported option is a located error before anything runs.
  const std::string knit = WEAVELAB_SOURCE_DIR "/experiments/scenes/knit_stockinette.toml";
  const std::vector<std::pair<std::string, std::string>> cases{
      {"--validate '" + kHangingWind + "'", "is knitted"},
      {"--border-strip", "--border-strip"},
      {"--grid-line-bending", "--grid-line-bending"},
      {"--tests rotated-shear", "expected it unrotated"},
      {"--patch 5", "need at least 6"},
  };
  expect_calibrate_rejected(knit, cases);
}

// --resolution, the old name of --time-steps, still works and says so on stderr.
TEST_F(Cli, ResolutionIsTheOldNameOfTimeSteps) {
  const fs::path out = dir_ / "out";
  const Result r = run_cli("calibrate '" + kHangingWind + "' --resolution fine --out '" + out.string() + "'", dir_);
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_NE(r.output.find("weavelab: --resolution is deprecated: use --time-steps\n"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(out));
  const Result plain = run_cli("calibrate '" + kHangingWind + "' --time-steps fine --out '" + out.string() + "'", dir_);
  EXPECT_EQ(plain.code, 2) << plain.output;
  EXPECT_EQ(plain.output.find("deprecated"), std::string::npos) << plain.output;
}

TEST_F(Cli, CalibrateWritesAParameterFileThatRunReads) {
  const fs::path out = dir_ / "cal", small = dir_ / "small.toml";
  std::ofstream(small) << wl::test::hanging_cloth_toml(5, 0.02);
  Result r = run_cli("calibrate '" + kHangingWind +
                         "' --tests uniaxial-warp,bending-warp --patch 7 --starts 1 --quiet --validate '" +
                         small.string() + "' --out '" + out.string() + "'",
                     dir_);
  ASSERT_EQ(r.code, 0) << r.output;
  for (const char* f : {"params.toml", "calibration.json", "curves.csv", "validation.csv"})
    EXPECT_TRUE(fs::exists(out / f)) << f;
  // The validation sets each side's time error beside the distance.
  const std::string record = file_text(out / "calibration.json");
  EXPECT_NE(record.find("\"yarn_time_error\""), std::string::npos);
  EXPECT_NE(record.find("\"budget\""), std::string::npos);
  EXPECT_NE(record.find("\"resolution\": \"sdirk2 under error control"), std::string::npos);
  const fs::path run = dir_ / "run";
  r = run_cli("run '" + kHangingWind + "' --model fem --duration 0.01 --quiet --fem-params '" +
                  (out / "params.toml").string() + "' --out '" + run.string() + "'",
              dir_);
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
  Result r = run_cli(
      "run '" + kHangingWind + "' --model fem --fem-params '" + params.string() + "' --out '" + out.string() + "'",
      dir_);
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_NE(r.output.find(params.string() + ":2: key 'colour'"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(out));
}

// `tiles` (docs/calibration.md §9): a bad sampling option or a knitted scene
// exits 2 naming the option and its value, before anything is written.
TEST_F(Cli, TilesBadSamplingOptionsAreRejected) {
  const std::string knit = WEAVELAB_SOURCE_DIR "/experiments/scenes/knit_stockinette.toml";
  const fs::path out = dir_ / "tiles";
  const std::vector<std::pair<std::string, std::string>> cases{
      {"--samples 1", "--samples 1: expected at least 2"},
      {"--holdout-every 1", "--holdout-every 1: expected at least 2"},
      {"--samples 100", "--samples 100: the law's"},
      {"--range shear=0.5,0.1", "--range shear=0.5,0.1: expected finite LO < HI"},
      {"--range bend=0,1", "--range bend=0,1: unknown strain 'bend'"},
      {"--range twist=a,1", "--range twist=a,1: LO and HI must be numbers"},
      {"--range twist", "--range twist: expected NAME=LO,HI"}};
  for (const auto& [args, fragment] : cases) {
    Result r = run_cli("tiles '" + kHangingWind + "' " + args + " --out '" + out.string() + "'", dir_);
    EXPECT_EQ(r.code, 2) << args << ": " << r.output;
    EXPECT_NE(r.output.find(fragment), std::string::npos) << args << ": missing '" << fragment << "' in " << r.output;
    EXPECT_FALSE(fs::exists(out)) << args;
  }
  Result r = run_cli("tiles '" + knit + "' --out '" + out.string() + "'", dir_);
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_NE(r.output.find("is knitted"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(out));
}
