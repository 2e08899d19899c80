// The fidelity ladder (docs/design.md §7.5) on 5×5 cloths of 50 ms: the
// reference and its aliases measure zero, a term that does nothing measures at
// round-off, a simplification that matters does not; the time rungs measure
// their own time error against a controlled reference; a time error above the
// tolerance is not within it; the plan refuses bad input; a ladder split into
// jobs over a reference file gives the rows of one run bit for bit.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "driver/fidelity.h"
#include "driver/fidelity_reference.h"
#include "driver/recorded_run.h"
#include "models/model_factory.h"

namespace wl {
namespace {

namespace fs = std::filesystem;

constexpr const char* kTime = "[time]\nduration_s = 0.05\ndt_s = 0.001\noutput_interval_s = 0.01\n";

// No pins, handles or wind: the cloth falls freely and rigidly, so no crossing
// slides and friction (built: sliding is on) exerts no force.
std::string free_fall() { return std::string("[cloth]\nwarps = 5\nwefts = 5\n") + kTime; }

// Held at two top corners in the wind, friction off: the yarns slide freely.
std::string sliding_in_wind() {
  return std::string(
             "[cloth]\nwarps = 5\nwefts = 5\n[[handles]]\nnode = [0, 0]\n[[handles]]\nnode = [4, 0]\n"
             "[wind]\nvelocity_m_per_s = [0.0, 5.0, 0.0]\nair_density_kg_per_m3 = 2.0\ndrag_Ns_per_m3 = 0.5\n"
             "[terms]\nfriction = false\n") +
         kTime;
}

class Fidelity : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("weavelab_fidelity_" + std::to_string(::getpid()) + "_" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  FidelityConfig config(const std::string& scene_text, std::vector<std::string> variants) {
    FidelityConfig c;
    c.scene_path = "test.toml";
    c.scene = parse_scene(scene_text, "test.toml");
    c.variants = std::move(variants);
    c.out_dir = dir_;
    c.progress = false;
    c.time_steps.scene = true;  // the model rungs at the scene's step, as written
    c.error_estimate = false;
    return c;
  }
  const FidelityRow& row(const FidelityResult& r, const std::string& name) {
    for (const FidelityRow& x : r.rows)
      if (x.variant == name) return x;
    throw std::runtime_error("no row " + name);
  }
  fs::path dir_;
};

TEST_F(Fidelity, ReferenceAndItsAliasMeasureZero) {
  // Friction is off in this scene, so no_friction is the full model under another name.
  const FidelityConfig c = config(sliding_in_wind(), {"no_friction"});
  const FidelityPlan p = plan_fidelity(c);
  ASSERT_EQ(p.variants.size(), 1u);
  EXPECT_FALSE(p.variants[0].variant.same_as_full.empty());
  const FidelityResult r = run_fidelity(c, p);
  ASSERT_EQ(r.rows.size(), 2u);
  for (const FidelityRow& x : r.rows) {
    SCOPED_TRACE(x.variant);
    EXPECT_EQ(x.outcome, "ok");
    EXPECT_EQ(x.compared_fraction, 1.0);
    EXPECT_EQ(x.rms_m, 0.0);  // assembly is bitwise reproducible (docs/design.md §3.3)
    EXPECT_EQ(x.max_m, 0.0);
    EXPECT_EQ(x.energy_diff_J, 0.0);
  }
  EXPECT_TRUE(fs::exists(dir_ / "fidelity.csv"));
  EXPECT_TRUE(fs::exists(dir_ / "fidelity.json"));
}

TEST_F(Fidelity, FrictionWhereNothingSlidesChangesNothing) {
  const FidelityConfig c = config(free_fall(), {"no_friction"});
  const FidelityPlan p = plan_fidelity(c);
  ASSERT_EQ(p.variants.size(), 1u);
  EXPECT_TRUE(p.variants[0].variant.same_as_full.empty());  // friction is built in the reference
  const FidelityResult r = run_fidelity(c, p);
  const FidelityRow& x = row(r, "no_friction");
  EXPECT_EQ(x.outcome, "ok");
  // Round-off on a 4 mm cloth that falls 12 mm: far below any physical effect.
  EXPECT_LT(x.max_m, 1e-12);
  EXPECT_GT(row(r, "full").steps, 0);
}

TEST_F(Fidelity, FrozenSlidingWhereYarnsSlideMatters) {
  const FidelityConfig c = config(sliding_in_wind(), {"frozen_sliding"});
  // The reference's crossings do slide: their material coordinates leave the rest grid.
  auto u_of = [](const Frame& f) {
    for (const DataArray& a : f.point_data)
      if (a.name == "u") return a.values;
    throw std::runtime_error("no u");
  };
  auto model = make_model(c.scene, "yarn");
  const std::vector<double> rest = u_of(model->frame(0.0, model->initial_q(), model->initial_v()));
  double slid = 0;
  RecordOptions rec;
  rec.on_frame = [&](const Frame& f) {
    const std::vector<double> u = u_of(f);
    for (size_t n = 0; n < u.size(); ++n) slid = std::max(slid, std::abs(u[n] - rest[n]));
  };
  IntegratorOptions o;
  o.dt = c.scene.dt_s;
  ASSERT_EQ(run_recorded(c.scene, "yarn", c.scene.integrator, o, rec).result.outcome, Outcome::ok);
  ASSERT_GT(slid, 1e-6);
  const FidelityResult r = run_fidelity(c, plan_fidelity(c));
  const FidelityRow& x = row(r, "frozen_sliding");
  EXPECT_EQ(x.outcome, "ok");
  EXPECT_LT(x.dofs, row(r, "full").dofs);
  EXPECT_GT(x.worst_frame_rms_m, 1e-6);  // 10⁶ × the round-off level of the test above
}

TEST_F(Fidelity, ContinuumIsMeasuredAtTheCrossingsMaterialPoints) {
  // Free fall is rigid, so the continuum's surface passes through every crossing.
  const FidelityConfig c = config(free_fall(), {"fem_first_guess"});
  const FidelityResult r = run_fidelity(c, plan_fidelity(c));
  const FidelityRow& x = row(r, "fem_first_guess");
  EXPECT_EQ(x.model, "fem");
  EXPECT_EQ(x.compared_fraction, 1.0);
  EXPECT_LT(x.max_m, 1e-12);
}

TEST_F(Fidelity, ALadderSplitIntoJobsGivesTheRowsOfOneRunBitForBit) {
  // One process: the reference and both rungs (a yarn rung and a continuum rung).
  FidelityConfig whole = config(sliding_in_wind(), {"frozen_sliding", "fem_first_guess"});
  const FidelityResult serial = run_fidelity(whole, plan_fidelity(whole));
  ASSERT_EQ(serial.rows.size(), 3u);

  // Jobs: the reference into a file, then each rung in its own folder against it.
  FidelityConfig reference = config(sliding_in_wind(), {});
  reference.out_dir = dir_ / "reference";
  reference.reference_only = true;
  const FidelityResult ref = run_fidelity(reference, plan_fidelity(reference));
  ASSERT_EQ(ref.rows.size(), 1u);
  ASSERT_TRUE(fs::exists(dir_ / "reference" / "reference.bin"));
  for (size_t i = 1; i < serial.rows.size(); ++i) {
    const FidelityRow& a = serial.rows[i];
    SCOPED_TRACE(a.variant);
    FidelityConfig rung = config(sliding_in_wind(), {a.variant});
    rung.out_dir = dir_ / a.variant;
    rung.reference_from = dir_ / "reference";
    const FidelityResult job = run_fidelity(rung, plan_fidelity(rung));
    ASSERT_EQ(job.rows.size(), 2u);
    EXPECT_EQ(job.rows[0].steps, ref.rows[0].steps);  // the reference row travels with the file
    const FidelityRow& b = job.rows[1];
    EXPECT_EQ(b.variant, a.variant);
    EXPECT_EQ(b.outcome, "ok");
    EXPECT_EQ(b.steps, a.steps);
    EXPECT_EQ(b.compared_fraction, a.compared_fraction);
    // bitwise: the file holds the reference's doubles as they were
    EXPECT_EQ(b.rms_m, a.rms_m);
    EXPECT_EQ(b.worst_frame_rms_m, a.worst_frame_rms_m);
    EXPECT_EQ(b.max_m, a.max_m);
    EXPECT_EQ(b.energy_diff_J, a.energy_diff_J);
    EXPECT_GT(b.worst_frame_rms_m, 1e-6);  // a rung that differs, so equality means something
  }
}

TEST_F(Fidelity, AReferenceFileOfAnotherSceneOrMissingIsRefused) {
  FidelityConfig reference = config(sliding_in_wind(), {});
  reference.out_dir = dir_ / "reference";
  reference.reference_only = true;
  run_fidelity(reference, plan_fidelity(reference));
  auto refused = [&](const FidelityConfig& c, const std::string& expected) {
    try {
      read_fidelity_reference(*c.reference_from, fidelity_reference_key(c));
      ADD_FAILURE() << "accepted; expected " << expected;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(expected), std::string::npos) << e.what();
    }
  };
  FidelityConfig other = config(free_fall(), {"frozen_sliding"});
  other.reference_from = dir_ / "reference";
  refused(other, "written for another scene");
  FidelityConfig same = config(sliding_in_wind(), {"frozen_sliding"});
  same.time_steps.scene = false;  // another resolution: other reference frames
  same.reference_from = dir_ / "reference";
  refused(same, "written for another scene");
  same.reference_from = dir_ / "nowhere";
  refused(same, "cannot be read");
}

// A file of the right key whose frames are not the scene's reference (damaged,
// or written by other code): refused naming what differs, before any rung runs.
TEST_F(Fidelity, AReferenceFileWhoseFramesAreNotTheScenesIsRefused) {
  FidelityConfig reference = config(sliding_in_wind(), {});
  reference.out_dir = dir_ / "reference";
  reference.reference_only = true;
  run_fidelity(reference, plan_fidelity(reference));
  const std::string key = fidelity_reference_key(reference);
  const FidelityReference good = read_fidelity_reference(dir_ / "reference", key);
  ASSERT_EQ(good.frames.x.size(), 5u);  // 50 ms, a frame every 10 ms
  ASSERT_EQ(good.frames.crossings(), 25);
  ASSERT_EQ(good.frames.times.back(), 0.05);
  auto refused = [&](const FidelityReference& tampered, const std::string& expected) {
    write_fidelity_reference(dir_ / "tampered", key, tampered);
    FidelityConfig rung = config(sliding_in_wind(), {"frozen_sliding"});
    rung.out_dir = dir_ / "rung";
    rung.reference_from = dir_ / "tampered";
    try {
      run_fidelity(rung, plan_fidelity(rung));
      ADD_FAILURE() << "accepted; expected " << expected;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find((dir_ / "tampered" / "reference.bin").string() + ": " + expected),
                std::string::npos)
          << e.what();
    }
    EXPECT_FALSE(fs::exists(dir_ / "rung" / "fidelity.csv"));
  };
  FidelityReference four = good;  // 4 crossings per frame
  for (FramePoints& x : four.frames.x) x = FramePoints(x.topRows(4));
  for (auto& uv : four.frames.uv) uv.resize(4);
  refused(four, "holds 5 frames of 4 compared points, the scene's reference has 5 frames (its output times) of 25");
  FidelityReference short_one = good;  // one frame short
  short_one.frames.times.pop_back();
  short_one.frames.x.pop_back();
  short_one.frames.uv.pop_back();
  short_one.frames.energy_change.pop_back();
  refused(short_one, "holds 4 frames of 25 compared points, the scene's reference has 5 frames");
  FidelityReference shifted = good;  // frames at other times
  shifted.frames.times[2] = 0.025;
  refused(shifted, "frame 2 is at t = 0.025 s, the scene's output time is 0.03 s");
  FidelityReference nan = good;
  nan.frames.x[3](7, 1) = std::nan("");
  refused(nan, "frame 3 holds a value that is not finite");
}

