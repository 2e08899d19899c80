// `weavelab fidelity`: a scene run at every rung of the fidelity ladder
// (fidelity_variants.h) and each rung measured against a yarn-level reference
// at the reference's crossings (a knit: its stitch contacts, docs/models.md §11.9)
// (docs/design.md §7.5). Writes into the output folder
//   fidelity.csv   one row per variant: DoFs, steps, CPU and wall time, RMS,
//                  worst-frame RMS and max distance, energy difference, the
//                  run's estimated time error (docs/models.md §7.8), Pareto front
//   fidelity.json  scene, reference, tolerance, the rows, the variants left
//                  out and why, the cheapest variant within the tolerance (and
//                  within 1 % and 5 % of the cloth size) with its speed-up
// (experiments/fidelity/scripts/plot_fidelity.py draws the Pareto chart from these).
#pragma once
#include <cmath>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "driver/fidelity_variants.h"
#include "driver/time_steps.h"
#include "models/scene/scene.h"

namespace wl {

struct FidelityConfig {
  std::filesystem::path scene_path;
  Scene scene;                                      // as loaded, command-line overrides applied
  std::map<std::string, std::string> overrides;     // recorded in the JSON
  std::string reference = "full";                   // a yarn-level variant
  std::vector<std::string> variants;                // empty: the whole ladder
  std::optional<std::filesystem::path> fem_params;  // calibrated continuum parameters
  std::optional<double> tolerance_m;                // absent: 1 % of the cloth size
  int repeats = 1;                                  // runs per variant; CPU and wall time are their medians
  TimeSteps time_steps;                             // of the reference and the model rungs
  bool error_estimate = true;                       // each run's time error beside its distance
  std::filesystem::path out_dir;
  bool progress = true;
  // A ladder split into jobs (experiments/fidelity/Snakefile): run only the
  // reference and also write it to out_dir/reference.bin; or read the reference
  // from that file in another folder instead of running it (fidelity_reference.h).
  bool reference_only = false;
  std::optional<std::filesystem::path> reference_from;
};

struct PlannedVariant {
  std::string name;
  VariantScene variant;
};

struct FidelityPlan {
  PlannedVariant reference;
  std::vector<PlannedVariant> variants;                       // in ladder order, without the reference
  std::vector<std::pair<std::string, std::string>> left_out;  // variant, why
  std::string calibration;                                    // where the calibrated parameters come from ("" = none)
  double cloth_size_m = 0;  // (max(wefts, warps) − 1)·L; a knit: the contact grid's larger span
  double tolerance_m = 0;
};

// Checks every input before anything runs or is written: throws
// std::invalid_argument (unknown variant, a continuum reference, a named
// variant the scene cannot have, a tolerance not > 0, repeats < 1) or
// FemParameterError.
// Variants of the default ladder the scene cannot have, or that equal the
// full model in this scene, are left out with the reason.
FidelityPlan plan_fidelity(const FidelityConfig& config);

struct FidelityRow {
  std::string variant, model, outcome, message;
  std::string same_as_full;  // why the variant is the full model under another name ("" otherwise)
  int dofs = 0;
  long steps = 0;
  double cpu_s = 0, wall_s = 0;  // medians over FidelityConfig::repeats runs
  // Distance between the reference crossings and the variant at the same
  // crossing (yarn) or material point (continuum), over the frames reached:
  //   rms = sqrt(mean over frames and compared points of d²), worst_frame_rms =
  //   max over frames of the frame's RMS, max = max d [m].
  double rms_m = 0, worst_frame_rms_m = 0, max_m = 0;
  // max over frames of |ΔE_variant − ΔE_reference|, ΔE = (T + V)(t) − (T + V)(0), each model's own V [J]
  double energy_diff_J = 0;
  double compared_fraction = 0;  // compared points / (reference frames × crossings)
  // The run's own estimated time error (docs/models.md §7.8): mean and worst
  // over frames of the per-frame RMS [m]; NaN when not estimated or the second run failed.
  std::string time_error_method;
  double time_error_mean_rms_m = NAN, time_error_worst_frame_rms_m = NAN;
  bool on_front = false;  // Pareto front of (cpu_s, worst_frame_rms_m) among the complete runs
  bool complete() const { return outcome == "ok" && compared_fraction > 0; }
};

struct FidelityChoice {
  double tolerance_m = 0;
  // cheapest complete variant with worst_frame_rms_m ≤ tolerance and, when
  // estimated, its time error's worst-frame RMS ≤ tolerance
  std::string variant;
  double cpu_s = 0;
  double speedup = 0;  // reference CPU time / the variant's
};

struct FidelityResult {
  std::vector<FidelityRow> rows;  // reference first
  FidelityChoice within_tolerance, within_1_percent, within_5_percent;
  double wall_s = 0;
};

// Runs the plan and writes the two files. A reference run that does not end ok
// is a std::runtime_error; a variant that fails is a row with its outcome. A
// SIGINT or SIGTERM ends the run under way at its step: the files with the rows
// complete so far and outcome interrupted (driver/interrupted_record.h), then Interrupted.
FidelityResult run_fidelity(const FidelityConfig& config, const FidelityPlan& plan);

// The cheapest complete row within `tolerance` (the rule of FidelityChoice::variant);
// the speed-up is over rows.front(), the reference.
FidelityChoice cheapest_within(const std::vector<FidelityRow>& rows, double tolerance);

// Pareto front of points (cost, error), both to be small: on_front[i] when no
// other point has cost ≤ and error ≤ with one of them strictly smaller.
std::vector<bool> pareto_front(const std::vector<double>& cost, const std::vector<double>& error);

}  // namespace wl
