// SIGINT and SIGTERM in the studies (diagnose, modes, fidelity, pull, stability,
// work-precision, tiles): the step under way ends, the study's JSON says outcome
// `interrupted` and the stage, every table begun is committed (no .part or
// temporary file), the exit code is 128 + the signal and the message names the
// signal, the stage and the folder (before, the default action killed them
// with .part files and no JSON).
#include <gtest/gtest.h>
#include <signal.h>

#include <algorithm>
#include <chrono>
#include <fstream>
#include <thread>

#include "tests/output/output_test_util.h"
#include "tests/support/child_process.h"

namespace wl {
namespace {

namespace fs = std::filesystem;
using test::read_text;
using test::ScratchDir;
using test::wait_exit;

// A size×size hanging cloth whose 100 s outlast any test.
std::string hanging_text(int size) {
  return "[cloth]\nwarps = " + std::to_string(size) + "\nwefts = " + std::to_string(size) +
         "\n[pose]\nkind = \"upright\"\nheight_m = 0.02\n[[handles]]\nnode = [0, 0]\n[[handles]]\nnode = [" +
         std::to_string(size - 1) + ", 0]\n[time]\ndt_s = 0.001\noutput_interval_s = 0.01\nduration_s = 100\n";
}

// The free stockinette patch at 8 × 8: its first pull rung takes hundreds of Newton iterations.
std::string knit_text() {
  std::string text = read_text(fs::path(WEAVELAB_SOURCE_DIR) / "experiments/scenes/knit_stockinette.toml");
  const std::string size = "courses = 16\nwales = 16\n";
  const size_t at = text.find(size);
  if (at != std::string::npos) text.replace(at, size.size(), "courses = 8\nwales = 8\n");
  return text;
}

// The longest a step may take after the signal: the Release build's bound, ten
// times that under AddressSanitizer (slower steps, several shards per core).
#if defined(__SANITIZE_ADDRESS__)
constexpr double kStepBound_s = 20.0;
#else
constexpr double kStepBound_s = 2.0;
#endif

struct StudyCase {
  std::string name;               // the subcommand
  std::vector<std::string> args;  // after SCENE and "--out OUT"; "DIR/" starts a path in the scratch folder
  std::string scene;              // hanging.toml (5 × 5), large.toml (25 × 25) or knit.toml
  std::string started;            // the progress line after which the signal is sent ("": after 1 s)
  std::string record;             // the study's JSON
  std::string stage;              // its interrupted_in
  int signal;
  std::vector<std::string> tables;  // committed with their rows so far
};

// Names a case by its subcommand in the test's listing.
void PrintTo(const StudyCase& c, std::ostream* os) { *os << c.name; }

class StudySignal : public ::testing::TestWithParam<StudyCase> {
 protected:
  void SetUp() override {
    std::ofstream(dir_ / "hanging.toml") << hanging_text(5);
    std::ofstream(dir_ / "large.toml") << hanging_text(25);
    const std::string knit = knit_text();
    ASSERT_NE(knit.find("courses = 8"), std::string::npos) << "the stockinette scene changed";
    std::ofstream(dir_ / "knit.toml") << knit;
  }
  // Starts `weavelab ARGS...` with stdout and stderr to the log; returns its pid.
  pid_t spawn(std::vector<std::string> args) {
    return test::spawn_logged(WEAVELAB_CLI, std::move(args), (dir_ / "log.txt").string());
  }
  std::string log() { return read_text(dir_ / "log.txt"); }

  ScratchDir dir_;
};

TEST_P(StudySignal, EndsTheStepAndLeavesAnInterruptedRecord) {
  const StudyCase& c = GetParam();
  const fs::path out = dir_ / "out";
  std::vector<std::string> args{c.name, (dir_ / c.scene).string(), "--out", out.string()};
  for (const std::string& a : c.args) args.push_back(a.rfind("DIR/", 0) == 0 ? (dir_ / a.substr(4)).string() : a);
  const pid_t pid = spawn(args);
  if (c.started.empty()) {
    std::this_thread::sleep_for(std::chrono::milliseconds(1000));
  } else {
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
    while (log().find(c.started) == std::string::npos && std::chrono::steady_clock::now() < deadline)
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    std::this_thread::sleep_for(std::chrono::milliseconds(100));  // well inside the stage
  }
  ::kill(pid, c.signal);
  const auto signalled = std::chrono::steady_clock::now();
  const int code = wait_exit(pid);
  const double delay = std::chrono::duration<double>(std::chrono::steady_clock::now() - signalled).count();
  RecordProperty("delay_s", std::to_string(delay));
  EXPECT_EQ(code, 128 + c.signal) << log();
  EXPECT_LT(delay, kStepBound_s) << log();
  const std::string signal = c.signal == SIGINT ? "SIGINT" : "SIGTERM";
  EXPECT_NE(log().find("weavelab: " + c.name + ": interrupted by " + signal + " in " + c.stage), std::string::npos)
      << log();
  EXPECT_NE(log().find("; the record so far in " + out.string()), std::string::npos) << log();
  const std::string record = read_text(out / c.record);
  EXPECT_NE(record.find("\"outcome\": \"interrupted\""), std::string::npos) << record;
  EXPECT_NE(record.find("\"interrupted_in\": \"" + c.stage), std::string::npos) << record;
  EXPECT_NE(record.find("\"message\": \"interrupted by " + signal + "\""), std::string::npos) << record;
  for (const std::string& table : c.tables) EXPECT_TRUE(fs::exists(out / table)) << table;
  for (const auto& entry : fs::recursive_directory_iterator(out))
    EXPECT_TRUE(entry.path().string().find(".part") == std::string::npos &&
                entry.path().string().find(".tmp-") == std::string::npos)
        << entry.path();
}

INSTANTIATE_TEST_SUITE_P(
    Studies, StudySignal,
    ::testing::Values(
        StudyCase{"diagnose",
                  {"--no-error-estimate"},
                  "hanging.toml",
                  "diagnose: yarn model",
                  "diagnosis.json",
                  "the yarn-level run",
                  SIGTERM,
                  {"energies.csv", "energy_directions.csv"}},
        StudyCase{"modes", {}, "large.toml", "modes: yarn model", "modes.json", "the yarn level's modes", SIGINT, {}},
        StudyCase{"fidelity",
                  {},
                  "hanging.toml",
                  "fidelity: reference full",
                  "fidelity.json",
                  "the reference full",
                  SIGTERM,
                  {"fidelity.csv"}},
        StudyCase{"pull", {}, "knit.toml", "", "pull.json", "the strain 0 rung", SIGTERM, {"pull.csv"}},
        StudyCase{"stability",
                  {"--models", "yarn", "--integrators", "be-linear"},
                  "hanging.toml",
                  "stability [1/",
                  "stability.json",
                  "the cell yarn be-linear x1",
                  SIGINT,
                  {"stability.csv", "stability_probes.csv"}},
        StudyCase{"work-precision",
                  {"--models", "yarn", "--integrators", "sdirk2", "--reference-dir", "DIR/refs"},
                  "hanging.toml",
                  "reference yarn",
                  "work_precision.json",
                  "the yarn reference",
                  SIGTERM,
                  {"work_precision.csv"}},
        StudyCase{"tiles",
                  {"--samples", "100000", "--no-fit"},
                  "hanging.toml",
                  "",
                  "tiles.json",
                  "the tile samples",
                  SIGINT,
                  {}}),
    [](const ::testing::TestParamInfo<StudyCase>& study) {
      std::string name = study.param.name;
      std::replace(name.begin(), name.end(), '-', '_');
      return name;
    });

}  // namespace
}  // namespace wl
