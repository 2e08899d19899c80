// The experiment driver (experiments/driver/sweep.h, work_precision.h,
// stability.h): the error metric, the reference cache, the stability
// bisection, the stretch multiplier and tiny end-to-end sweeps on a 5×5 cloth.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <random>
#include <sstream>

#include "experiments/driver/stability.h"
#include "experiments/driver/sweep.h"
#include "experiments/driver/work_precision.h"
#include "models/fem/fem_material.h"
#include "tests/output/output_test_util.h"

namespace wl {
namespace {

using test::ScratchDir;

Trajectory random_trajectory(int nodes, int times, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-0.02, 0.02);
  Trajectory t;
  for (int k = 0; k < times; ++k) t.times.push_back(1e-3 * (k + 1));
  t.positions.resize(3 * nodes, times);
  for (Eigen::Index i = 0; i < t.positions.size(); ++i) t.positions.data()[i] = u(rng);
  return t;
}

// A 5×5 hanging cloth (two top corners held), 4 ms with outputs every 2 ms.
std::string tiny_scene_text(double duration = 0.004) {
  std::ostringstream s;
  s << "[cloth]\nwarps = 5\nwefts = 5\n"
    << "[pose]\nkind = \"upright\"\nheight_m = 0.02\n"
    << "[[handles]]\nnode = [0, 0]\nstiffness_N_per_m = 1.0e4\n"
    << "[[handles]]\nnode = [4, 0]\nstiffness_N_per_m = 1.0e4\n"
    << "[wind]\nvelocity_m_per_s = [0.0, 5.0, 0.0]\nair_density_kg_per_m3 = 2.0\ndrag_Ns_per_m3 = 0.5\n"
    << "[time]\nduration_s = " << duration << "\noutput_interval_s = 0.002\n";
  return s.str();
}

TEST(TrajectoryError, RunAgainstItselfIsZero) {
  const Trajectory t = random_trajectory(25, 4, 1);
  const ErrorNorms e = trajectory_error(t, t);
  EXPECT_EQ(e.rms, 0.0);
  EXPECT_EQ(e.max, 0.0);
}

TEST(TrajectoryError, UniformOffsetGivesThatOffset) {
  const Trajectory ref = random_trajectory(25, 4, 2);
  Trajectory run = ref;
  const Eigen::Vector3d d(3e-4, -4e-4, 0.0);  // ‖d‖ = 5e-4 m
  for (Eigen::Index k = 0; k < run.positions.cols(); ++k)
    for (int n = 0; n < run.nodes(); ++n) run.positions.col(k).segment<3>(3 * n) += d;
  const ErrorNorms e = trajectory_error(run, ref);
  EXPECT_NEAR(e.rms, 5e-4, 1e-15);
  EXPECT_NEAR(e.max, 5e-4, 1e-15);
}

TEST(TrajectoryError, SingleNodeOffsetIsAveragedOverNodesAndTimes) {
  const int nodes = 16, times = 4;
  const Trajectory ref = random_trajectory(nodes, times, 3);
  Trajectory run = ref;
  run.positions(3 * 5 + 2, 1) += 2e-3;  // node 5, z, second output time
  const ErrorNorms e = trajectory_error(run, ref);
  EXPECT_NEAR(e.max, 2e-3, 1e-15);
  EXPECT_NEAR(e.rms, 2e-3 / std::sqrt(double(nodes * times)), 1e-15);
}

TEST(TrajectoryError, MismatchedShapesAreRejected) {
  const Trajectory a = random_trajectory(9, 3, 4);
  EXPECT_THROW(trajectory_error(a, random_trajectory(16, 3, 4)), std::invalid_argument);
  EXPECT_THROW(trajectory_error(a, random_trajectory(9, 2, 4)), std::invalid_argument);
  Trajectory shifted = a;
  shifted.times[1] += 1e-4;
  EXPECT_THROW(trajectory_error(a, shifted), std::invalid_argument);
}

TEST(OutputTimes, MultiplesOfTheIntervalUpToTheDuration) {
  Scene s;
  s.duration_s = 0.01;
  s.output_interval_s = 0.004;
  const auto t = output_times(s);
  ASSERT_EQ(t.size(), 3u);
  EXPECT_DOUBLE_EQ(t[0], 0.004);
  EXPECT_DOUBLE_EQ(t[1], 0.008);
  EXPECT_DOUBLE_EQ(t[2], 0.01);
}

TEST(ReferenceCache, HashDependsOnSceneTextModelAndOverrides) {
  ReferenceOptions o;
  const std::string text = tiny_scene_text();
  const std::string h = reference_hash(reference_key(text, "yarn", {}, o));
  EXPECT_EQ(h.size(), 16u);
  EXPECT_EQ(h, reference_hash(reference_key(text, "yarn", {}, o)));
  EXPECT_NE(h, reference_hash(reference_key(tiny_scene_text(0.006), "yarn", {}, o)));
  EXPECT_NE(h, reference_hash(reference_key(text + "# a comment\n", "yarn", {}, o)));
  EXPECT_NE(h, reference_hash(reference_key(text, "fem", {}, o)));
  EXPECT_NE(h, reference_hash(reference_key(text, "yarn", {{"duration_s", "0.002"}}, o)));
}

TEST(ReferenceCache, FileRoundTripsAndRejectsOtherKeysAndTornFiles) {
  ScratchDir dir;
  Reference r;
  r.trajectory = random_trajectory(9, 3, 5);
  r.rtol = 1e-10;
  r.atol = 1e-13;
  r.cpu_s = 1.5;
  const auto file = dir / "ref.bin";
  write_reference_file(file, "key A", r);
  Reference back;
  ASSERT_TRUE(read_reference_file(file, "key A", back));
  EXPECT_EQ(back.trajectory.times, r.trajectory.times);
  EXPECT_EQ(back.trajectory.positions, r.trajectory.positions);
  EXPECT_EQ(back.rtol, 1e-10);
  EXPECT_EQ(back.cpu_s, 1.5);
  EXPECT_FALSE(read_reference_file(file, "key B", back));
  EXPECT_FALSE(read_reference_file(dir / "missing.bin", "key A", back));
  const std::string bytes = test::read_text(file);
  std::ofstream(dir / "torn.bin", std::ios::binary) << bytes.substr(0, bytes.size() - 8);
  EXPECT_FALSE(read_reference_file(dir / "torn.bin", "key A", back));
}

TEST(ReferenceCache, SecondCallReadsTheFileAndAChangedSceneComputesAnew) {
  ScratchDir dir;
  const std::string text = tiny_scene_text(0.002);
  const Scene scene = parse_scene(text, "tiny.toml");
  ReferenceOptions o;
  o.cache_dir = dir / "reference";
  o.rtols = {1e-7};  // tolerance irrelevant here; keeps the test fast
  o.required_rtol = 1e-7;
  o.progress = false;
  const Reference first = load_or_compute_reference(scene, text, "fem", {}, o);
  EXPECT_FALSE(first.from_cache);
  EXPECT_TRUE(std::filesystem::exists(first.file));
  EXPECT_EQ(first.file, o.cache_dir / (first.hash + ".bin"));
  EXPECT_EQ(first.rtol, 1e-7);
  ASSERT_EQ(first.attempts.size(), 1u);
  const Reference second = load_or_compute_reference(scene, text, "fem", {}, o);
  EXPECT_TRUE(second.from_cache);
  EXPECT_TRUE(second.attempts.empty());
  EXPECT_EQ(second.trajectory.positions, first.trajectory.positions);
  EXPECT_EQ(second.rtol, first.rtol);

  const std::string other_text = text + "# changed\n";
  const Reference third = load_or_compute_reference(parse_scene(other_text, "tiny.toml"), other_text, "fem", {}, o);
  EXPECT_FALSE(third.from_cache);
  EXPECT_NE(third.hash, first.hash);
  EXPECT_EQ(test::count_entries(o.cache_dir), 2);
}

TEST(ReferenceCache, NoConvergingToleranceIsAnError) {
  ScratchDir dir;
  const std::string text = tiny_scene_text(0.002);
  ReferenceOptions o;
  o.cache_dir = dir / "reference";
  o.max_steps = 3;  // far too few for 2 ms: every attempt ends with max_steps
  o.rtols = {1e-9, 1e-8};
  o.progress = false;
  try {
    load_or_compute_reference(parse_scene(text, "tiny.toml"), text, "fem", {}, o);
    FAIL() << "expected an error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("rtol=1e-09"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("rtol=1e-08: max_steps"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(std::filesystem::exists(o.cache_dir) && test::count_entries(o.cache_dir) > 0);
}

StabilityProbe synthetic(double dt, double threshold) {
  StabilityProbe p;
  p.bounded = dt < threshold;
  if (!p.bounded) p.result = {Outcome::diverged, "runaway state"};
  return p;
}

TEST(StabilityBisection, BracketsTheThresholdOfAMonotonePredicate) {
  const double threshold = 3.7e-4;
  const StabilityLimit lim = find_stability_limit([&](double dt) { return synthetic(dt, threshold); }, 1e-6, 1e-2, 8);
  ASSERT_TRUE(std::isfinite(lim.largest_stable_dt));
  ASSERT_TRUE(std::isfinite(lim.smallest_unstable_dt));
  EXPECT_LT(lim.largest_stable_dt, threshold);
  EXPECT_GE(lim.smallest_unstable_dt, threshold);
  // 8 bisections of a factor 1e4 in log space leave a factor 1e4^(1/256).
  EXPECT_NEAR(std::log(lim.smallest_unstable_dt / lim.largest_stable_dt), std::log(1e4) / 256, 1e-9);
  EXPECT_EQ(lim.probes.size(), 9u);  // dt_max + 8 midpoints
  EXPECT_EQ(lim.failure.result.outcome, Outcome::diverged);
}

TEST(StabilityBisection, AlwaysBoundedStopsAtDtMax) {
  const StabilityLimit lim = find_stability_limit([](double dt) { return synthetic(dt, 1.0); }, 1e-6, 1e-2, 8);
  EXPECT_EQ(lim.largest_stable_dt, 1e-2);
  EXPECT_TRUE(std::isnan(lim.smallest_unstable_dt));
  EXPECT_EQ(lim.probes.size(), 1u);
}

TEST(StabilityBisection, NeverBoundedEndsAtDtMin) {
  const StabilityLimit lim = find_stability_limit([](double dt) { return synthetic(dt, 1e-9); }, 1e-6, 1e-2, 8);
  EXPECT_TRUE(std::isnan(lim.largest_stable_dt));
  EXPECT_EQ(lim.smallest_unstable_dt, 1e-6);
  EXPECT_EQ(lim.probes.size(), 10u);  // dt_max, 8 midpoints, dt_min
}

TEST(StabilityBisection, BadBoundsAreRejected) {
  auto p = [](double dt) { return synthetic(dt, 1.0); };
  EXPECT_THROW(find_stability_limit(p, 0.0, 1e-2, 8), std::invalid_argument);
  EXPECT_THROW(find_stability_limit(p, 1e-2, 1e-3, 8), std::invalid_argument);
}

TEST(ScaleStretch, ScalesYarnModuliAndFemStretchOnly) {
  const Scene s = parse_scene(tiny_scene_text(), "tiny.toml");
  const Scene x = scale_stretch(s, 100.0);
  for (const auto& [name, t] : s.yarn_types) {
    EXPECT_DOUBLE_EQ(x.yarn_types.at(name).stretch_modulus_Pa, 100.0 * t.stretch_modulus_Pa);
    EXPECT_DOUBLE_EQ(x.yarn_types.at(name).bending_modulus_Pa, t.bending_modulus_Pa);
  }
  const FemMaterial a = fem_material(s), b = fem_material(x);
  EXPECT_DOUBLE_EQ(b.warp_stretch_N_per_m, 100.0 * a.warp_stretch_N_per_m);
  EXPECT_DOUBLE_EQ(b.weft_stretch_N_per_m, 100.0 * a.weft_stretch_N_per_m);
  EXPECT_DOUBLE_EQ(b.shear_N_per_m, a.shear_N_per_m);
  EXPECT_DOUBLE_EQ(b.warp_bending_N_m, a.warp_bending_N_m);
  EXPECT_DOUBLE_EQ(b.areal_density_kg_per_m2, a.areal_density_kg_per_m2);
}

// Every CSV line as cells (no quoted commas in the columns read here).
std::vector<std::vector<std::string>> read_csv(const std::filesystem::path& p) {
  std::vector<std::vector<std::string>> rows;
  std::ifstream in(p);
  std::string line;
  while (std::getline(in, line)) {
    std::vector<std::string> cells;
    std::stringstream ss(line);
    std::string c;
    while (std::getline(ss, c, ',')) cells.push_back(c);
    rows.push_back(cells);
  }
  return rows;
}

TEST(WorkPrecisionSweep, TinySceneTwoIntegratorsEndToEnd) {
  ScratchDir dir;
  WorkPrecisionConfig c;
  c.scene_path = "tiny.toml";
  c.scene_text = tiny_scene_text();
  c.scene = parse_scene(c.scene_text, "tiny.toml");
  c.models = {"fem"};
  c.integrators = {"be-linear", "ida"};
  c.rtols = {1e-4, 1e-6};
  c.dt_max = 2e-3;
  c.dt_min = 5e-4;
  c.reference.cache_dir = dir / "reference";
  c.reference.rtols = {1e-9};
  c.reference.progress = false;
  c.out_dir = dir / "wp";
  c.progress = false;
  const WorkPrecisionResult r = run_work_precision(c);
  ASSERT_EQ(r.rows.size(), 5u);  // dt 2, 1, 0.5 ms; rtol 1e-4, 1e-6
  for (const auto& row : r.rows) {
    ASSERT_EQ(row.run.result.outcome, Outcome::ok) << row.integrator << ": " << row.run.result.message;
    EXPECT_GT(row.error.rms, 0.0);
    EXPECT_GE(row.error.max, row.error.rms);
    EXPECT_GT(row.run.cpu_s, 0.0);
  }
  // Backward Euler is first order: halving dt roughly halves the error.
  for (int k = 0; k < 2; ++k) {
    const double ratio = r.rows[k].error.rms / r.rows[k + 1].error.rms;
    EXPECT_GT(ratio, 1.6) << "dt " << r.rows[k].dt;
    EXPECT_LT(ratio, 2.5) << "dt " << r.rows[k].dt;
  }
  // IDA at rtol 1e-6 is far more accurate than backward Euler at 0.5 ms and
  // at least as accurate as at rtol 1e-4.
  EXPECT_LT(r.rows[4].error.rms, 1e-2 * r.rows[2].error.rms);
  EXPECT_LE(r.rows[4].error.rms, r.rows[3].error.rms);
  ASSERT_TRUE(r.references.count("fem"));
  EXPECT_EQ(r.references.at("fem").rtol, 1e-9);

  const auto csv = read_csv(c.out_dir / "work_precision.csv");
  ASSERT_EQ(csv.size(), 6u);
  EXPECT_EQ(csv[0], kWorkPrecisionColumns);
  EXPECT_EQ(csv[1][1], "be-linear");
  EXPECT_EQ(csv[5][1], "ida");
  const std::string json = test::read_text(c.out_dir / "work_precision.json");
  for (const char* key : {"\"git_revision\"", "\"machine\"", "\"text\"", "\"references\"", "\"rtols\""})
    EXPECT_NE(json.find(key), std::string::npos) << key;
  EXPECT_NE(json.find(r.references.at("fem").hash), std::string::npos);

  // The chart script reads these files.
  ASSERT_TRUE(test::python_with("numpy, matplotlib"));
  const std::string script = std::string(WEAVELAB_SOURCE_DIR) + "/experiments/plot_work_precision.py";
  const auto out = test::run_command(std::string(test::python()) + " " + test::shell_quote(script) + " " +
                                     test::shell_quote(c.out_dir.string()));
  ASSERT_EQ(out.exit_code, 0) << out.output;
  EXPECT_TRUE(std::filesystem::exists(c.out_dir / "work_precision.png"));
  EXPECT_TRUE(std::filesystem::exists(c.out_dir / "work_precision.svg"));
  EXPECT_NE(test::read_text(c.out_dir / "slopes.csv").find("fem,be-linear,fixed,3,"), std::string::npos);
}

TEST(StabilitySweep, TinySceneExplicitLimitBelowImplicit) {
  ScratchDir dir;
  StabilityConfig c;
  c.scene_path = "tiny.toml";
  c.scene_text = tiny_scene_text();
  c.scene = parse_scene(c.scene_text, "tiny.toml");
  c.models = {"fem"};
  c.integrators = {"be-linear", "symplectic"};
  c.multipliers = {1.0};
  c.dt_min = 1e-6;
  c.dt_max = 1e-3;
  c.bisections = 4;
  c.out_dir = dir / "st";
  c.progress = false;
  const StabilityResult r = run_stability(c);
  ASSERT_EQ(r.rows.size(), 2u);
  const StabilityLimit& be = r.rows[0].limit;
  const StabilityLimit& se = r.rows[1].limit;
  EXPECT_EQ(be.largest_stable_dt, 1e-3);  // backward Euler: bounded at the largest step
  ASSERT_TRUE(std::isfinite(se.smallest_unstable_dt));
  EXPECT_LT(se.smallest_unstable_dt, 1e-3);  // symplectic Euler has a step limit
  EXPECT_FALSE(se.failure.bounded);
  const auto csv = read_csv(c.out_dir / "stability.csv");
  ASSERT_EQ(csv.size(), 3u);
  EXPECT_EQ(csv[2][1], "symplectic");
  EXPECT_TRUE(std::filesystem::exists(c.out_dir / "stability_probes.csv"));
  const std::string json = test::read_text(c.out_dir / "stability.json");
  EXPECT_NE(json.find("\"git_revision\""), std::string::npos);
  EXPECT_NE(json.find("\"speed_bound_m_per_s\""), std::string::npos);

  ASSERT_TRUE(test::python_with("numpy, matplotlib"));
  const std::string script = std::string(WEAVELAB_SOURCE_DIR) + "/experiments/plot_stability.py";
  const auto out = test::run_command(std::string(test::python()) + " " + test::shell_quote(script) + " " +
                                     test::shell_quote(c.out_dir.string()));
  ASSERT_EQ(out.exit_code, 0) << out.output;
  EXPECT_TRUE(std::filesystem::exists(c.out_dir / "stability.png"));
  EXPECT_TRUE(std::filesystem::exists(c.out_dir / "stability.svg"));
}

}  // namespace
}  // namespace wl
