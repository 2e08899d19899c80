// A run's record stays true when the run is interrupted (SIGINT, SIGTERM,
// broken pipe, kill -9), when a second run aims at its folder, and when a run
// reuses an old folder.
#include <gtest/gtest.h>
#include <signal.h>
#include <unistd.h>

#include <chrono>
#include <thread>

#include "tests/output/output_test_util.h"
#include "tests/support/child_process.h"

namespace wl {
namespace {

namespace fs = std::filesystem;
using test::read_text;
using test::ScratchDir;
using test::wait_exit;

// A 5×5 hanging cloth: quick steps, so a long duration runs until a signal ends it.
std::string scene_text(double duration_s) {
  return "[cloth]\nwarps = 5\nwefts = 5\n[pose]\nkind = \"upright\"\nheight_m = 0.02\n"
         "[[handles]]\nnode = [0, 0]\n[[handles]]\nnode = [4, 0]\n"
         "[time]\ndt_s = 0.001\noutput_interval_s = 0.01\nduration_s = " +
         std::to_string(duration_s) + "\n";
}

// Checks that the folder holds one true record: summary.json with `outcome`;
// metrics.csv complete (no .part), one row per step plus the initial state,
// ending at end_time_s; run.pvd listing exactly the frame files present, as
// many as the summary counts; no temporary files.
const char* kCheckRecord = R"py(
import json, os, re, sys
out, outcome = sys.argv[1], sys.argv[2]
s = json.load(open(os.path.join(out, "summary.json")))
r = s["result"]
assert r["outcome"] == outcome, r
assert not os.path.exists(os.path.join(out, "metrics.csv.part")), "metrics.csv.part left"
rows = [l.split(",") for l in open(os.path.join(out, "metrics.csv")).read().splitlines()]
assert all(len(x) == len(rows[0]) for x in rows), "ragged metrics rows"
assert len(rows) - 2 == s["statistics"]["steps"], (len(rows), s["statistics"]["steps"])
assert float(rows[-1][0]) == r["end_time_s"], (rows[-1][0], r["end_time_s"])
listed = re.findall(r'file="([^"]+)"', open(os.path.join(out, "run.pvd")).read())
present = sorted("frames/" + f for f in os.listdir(os.path.join(out, "frames")))
assert sorted(listed) == present, (listed, present)
assert len(listed) == r["frames"], (len(listed), r["frames"])
temps = [f for _, _, fs in os.walk(out) for f in fs if ".tmp-" in f]
assert not temps, temps
print("consistent", r["frames"], "frames", s["statistics"]["steps"], "steps")
)py";

class RunRecord : public ::testing::Test {
 protected:
  void SetUp() override {
    ASSERT_TRUE(test::python_with("json"));
    std::ofstream(dir_ / "long.toml") << scene_text(100.0);
    std::ofstream(dir_ / "short.toml") << scene_text(0.05);
  }

