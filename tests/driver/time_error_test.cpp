// The global time error estimate (driver/time_error.h) against
// true errors: a closed-form motion, and a 6×6 cloth in wind against a
// converged reference.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "driver/accuracy.h"
#include "driver/time_error.h"
#include "driver/trajectory_error.h"
#include "tests/support/test_scenes.h"

namespace wl {
namespace {

struct EstimatedRun {
  RecordedRun run;
  TimeErrorEstimate estimate;
};

EstimatedRun run_and_estimate(const Scene& scene, const std::string& integrator, const IntegratorOptions& opt) {
  RecordOptions record;
  record.step_ends = true;
  EstimatedRun r{run_recorded(scene, "yarn", integrator, opt, record), {}};
  EXPECT_EQ(r.run.result.outcome, Outcome::ok) << r.run.result.message;
  r.estimate = estimate_time_error(scene, "yarn", integrator, opt, r.run);
  EXPECT_TRUE(r.estimate.ok()) << r.estimate.second_run.message;
  return r;
}

IntegratorOptions fixed(double dt) {
  IntegratorOptions o;
  o.dt = dt;
  return o;
}

// A 6×6 cloth in wind, 40 ms, default physics with sliding frozen.
Scene small_cloth() {
  Scene s = parse_scene(test::hanging_cloth_toml(6, 0.04), "cloth.toml");
  s.sliding = false;
  return s;
}

// Its converged motion: IDA at rtol 1e-10 (computed once per test process).
const RecordedRun& small_cloth_reference() {
  static const RecordedRun reference = [] {
    IntegratorOptions tight;
    tight.adaptive = true;
    tight.rtol = 1e-10;
    tight.atol = 1e-13;
    tight.dt = 1e-6;
    return run_recorded(small_cloth(), "yarn", "ida", tight);
  }();
  return reference;
}

// Free fall (every force but gravity off): backward Euler's error is exactly
// ½ g h t at every node, linear in h, so Richardson's rule recovers it to
// round-off; SDIRK2 integrates the parabola exactly.
TEST(TimeErrorEstimate, FreeFallIsRecoveredExactly) {
  Scene s = parse_scene(
      "[cloth]\nwarps = 3\nwefts = 3\nsliding = false\n[pose]\nkind = \"flat\"\n[gravity]\n"
      "acceleration_m_per_s2 = [0.0, 0.0, -9.8]\n[time]\nduration_s = 0.05\ndt_s = 0.001\noutput_interval_s = 0.01\n"
      "[terms]\nstretch = false\nbending = false\nshear = false\nparallel_contact = false\nfriction = false\n"
      "wind = false\nhandles = false\n",
      "fall.toml");
  const EstimatedRun be = run_and_estimate(s, "be-linear", fixed(1e-3));
  EXPECT_EQ(be.estimate.method, "richardson");
  ASSERT_EQ(be.estimate.rms.size(), 5u);
  for (size_t k = 0; k < be.estimate.rms.size(); ++k) {
    const double exact = 0.5 * 9.8 * 1e-3 * be.estimate.times[k];
    EXPECT_NEAR(be.estimate.rms[k], exact, 1e-9 * exact) << "frame " << k;
    EXPECT_NEAR(be.estimate.max[k], exact, 1e-9 * exact) << "frame " << k;
  }
  const EstimatedRun sd = run_and_estimate(s, "sdirk2", fixed(1e-3));
  EXPECT_LT(sd.estimate.max_max, 1e-12);
}

// Each estimate on the small cloth against its distance to the IDA run. Per frame the
// estimate is within a factor 2 of the true error wherever the true error is
// well above the reference's own (1e-9 m).
TEST(TimeErrorEstimate, WithinAFactorTwoOnASmallCloth) {
  const Scene s = small_cloth();
  const RecordedRun& reference = small_cloth_reference();
  ASSERT_EQ(reference.result.outcome, Outcome::ok) << reference.result.message;
  IntegratorOptions adaptive;
  adaptive.adaptive = true;
  adaptive.rtol = 1e-5;
  adaptive.atol = 1e-8;
  const std::vector<std::pair<std::string, IntegratorOptions>> runs = {
      {"be-linear", fixed(1e-3)}, {"be-linear", fixed(5e-4)}, {"sdirk2", fixed(1e-3)}, {"sdirk2", adaptive}};
  for (const auto& [name, opt] : runs) {
    const EstimatedRun r = run_and_estimate(s, name, opt);
    std::vector<double> rms, max;
    frame_distances(r.run.trajectory, reference.trajectory, 1.0, rms, max);
    double worst = 1.0;
    for (size_t k = 0; k < rms.size(); ++k) {
      if (rms[k] < 1e-8) continue;
      const double ratio = r.estimate.rms[k] / rms[k];
      worst = std::max(worst, std::max(ratio, 1.0 / ratio));
      EXPECT_GT(ratio, 0.5) << name << " frame " << k;
      EXPECT_LT(ratio, 2.0) << name << " frame " << k;
    }
    std::printf("[ time error ] %-9s %s: estimated %.3e m, true %.3e m (mean RMS), worst frame ratio %.2f\n",
                name.c_str(), opt.adaptive ? "rtol 1e-5" : (opt.dt == 1e-3 ? "dt 1 ms" : "dt 0.5 ms"),
                r.estimate.mean_rms, trajectory_error(r.run.trajectory, reference.trajectory).rms, worst);
  }
}

// --accuracy on the small cloth: the chosen run's estimate meets the target,
// and so does its distance to the IDA run.
TEST(AccuracyChoice, ReachesItsTargetOnASmallCloth) {
  const Scene s = small_cloth();
  const RecordedRun& reference = small_cloth_reference();
  ASSERT_EQ(reference.result.outcome, Outcome::ok) << reference.result.message;
  for (double target : {1e-5, 1e-7}) {
    const AccuracyChoice c = choose_for_accuracy(s, "yarn", target, false);
    ASSERT_TRUE(c.reached) << "target " << target;
    EXPECT_LE(c.estimate.mean_rms, target);
    IntegratorOptions opt;
    opt.adaptive = true;
    opt.rtol = c.rtol;
    opt.atol = c.atol;
    opt.dt = s.dt_s;
    const RecordedRun run = run_recorded(s, "yarn", c.integrator, opt);
    std::vector<double> rms, max;
    frame_distances(run.trajectory, reference.trajectory, 1.0, rms, max);
    double mean = 0.0;
    for (double r : rms) mean += r / double(rms.size());
    std::printf("[ accuracy ] target %.0e m: %zu trials, rtol %.2e, estimated %.3e m, true %.3e m\n", target,
                c.trials.size(), c.rtol, c.estimate.mean_rms, mean);
    EXPECT_LE(mean, target);
  }
}

// The verdict beside a distance: resolved only when both time errors are below a tenth of it.
TEST(TimeErrorEstimate, BudgetVerdict) {
  TimeErrorEstimate a, b;
  a.mean_rms = 1e-5;
  b.mean_rms = 5e-5;
  EXPECT_EQ(error_budget_verdict(1e-3, a, b), "resolved");
  b.mean_rms = 2e-4;
  EXPECT_EQ(error_budget_verdict(1e-3, a, b), "time error above a tenth of the distance");
  a.mean_rms = 2e-3;
  EXPECT_EQ(error_budget_verdict(1e-3, a, b), "time error exceeds the distance");
  b.second_run = {Outcome::diverged, "failed"};
  EXPECT_EQ(error_budget_verdict(1e-3, a, b), "time error unknown");
}

// An error-controlled library method is estimated by a rerun at rtol/100.
TEST(TimeErrorEstimate, LibraryMethodsUseATighterTolerance) {
  Scene s = parse_scene(test::hanging_cloth_toml(4, 0.02), "cloth.toml");
  s.sliding = false;
  IntegratorOptions opt;
  opt.adaptive = true;
  opt.rtol = 1e-5;
  opt.atol = 1e-8;
  const EstimatedRun r = run_and_estimate(s, "ida", opt);
  EXPECT_EQ(r.estimate.method, "tolerance");
  EXPECT_GT(r.estimate.mean_rms, 0.0);
  EXPECT_LT(r.estimate.mean_rms, 1e-4);
}

}  // namespace
}  // namespace wl
