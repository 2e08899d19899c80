// The work-precision experiment: per model and integrator a
// ladder of tolerances (error-controlled methods) or step sizes (fixed-step
// methods), each run's error against the cached IDA reference
// (driver/reference_cache.h) and its CPU time. Writes into out_dir:
//   work_precision.csv   one row per run (columns: see kWorkPrecisionColumns)
//   work_precision.json  scene file and text, parameters, references, git revision, machine, timing
// with progress on stderr.
#pragma once
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "driver/reference_cache.h"
#include "driver/trajectory_error.h"
#include "models/scene/scene.h"

namespace wl {

struct WorkPrecisionConfig {
  std::filesystem::path scene_path;              // for the metadata; the text below is what counts
  std::string scene_text;                        // the scene file's text (reference hash, metadata)
  Scene scene;                                   // parsed, with the overrides applied
  std::map<std::string, std::string> overrides;  // e.g. duration_s (part of the reference hash)
  std::vector<std::string> models = {"yarn", "fem"};
  std::vector<std::string> integrators;  // default: integrator_names()
  // Error-controlled methods: rtol ladder, atol = rtol × atol_per_rtol, initial step hint.
  std::vector<double> rtols = {1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8};
  double atol_per_rtol = 1e-3;
  double adaptive_initial_dt = 1e-5;
  // Fixed-step methods: dt = dt_max / 2^k while dt ≥ dt_min.
  double dt_max = 4e-3, dt_min = 4e-3 / 256;
  // A ladder stops when its next rung is predicted to exceed this CPU time
  // (last rung's CPU × the growth between the last two rungs, at least 1.5).
  // A run is first tried with a step limit (pilot_steps for a ladder's first
  // rung, then 4 × the previous rung's steps, at least pilot_steps). When it
  // hits the limit, its CPU time to the end is extrapolated from the time
  // reached: within the budget it is rerun without a limit; otherwise the
  // limit grows ×10 while such a pilot is predicted (CPU per step × steps) to
  // stay within the budget, else the run is recorded as "over_budget" and the
  // ladder stops. Fixed-step ladders also stop when the next rung is predicted
  // to exceed the budget (last rung's CPU × the growth between the last two).
  double run_budget_cpu_s = 30.0;
  long pilot_steps = 20;
  // A run whose max node speed exceeds this is "diverged" (no error is
  // computed for it): physical speeds in the hanging-cloth scenes stay below
  // 1 m/s, an unstable fixed-step run passes this within a few steps [m/s].
  double speed_bound = 10.0;
  ReferenceOptions reference;
  std::filesystem::path out_dir = "results/work_precision";
  bool progress = true;
};

struct WorkPrecisionRow {
  std::string model, integrator, mode;  // mode: "adaptive" | "fixed"
  double rtol = 0, atol = 0, dt = 0;    // rtol/atol for adaptive, dt for fixed (NaN when not used)
  RecordedRun run;
  ErrorNorms error;              // NaN when the run did not end ok
  bool over_budget = false;      // stopped at the pilot step limit (see run_budget_cpu_s)
  double predicted_cpu_s = 0.0;  // extrapolated full-run CPU time when over_budget
  std::string outcome() const { return over_budget ? "over_budget" : to_string(run.result.outcome); }
};

struct WorkPrecisionResult {
  std::vector<WorkPrecisionRow> rows;
  std::map<std::string, Reference> references;  // by model
  std::vector<std::string> notes;               // ladder stops, skipped pairs
  double wall_s = 0.0;
};

extern const std::vector<std::string> kWorkPrecisionColumns;

// Runs the experiment and writes the CSV and JSON (atomically). Throws
// std::invalid_argument for an unknown model/integrator name (before any run)
// and std::runtime_error when a reference cannot be computed. A SIGINT or SIGTERM
// ends the run under way at its step: the files with the runs complete so far and
// outcome interrupted (driver/interrupted_record.h), then Interrupted.
WorkPrecisionResult run_work_precision(const WorkPrecisionConfig& config);

}  // namespace wl
