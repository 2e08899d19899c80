// `weavelab diagnose`: where and when the continuum parts from the yarn level
// on one scene (docs/design.md §7.6). Both models run at the same time steps
// (time_steps.h), each with its own time error, and the command writes into
// the output folder
//   energies.csv    per model and output frame: kinetic energy, the potential
//                   energy of every conservative term (stretch, shear, bending,
//                   gravity, handles, …) and the work done so far by every
//                   other force (wind, friction, damping), integrated over the
//                   steps by the trapezoidal rule [J]
//   energy_directions.csv   per model, frame and term (stretch, bending): the
//                   part of its energy along the warp and along the weft, which
//                   sum to the term's energy in energies.csv (energy_split.h) [J]
//   distance.csv    per frame: RMS and max over the crossings of the distance
//                   between each yarn crossing and the continuum surface at
//                   its material point, and the RMS over the border crossings
//                   and over the interior ones [m]
//   rows.csv        per row of crossings (0 = the held top row): the RMS over
//                   frames and crossings of that row [m]
//   distance.pvd, frames/   the yarn frames with the point data
//                   "distance_to_continuum_m", for ParaView
//   diagnosis.json  scene, resolution, both time errors, the mean distance,
//                   its verdict, and the crossings farthest apart
// (experiments/diagnosis/scripts/plot_diagnosis.py draws the charts from these).
#pragma once
#include <filesystem>
#include <map>
#include <optional>
#include <string>

#include "driver/time_steps.h"
#include "models/scene/scene.h"

namespace wl {

struct DiagnoseConfig {
  std::filesystem::path scene_path;
  Scene scene;                                      // as loaded, command-line overrides applied
  std::map<std::string, std::string> overrides;     // recorded in the JSON
  std::optional<std::filesystem::path> fem_params;  // the continuum's parameters (default: the scene's)
  TimeSteps time_steps;
  bool error_estimate = true;
  std::filesystem::path out_dir;
  bool progress = true;
};

struct DiagnoseResult {
  double mean_rms_m = 0;                                   // mean over frames of the RMS distance
  double border_rms_m = 0, interior_rms_m = 0;             // RMS over frames and those crossings
  double yarn_time_error_m = NAN, fem_time_error_m = NAN;  // mean RMS estimates (NaN: not estimated)
  std::string verdict;                                     // error_budget_verdict
};

// Checks the inputs (a bad parameter file: FemParameterError) before anything
// runs; a yarn-level or continuum run that does not end ok is a
// std::runtime_error after which nothing is written. A SIGINT or SIGTERM ends
// the run or time-error estimate under way at its step: the tables so far and
// diagnosis.json with outcome interrupted (driver/interrupted_record.h), then Interrupted.
DiagnoseResult run_diagnosis(const DiagnoseConfig& config);

}  // namespace wl