TEST_F(Fidelity, DefaultLadderLeavesOutWhatTheSceneCannotHave) {
  // 7×7 held at (0,0) and (6,0): stride 4 misses the handles; no calibrated parameters.
  const std::string scene = "[cloth]\nwarps = 7\nwefts = 7\n[[handles]]\nnode = [0, 0]\n[[handles]]\nnode = [6, 0]\n";
  const FidelityPlan p = plan_fidelity(config(scene, {}));
  std::vector<std::string> run, out;
  for (const auto& v : p.variants) run.push_back(v.name);
  for (const auto& [name, why] : p.left_out) out.push_back(name);
  EXPECT_EQ(run, (std::vector<std::string>{"no_friction", "no_parallel_contact", "linear_shear", "frozen_sliding",
                                           "fem_first_guess", "half_step", "quarter_step", "sdirk2_rtol_1e-3"}));
  EXPECT_EQ(out, (std::vector<std::string>{"fem_s1", "fem_s2", "fem_s3", "fem_s4", "scene_step"}));
  EXPECT_DOUBLE_EQ(p.cloth_size_m, 6e-3);
  EXPECT_DOUBLE_EQ(p.tolerance_m, 6e-5);  // 1 % of the cloth size
}

TEST_F(Fidelity, PlanRefusesBadInput) {
  const std::string scene = free_fall();
  auto refused = [&](FidelityConfig c, const std::string& fragment) {
    try {
      (void)plan_fidelity(c);
      ADD_FAILURE() << "accepted; expected an error containing '" << fragment << "'";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
    }
  };
  refused(config(scene, {"no_friction", "coarse"}), "--variants: unknown variant 'coarse'");
  refused(config(scene, {"no_friction", "no_friction"}), "listed twice");
  refused(config(scene, {"fem_s1"}), "no calibrated parameters");
  FidelityConfig c = config(scene, {});
  c.reference = "fem_first_guess";
  refused(c, "expected a yarn-level variant");
  c.reference = "finest";
  refused(c, "--reference: unknown variant 'finest'");
  c = config(scene, {});
  c.tolerance_m = 0.0;
  refused(c, "--tolerance");
  c.tolerance_m = -1e-3;
  refused(c, "--tolerance");
  c = config(scene, {});
  c.repeats = 0;
  refused(c, "--repeats");
  EXPECT_FALSE(fs::exists(dir_));
}

