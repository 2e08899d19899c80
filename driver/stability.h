// The stability experiment: per integrator at fixed steps ×
// model × stretch-modulus multiplier, the largest step that stays bounded over
// the scene's duration (bisection on log dt, driver/stability_bisection.h) and
// the failure mode just above it. "Bounded" = outcome ok and max node speed
// below speed_bound at every accepted step. Writes into out_dir:
//   stability.csv         one row per (model, integrator, multiplier)
//   stability_probes.csv  every probe run (dt, bounded, outcome, …)
//   stability.json        scene file and text, parameters, git revision, machine, timing
// with progress on stderr.
#pragma once
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "driver/stability_bisection.h"
#include "models/scene/scene.h"

namespace wl {

struct StabilityConfig {
  std::filesystem::path scene_path;
  std::string scene_text;
  Scene scene;  // with overrides applied
  std::map<std::string, std::string> overrides;
  std::vector<std::string> models = {"yarn", "fem"};
  // Default: every integrator with a fixed-step mode (not ida, whose "fixed"
  // mode caps the step at dt but keeps error control).
  std::vector<std::string> integrators;
  std::vector<double> multipliers = {1, 10, 100, 1000};
  double dt_min = 1e-6, dt_max = 1e-2;
  int bisections = 8;
  double speed_bound = 10.0;  // [m/s]
  std::filesystem::path out_dir = "results/stability";
  bool progress = true;
};

struct StabilityRow {
  std::string model, integrator;
  double multiplier = 1;
  StabilityLimit limit;
  double cpu_s = 0.0;  // all probes
  bool not_offered = false;
  std::string not_offered_message;
};

struct StabilityResult {
  std::vector<StabilityRow> rows;
  double wall_s = 0.0;
};

std::vector<std::string> default_stability_integrators();

// Runs the experiment and writes the CSVs and JSON. Throws
// std::invalid_argument for unknown names or bad bounds (before any run). A
// SIGINT or SIGTERM ends the probe under way at its step: the files with the cells
// and probes complete so far and outcome interrupted (driver/interrupted_record.h),
// then Interrupted.
StabilityResult run_stability(const StabilityConfig& config);

}  // namespace wl
