// `weavelab calibrate`: the continuum fitted to the yarn level of a scene's
// fabric through virtual material tests (calibration/, docs/calibration.md),
// then validated on motion it was not fitted to. Writes into the output folder
//   params.toml        the FEM parameter file, with provenance
//   calibration.json   parameters (value, std_error, at_bound), correlations,
//                      singular values, residual per test, starts, timings,
//                      validation summary
//   curves.csv         yarn, fitted and first-guess response per test and load
//   validation.csv     per validation scene, variant and frame: RMS and max
//                      distance between the yarn crossings and the continuum
// (experiments/calibration/scripts/plot_calibration.py draws the charts from these).
#pragma once
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "calibration/fit.h"
#include "driver/time_steps.h"
#include "models/scene/scene.h"

namespace wl {

struct CalibrateConfig {
  std::filesystem::path scene_path;
  std::vector<std::string> tests;                      // names; empty = all
  int patch = 0;                                       // crossings per side; 0 = the scene's size, at most 33
  std::map<std::string, std::vector<double>> ladders;  // per test name; absent = default_ladder()
  bool sliding = false;                                // sliding coordinates free in the tests
  bool border_strip = false;                           // continuum with [fem] border_strip (tests and validation)
  bool grid_line_bending = false;                      // continuum with [fem] grid_line_bending (tests and validation)
  bool diagonal_bending = false;  // fit the 45° hinges' own stiffness ([fem] diagonal_bending_N_m), from the mean
  // Fit the stretch's warp–weft coupling and quartic stiffening (docs/models.md §6.3.1), each
  // starting from the curves (docs/calibration.md §8).
  bool stretch_coupling = false, stretch_stiffening = false;
  // Non-empty: fit the spline shear law with these knot angles ([fem] shear_law = "spline"), its knot
  // values starting at shear_N_per_m; empty: the scene's own shear law.
  std::vector<double> shear_knots_rad;
  FitOptions fit;
  std::vector<std::filesystem::path> validate;  // scenes to validate on
  TimeSteps time_steps;                         // of the validation runs (both sides)
  std::filesystem::path out_dir;
  bool progress = true;
};

// Checks the configuration and every input file before anything runs or is
// written: throws SceneError, FemParameterError or std::invalid_argument.
struct CalibratePlan {
  Scene scene;
  std::string scene_text;
  Scene test_scene;
  std::vector<TestSpec> tests;
  std::vector<Scene> validation_scenes;
  std::vector<std::string> validation_texts;
};
CalibratePlan plan_calibration(const CalibrateConfig& config);

struct CalibrateSummary {
  FitResult fit;
  double yarn_tests_s = 0, fem_tests_s = 0, fit_s = 0, validation_s = 0;  // wall
  // Non-empty: SIGINT or SIGTERM (driver/interrupt.h) ended the calibration in this stage ("the
  // fit", ...); calibration.json says outcome `interrupted`, params.toml exists when the fit was whole.
  std::string interrupted_in;
};
// Runs the plan; a yarn-level test that does not converge far enough to fit
// is a std::runtime_error naming the test and the rung.
CalibrateSummary run_calibration(const CalibrateConfig& config, const CalibratePlan& plan);

// Areal density [kg/m²] at which the continuum on the crossing grid carries the
// yarn level's total mass: Σ_yarns ρ·(length) / ((wefts−1)(warps−1)L²).
double matched_areal_density(const Scene& scene);

// The scene with every [fem] material value and the shear law set from `m` (no
// parameter file; a tile law, as [fem] tile_law or as the parameter file, stays as
// [fem] tile_law) and [fem] border_strip set to `border_strip`.
Scene with_material(Scene s, const FemMaterial& m, bool border_strip);

}  // namespace wl