  // Starts `weavelab run SCENE --out OUT extra...` with stdout and stderr to
  // `log` (or to `stderr_fd` when ≥ 0); returns its pid.
  pid_t start(const std::string& scene, const fs::path& out, std::vector<std::string> extra = {}, int stderr_fd = -1) {
    std::vector<std::string> args = {"run", (dir_ / scene).string(), "--out", out.string()};
    args.insert(args.end(), extra.begin(), extra.end());
    return spawn(args, stderr_fd);
  }
  // Starts `weavelab ARGS...` with stdout and stderr to `log` (or stderr to `stderr_fd` when ≥ 0).
  pid_t spawn(std::vector<std::string> args, int stderr_fd = -1) {
    return test::spawn_logged(WEAVELAB_CLI, std::move(args), (dir_ / "log.txt").string(), stderr_fd);
  }
  // Waits until the run has written at least `rows` metrics rows (at most 60 s).
  static void wait_for_rows(const fs::path& out, int rows) {
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
    while (std::chrono::steady_clock::now() < deadline) {
      const std::string text = read_text(out / "metrics.csv.part");
      if (std::count(text.begin(), text.end(), '\n') > rows) return;
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    ADD_FAILURE() << "the run wrote no " << rows << " metrics rows in 60 s";
  }
  ::testing::AssertionResult consistent(const fs::path& out, const std::string& outcome) {
    const auto r = test::run_python_script(dir_.path(), kCheckRecord, test::shell_quote(out.string()) + " " + outcome);
    if (r.exit_code == 0) return ::testing::AssertionSuccess() << r.output;
    return ::testing::AssertionFailure() << "record in " << out << " not consistent:\n"
                                         << r.output << "\nrun log:\n"
                                         << read_text(dir_ / "log.txt");
  }
  std::string log() { return read_text(dir_ / "log.txt"); }

  ScratchDir dir_;
};

TEST_F(RunRecord, SigintAndSigtermLeaveAnInterruptedRecord) {
  for (const auto& [sig, code] : {std::pair{SIGINT, 130}, std::pair{SIGTERM, 143}}) {
    const fs::path out = dir_ / ("out" + std::to_string(sig));
    const pid_t pid = start("long.toml", out, {"--quiet"});
    wait_for_rows(out, 40);
    ::kill(pid, sig);
    EXPECT_EQ(wait_exit(pid), code) << log();
    EXPECT_NE(log().find(sig == SIGINT ? "SIGINT" : "SIGTERM"), std::string::npos) << log();
    EXPECT_TRUE(consistent(out, "interrupted"));
  }
}

// Every --accuracy trial is a written run: a signal during one ends its step
// and leaves its record (before, the trials ignored it and a second signal
// killed the process with nothing written).
TEST_F(RunRecord, SigtermDuringAnAccuracyTrialLeavesAnInterruptedRecord) {
  const fs::path out = dir_ / "accuracy";
  const pid_t pid = start("long.toml", out, {"--quiet", "--accuracy", "1e-4"});
  wait_for_rows(out, 5);
  ::kill(pid, SIGTERM);
  EXPECT_EQ(wait_exit(pid), 143) << log();
  EXPECT_TRUE(consistent(out, "interrupted"));
  const std::string summary = read_text(out / "summary.json");
  EXPECT_NE(summary.find("\"verdict\": \"interrupted\""), std::string::npos) << summary;
  EXPECT_NE(summary.find("\"name\": \"sdirk2\""), std::string::npos) << summary;
}

// A signal during a fit ends the simulation at its step and the fit at once,
// with fit.json (outcome `interrupted`), convergence.csv and frames.csv written
// whole (before, the default action killed it with nothing written).
TEST_F(RunRecord, SigtermDuringAFitLeavesAnInterruptedRecord) {
  std::ofstream(dir_ / "half.toml") << scene_text(0.5);
  ASSERT_EQ(wait_exit(start("half.toml", dir_ / "target", {"--quiet"})), 0) << log();
  const fs::path out = dir_ / "fit";
  const pid_t pid =
      spawn({"fit", (dir_ / "half.toml").string(), "--target", (dir_ / "target").string(), "--free",
             "contact.shear_modulus_Pa", "--start", "contact.shear_modulus_Pa=1500", "--out", out.string()});
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (log().find("fit iteration") == std::string::npos && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  ::kill(pid, SIGTERM);
  EXPECT_EQ(wait_exit(pid), 143) << log();
  EXPECT_NE(log().find("interrupted by SIGTERM"), std::string::npos) << log();
  EXPECT_NE(read_text(out / "fit.json").find("\"outcome\": \"interrupted\""), std::string::npos) << log();
  for (const char* file : {"convergence.csv", "frames.csv"}) EXPECT_TRUE(fs::exists(out / file)) << file;
  for (const auto& entry : fs::directory_iterator(out))
    EXPECT_EQ(entry.path().string().find(".part"), std::string::npos) << entry.path();
}

// A signal during calibrate ends the stage under way and leaves calibration.json
// with outcome `interrupted` (before, the default action killed it with nothing
// written): in the fit (forty starts) each start at its Ceres iteration, no
// params.toml; in the validation the time step, with the whole fit's params.toml
// and curves.csv and validation.csv closed.
TEST_F(RunRecord, SignalsDuringACalibrationLeaveAnInterruptedRecord) {
  const struct {
    int signal, code;
    std::vector<std::string> options;
    std::string wait_for, stage;
    std::vector<std::string> files, absent;
  } cases[] = {
      {SIGTERM, 143, {"--starts", "40"}, "fit start 1: iteration 2", "the fit", {}, {"params.toml", "curves.csv"}},
      {SIGINT,
       130,
       {"--starts", "1", "--validate", (dir_ / "long.toml").string()},
       "validation long: yarn level",
       "the validation",
       {"params.toml", "curves.csv", "validation.csv"},
       {}},
  };
  for (const auto& c : cases) {
    const fs::path out = dir_ / ("calibration" + std::to_string(c.signal));
    std::vector<std::string> args = {"calibrate", (dir_ / "short.toml").string(), "--tests", "shear", "--out",
                                     out.string()};
    args.insert(args.end(), c.options.begin(), c.options.end());
    const pid_t pid = spawn(args);
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
    while (log().find(c.wait_for) == std::string::npos && std::chrono::steady_clock::now() < deadline)
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    ::kill(pid, c.signal);
    const auto signalled = std::chrono::steady_clock::now();
    EXPECT_EQ(wait_exit(pid), c.code) << log();
    EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - signalled).count(), 2.0) << log();
    EXPECT_NE(log().find("interrupted by " + std::string(c.signal == SIGINT ? "SIGINT" : "SIGTERM") + " in " + c.stage),
              std::string::npos)
        << log();
    const std::string record = read_text(out / "calibration.json");
    EXPECT_NE(record.find("\"outcome\": \"interrupted\""), std::string::npos) << record;
    EXPECT_NE(record.find("\"interrupted_in\": \"" + c.stage + "\""), std::string::npos) << record;
    for (const std::string& file : c.files) EXPECT_TRUE(fs::exists(out / file)) << c.stage << ": " << file;
    for (const std::string& file : c.absent) EXPECT_FALSE(fs::exists(out / file)) << c.stage << ": " << file;
    for (const auto& entry : fs::directory_iterator(out))
      EXPECT_TRUE(entry.path().string().find(".part") == std::string::npos &&
                  entry.path().string().find(".tmp-") == std::string::npos)
          << entry.path();
  }
}

TEST_F(RunRecord, BrokenStderrPipeKeepsTheRecord) {
  int fds[2];
  ASSERT_EQ(::pipe(fds), 0);
  ::close(fds[0]);  // nobody reads: every progress line meets a broken pipe
  const fs::path out = dir_ / "out";
  const pid_t pid = start("short.toml", out, {}, fds[1]);
  ::close(fds[1]);
  EXPECT_EQ(wait_exit(pid), 0) << log();
  EXPECT_TRUE(consistent(out, "ok"));
}

TEST_F(RunRecord, KillNineLeavesCompleteMetricsRows) {
  const fs::path out = dir_ / "out";
  const pid_t pid = start("long.toml", out, {"--quiet"});
  wait_for_rows(out, 40);
  ::kill(pid, SIGKILL);
  EXPECT_EQ(wait_exit(pid), 1000 + SIGKILL);
  const std::string text = read_text(out / "metrics.csv.part");
  ASSERT_FALSE(text.empty());
  EXPECT_EQ(text.back(), '\n') << "torn last row";
  std::istringstream lines(text);
  std::string line;
  std::getline(lines, line);
  const auto columns = std::count(line.begin(), line.end(), ',');
  int rows = 0;
  while (std::getline(lines, line)) {
    EXPECT_EQ(std::count(line.begin(), line.end(), ','), columns) << line;
    ++rows;
  }
  EXPECT_GE(rows, 40);  // at least the rows seen before the kill (header + 40 lines)
  // The lock dies with the process: the next run may use the folder.
  EXPECT_EQ(wait_exit(start("short.toml", out, {"--quiet"})), 0) << log();
  EXPECT_TRUE(consistent(out, "ok"));
}

TEST_F(RunRecord, SecondRunIntoABusyFolderIsRefused) {
  const fs::path out = dir_ / "out";
  const pid_t first = start("long.toml", out, {"--quiet"});
  wait_for_rows(out, 20);
  const auto second =
      test::run_command(std::string(WEAVELAB_CLI) + " run " + test::shell_quote((dir_ / "short.toml").string()) +
                        " --quiet --out " + test::shell_quote(out.string()));
  EXPECT_EQ(second.exit_code, 2) << second.output;
  EXPECT_NE(second.output.find(out.string()), std::string::npos) << second.output;
  EXPECT_NE(second.output.find("in use"), std::string::npos) << second.output;
  ::kill(first, SIGINT);
  EXPECT_EQ(wait_exit(first), 130) << log();
  EXPECT_TRUE(consistent(out, "interrupted"));  // the first run's record, untouched by the second
}

TEST_F(RunRecord, RerunIntoAnOldFolderLeavesNoOldFile) {
  const fs::path out = dir_ / "out";
  ASSERT_EQ(wait_exit(start("short.toml", out, {"--quiet", "--duration", "0.1"})), 0) << log();
  const int old_frames = test::count_entries(out / "frames");
  std::ofstream(out / "notes.txt") << "the user's own file";
  // A shorter rerun: fewer frames, none of the old ones left.
  ASSERT_EQ(wait_exit(start("short.toml", out, {"--quiet"})), 0) << log();
  EXPECT_LT(test::count_entries(out / "frames"), old_frames);
  EXPECT_TRUE(consistent(out, "ok"));
  EXPECT_TRUE(fs::exists(out / "notes.txt")) << "a file no run writes was removed";
  // An interrupted rerun: no old summary beside the new frames.
  const pid_t pid = start("long.toml", out, {"--quiet"});
  wait_for_rows(out, 20);
  ::kill(pid, SIGINT);
  EXPECT_EQ(wait_exit(pid), 130) << log();
  EXPECT_TRUE(consistent(out, "interrupted"));
}

}  // namespace
}  // namespace wl