TEST_F(Fidelity, TimeRungsMeasureTheirStepAgainstAControlledReference) {
  FidelityConfig c = config(sliding_in_wind(), {"scene_step", "half_step", "quarter_step"});
  c.time_steps = {false, 1e-7};  // the reference: sdirk2 at rtol 1e-7
  c.error_estimate = true;
  const FidelityResult r = run_fidelity(c, plan_fidelity(c));
  const FidelityRow& ref = row(r, "full");
  ASSERT_EQ(ref.time_error_method, "richardson");
  const double d1 = row(r, "scene_step").rms_m, d2 = row(r, "half_step").rms_m, d4 = row(r, "quarter_step").rms_m;
  SCOPED_TRACE(testing::Message() << "distances " << d1 << " " << d2 << " " << d4 << ", reference's own "
                                  << ref.time_error_mean_rms_m);
  EXPECT_LT(ref.time_error_worst_frame_rms_m, 0.02 * row(r, "quarter_step").worst_frame_rms_m);
  // backward Euler is first order: halving the step halves the distance (to ± 20 %)
  EXPECT_NEAR(d1 / d2, 2.0, 0.4);
  EXPECT_NEAR(d2 / d4, 2.0, 0.4);
  // each rung's own estimate matches its distance to the controlled reference (within 1.5×)
  for (const char* name : {"scene_step", "half_step", "quarter_step"}) {
    const FidelityRow& x = row(r, name);
    EXPECT_EQ(x.time_error_method, "richardson") << name;
    EXPECT_GT(x.time_error_worst_frame_rms_m / x.worst_frame_rms_m, 1 / 1.5) << name;
    EXPECT_LT(x.time_error_worst_frame_rms_m / x.worst_frame_rms_m, 1.5) << name;
  }
}

