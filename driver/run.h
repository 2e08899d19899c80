// Runs one scene with one model and integrator, writing the frames (PVD/VTU),
// the metrics CSV and the run summary JSON into an output folder, with
// progress on stderr. A numerical failure ends the run with its outcome in the
// summary; it is not an exception.
#pragma once
#include <filesystem>
#include <functional>
#include <map>
#include <optional>
#include <string>

#include "driver/accuracy.h"
#include "driver/drape_measure.h"
#include "driver/time_error.h"
#include "integrators/integrator.h"
#include "models/scene/scene.h"

namespace wl {

struct RunOptions {
  std::string model;              // "yarn", "knit" or "fem"; empty: the scene's yarn level (yarn_level_model)
  std::filesystem::path out_dir;  // empty: a run in memory, nothing written (RunReport::summary_json only)
  bool progress = true;
  std::map<std::string, std::string> overrides;  // command-line values that replaced scene values
  // Called with every output frame, t = 0 included, as it is written; with
  // time.accuracy_m, with the chosen trial's frames once the search has ended.
  std::function<void(const Frame&)> on_frame;
  // Called after every accepted step of every run this call makes, with what
  // the run is ("run", "accuracy trial K", "time error") and the time reached.
  std::function<void(const std::string& phase, double t)> on_step;
};

// The end state of a run with a settling phase (time.settle_dt_s): how far it
// is from an equilibrium: the largest generalized force on a free DoF at the
// final (t, q) at rest (v = 0), against the largest diagonal entry of M(q)
// times ‖g‖ (a node's weight), and the kinetic energy at the final v.
struct SettledBalance {
  double max_force_N = 0.0, heaviest_weight_N = 0.0, kinetic_J = 0.0;
};

struct RunReport {
  StepResult result;
  IntegratorStats stats;
  int frames = 0;
  double end_time = 0.0;
  // Scene key time.error_estimate (--error-estimate): the estimate after a run that ended ok.
  std::optional<TimeErrorEstimate> time_error;
  // Scene key time.accuracy_m (--accuracy): the choice made before the run.
  std::optional<AccuracyChoice> accuracy;
  std::optional<SettledBalance> settled;  // time.settle_dt_s set and the run ended ok
  // Scene key measures.drape: the last frame's drape (nullopt inside: its shadow was too large to rasterize).
  std::optional<std::optional<DrapeMeasure>> drape;
  std::string summary_json;  // the text of summary.json
};

// The frames, metrics.csv and summary.json go to options.out_dir (README,
// "Using it"). With time.accuracy_m set, every trial of the tolerance search
// (driver/accuracy.h) is a written run into the folder, each replacing the one
// before, and the record is the last trial's. SIGINT and SIGTERM (driver/interrupt.h)
// end the current step of whichever run is going (a trial, the run, the time
// error's second run): outcome `interrupted`, with frames, metrics and summary so far.
RunReport run_scene(const Scene& scene, const RunOptions& options);

}  // namespace wl
