// SIGINT and SIGTERM end the current step of whichever run `run_scene` is
// making (driver/run.h): the --error-estimate second run and each --accuracy
// trial, like the run itself, end within the step the signal arrived in and
// leave the record of an interrupted run. The signal is raised from the step
// observer at a known step of a known phase.
#include <gtest/gtest.h>

#include <csignal>
#include <filesystem>

#include "driver/accuracy.h"
#include "driver/interrupt.h"
#include "driver/run.h"
#include "tests/output/output_test_util.h"
#include "tests/support/test_scenes.h"

namespace wl {
namespace {

namespace fs = std::filesystem;

// What the observer saw: whether it raised the signal, the steps of any run after it.
struct Observed {
  bool raised = false;
  int steps_after_signal = 0;
};

// Options writing into `out` whose step observer raises `sig` at step `at` of `phase`.
RunOptions raising(const fs::path& out, const std::string& phase, int at, int sig, Observed& seen) {
  RunOptions opt;
  opt.out_dir = out;
  opt.progress = false;
  opt.on_step = [&seen, phase, at, sig, count = 0](const std::string& p, double) mutable {
    if (seen.raised) ++seen.steps_after_signal;
    else if (p == phase && ++count == at) {
      seen.raised = true;
      std::raise(sig);
    }
  };
  return opt;
}

// The record a plain interrupted run leaves: the files, and a summary saying so.
void expect_interrupted_record(const fs::path& out, const RunReport& rep, const char* signal_name) {
  EXPECT_EQ(rep.result.outcome, Outcome::interrupted) << rep.result.message;
  EXPECT_EQ(rep.result.message, std::string("interrupted by ") + signal_name);
  for (const char* file : {"run.pvd", "metrics.csv", "summary.json", "frames/run_00000.vtu"})
    EXPECT_TRUE(fs::exists(out / file)) << file;
  EXPECT_FALSE(fs::exists(out / "metrics.csv.part"));
  EXPECT_NE(test::read_text(out / "summary.json").find("\"outcome\": \"interrupted\""), std::string::npos);
}

class RunInterrupt : public ::testing::Test {
 protected:
  Scene scene(double duration_s) { return parse_scene(test::hanging_cloth_toml(5, duration_s), "cloth.toml"); }
  // The signal each test raises is forgotten after it: the tests after it run in the same process.
  void TearDown() override { clear_interrupt_signal(); }
  InterruptScope handlers_;  // records SIGINT and SIGTERM for this test, cleared first
  test::ScratchDir dir_;
};

TEST_F(RunInterrupt, TheRunItselfEndsInTheStepOfTheSignal) {
  Observed seen;
  const RunReport rep = run_scene(scene(0.05), raising(dir_ / "run", "run", 12, SIGTERM, seen));
  ASSERT_TRUE(seen.raised);
  EXPECT_EQ(seen.steps_after_signal, 0);
  EXPECT_NEAR(rep.end_time, 0.012, 1e-9);
  expect_interrupted_record(dir_ / "run", rep, "SIGTERM");
}

// Before: the second run went on to its end, and the summary said `ok`.
TEST_F(RunInterrupt, TheErrorEstimatesSecondRunEndsTheRunInterrupted) {
  Scene s = scene(0.05);
  s.error_estimate = true;
  Observed seen;
  const RunReport rep = run_scene(s, raising(dir_ / "run", "time error", 7, SIGTERM, seen));
  ASSERT_TRUE(seen.raised);
  EXPECT_EQ(seen.steps_after_signal, 0);
  expect_interrupted_record(dir_ / "run", rep, "SIGTERM");
  ASSERT_TRUE(rep.time_error.has_value());
  EXPECT_EQ(rep.time_error->second_run.outcome, Outcome::interrupted);
  EXPECT_NE(rep.summary_json.find("\"second_run_outcome\": \"interrupted\""), std::string::npos);
  EXPECT_EQ(rep.frames, 6) << "the run itself had ended: every frame is in the record";
}

// Before: the trials ignored the signal (a second one killed the process with nothing written).
TEST_F(RunInterrupt, AnAccuracyTrialEndsTheRunInterrupted) {
  Scene s = scene(0.03);
  s.accuracy_m = 1e-12;  // not reached in two trials
  Observed seen;
  const RunReport rep = run_scene(s, raising(dir_ / "run", "accuracy trial 2", 5, SIGINT, seen));
  ASSERT_TRUE(seen.raised);
  EXPECT_EQ(seen.steps_after_signal, 0);
  expect_interrupted_record(dir_ / "run", rep, "SIGINT");
  ASSERT_TRUE(rep.accuracy.has_value());
  EXPECT_EQ(rep.accuracy->verdict, "interrupted");
  EXPECT_FALSE(rep.accuracy->reached);
  ASSERT_EQ(rep.accuracy->trials.size(), 2u);
  EXPECT_EQ(rep.accuracy->trials[1].outcome, "interrupted");
  EXPECT_NE(rep.summary_json.find("\"verdict\": \"interrupted\""), std::string::npos);
}

// The search with trials in memory stops at the first step after a signal.
TEST_F(RunInterrupt, AnInMemoryAccuracySearchStopsOnASignal) {
  std::raise(SIGTERM);
  const AccuracyChoice c = choose_for_accuracy(scene(0.03), "yarn", 1e-12, false);
  EXPECT_EQ(c.verdict, "interrupted");
  ASSERT_EQ(c.trials.size(), 1u);
  EXPECT_EQ(c.note, "interrupted by SIGTERM");
}

}  // namespace
}  // namespace wl