TEST(FidelityChoice, ATimeErrorAboveTheToleranceIsNotWithinIt) {
  auto make = [](const std::string& name, double cpu, double distance, double time_error) {
    FidelityRow r;
    r.variant = name;
    r.outcome = "ok";
    r.compared_fraction = 1;
    r.cpu_s = cpu;
    r.worst_frame_rms_m = distance;
    r.time_error_worst_frame_rms_m = time_error;
    return r;
  };
  std::vector<FidelityRow> rows{make("full", 10, 0, 1e-6), make("cheap_but_unresolved", 1, 5e-5, 2e-4),
                                make("resolved", 4, 8e-5, 1e-5), make("not_estimated", 6, 9e-5, NAN)};
  EXPECT_EQ(cheapest_within(rows, 1e-4).variant, "resolved");
  EXPECT_DOUBLE_EQ(cheapest_within(rows, 1e-4).speedup, 2.5);
  EXPECT_EQ(cheapest_within(rows, 1e-3).variant, "cheap_but_unresolved");
  rows[2].time_error_worst_frame_rms_m = 2e-4;
  EXPECT_EQ(cheapest_within(rows, 1e-4).variant, "not_estimated");
}

TEST(ParetoFront, KeepsExactlyTheUndominatedPoints) {
  // (cost, error): b dominates c; d ties a on cost with a larger error; e is the cheapest.
  const std::vector<double> cost{1.0, 2.0, 3.0, 1.0, 0.5}, error{0.5, 0.1, 0.2, 0.6, 1.0};
  EXPECT_EQ(pareto_front(cost, error), (std::vector<bool>{true, true, false, false, true}));
}

}  // namespace
}  // namespace wl
