// weavelab command line: `weavelab run SCENE`, `weavelab info SCENE`,
// `weavelab work-precision SCENE`, `weavelab stability SCENE`,
// `weavelab calibrate SCENE`, `weavelab fidelity SCENE`, `weavelab fit SCENE --target RUN_DIR`,
// `weavelab diagnose SCENE`, `weavelab modes SCENE`.
// Exit codes: 0 success, 1 numerical failure (outcome in the summary),
// 2 bad scene, input file or arguments, or an output folder in use,
// 3 output could not be written, 130 / 143 interrupted by SIGINT / SIGTERM.
#include <CLI/CLI.hpp>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <map>

#include "calibration/scene_parameters.h"
#include "driver/calibrate.h"
#include "driver/determinism.h"
#include "driver/diagnose.h"
#include "driver/fidelity.h"
#include "driver/fidelity_reference.h"
#include "driver/fit_command.h"
#include "driver/interrupt.h"
#include "driver/modes.h"
#include "driver/run.h"
#include "driver/run_settings.h"
#include "driver/stability.h"
#include "driver/uniaxial_pull.h"
#include "driver/work_precision.h"
#include "output/run_reader.h"
#include "integrators/integrator.h"
#include "models/fem/fem_material.h"
#include "models/model_factory.h"
#include "models/scene/scene.h"

namespace {

const std::string kResolutionHelp =
    "Time resolution of the comparison: controlled (sdirk2 under error control at --rtol) or scene (each "
    "scene's own integrator and step)";

std::string joined(const std::vector<std::string>& names) {
  std::string s;
  for (const auto& n : names) s += (s.empty() ? "" : ", ") + n;
  return s;
}

// "a,b,c" → {"a", "b", "c"} (empty items dropped).
std::vector<std::string> split_list(const std::string& text) {
  std::vector<std::string> out;
  std::string item;
  for (char c : text + ",") {
    if (c == ',') {
      if (!item.empty()) out.push_back(item);
      item.clear();
    } else if (c != ' ') {
      item += c;
    }
  }
  return out;
}

std::vector<double> split_numbers(const std::string& text, const std::string& option) {
  std::vector<double> out;
  for (const auto& s : split_list(text)) {
    size_t used = 0;
    double x = 0;
    try {
      x = std::stod(s, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used != s.size() || !(x > 0))
      throw std::invalid_argument(option + ": got '" + s + "', expected a comma-separated list of numbers > 0");
    out.push_back(x);
  }
  if (out.empty()) throw std::invalid_argument(option + ": empty list");
  return out;
}

// Options shared by the two experiments.
struct ExperimentArgs {
  std::string scene, models = "yarn,fem", integrators, out;
  double duration = 0;
  bool quiet = false;
};

void add_experiment_options(CLI::App* cmd, ExperimentArgs& a, const std::string& default_out) {
  cmd->add_option("scene", a.scene, "Scene file (TOML)")->required();
  cmd->add_option("--models", a.models, "Comma-separated models: " + joined(wl::model_names()))->capture_default_str();
  cmd->add_option("--integrators", a.integrators,
                  "Comma-separated integrators (default: all that apply): " + joined(wl::integrator_names()));
  cmd->add_option("--duration", a.duration, "Simulated time [s] (overrides the scene)");
  cmd->add_option("--out", a.out, "Output folder (default " + default_out + ")");
  cmd->add_flag("--quiet", a.quiet, "No progress on stderr");
}

// Loads the scene and applies --duration; fills path, text, scene and overrides.
template <class Config>
void load_experiment_scene(const ExperimentArgs& a, CLI::App* cmd, Config& c) {
  c.scene_path = a.scene;
  c.scene = wl::load_scene(a.scene);  // a missing or bad file is a SceneError (exit 2)
  c.scene_text = c.scene.text;
  if (cmd->count("--duration")) wl::apply_duration_override(c.scene, a.duration, c.overrides);
  c.models = split_list(a.models);
  if (c.models.empty()) throw std::invalid_argument("--models: empty list");
  c.integrators = split_list(a.integrators);
  c.progress = !a.quiet;
}

}  // namespace

int main(int argc, char** argv) {
  wl::hold_blas_threads();  // bitwise reproducible runs (README: reproducibility)
  CLI::App app{"weavelab: yarn-level and continuum cloth under pluggable integrators"};
  app.require_subcommand(1);

  std::string scene_path, model = "yarn", integrator, out_dir;
  double dt = 0, duration = 0, output_interval = 0, rtol = 0;
  bool quiet = false, adaptive = false;
  auto* run = app.add_subcommand("run", "Simulate a scene and write frames (VTU/PVD), metrics.csv and summary.json");
  run->add_option("scene", scene_path, "Scene file (TOML)")->required();
  run->add_option("--model", model, "Model: " + joined(wl::model_names()))->capture_default_str();
  run->add_option("--integrator", integrator, "Integrator (overrides the scene): " + joined(wl::integrator_names()));
  std::string linear_solver;
  run->add_option("--linear-solver", linear_solver,
                  "Step matrix solver (overrides the scene): " + joined(wl::linear_solver_names()));
  run->add_option("--dt", dt, "Time step [s] (overrides the scene)");
  run->add_option("--duration", duration, "Simulated time [s] (overrides the scene)");
  run->add_option("--output-interval", output_interval, "Time between frames [s] (overrides the scene)");
  run->add_option("--out", out_dir, "Output folder (default results/<scene name>/<model>)");
  run->add_flag("--adaptive", adaptive,
                "Adaptive steps with error control (overrides the scene; --dt is the first step)");
  run->add_option("--rtol", rtol, "Relative tolerance of adaptive steps (implies --adaptive; atol = 1e-3 rtol m)");
  run->add_flag("--quiet", quiet, "No progress on stderr");
  bool error_estimate = false;
  run->add_flag("--error-estimate", error_estimate,
                "Estimate the run's time error per frame with a second run (summary.json: time_error)");
  double accuracy = 0;
  run->add_option("--accuracy", accuracy,
                  "Time error target [m], mean over frames of the RMS over nodes: chooses the integrator and "
                  "tolerance (no --dt, --rtol, --adaptive or --integrator beside it)");
  std::string fem_params;
  run->add_option("--fem-params", fem_params,
                  "FEM parameter file (TOML, as written by `calibrate`); replaces the scene's parameter_file");

  std::string info_scene, info_model = "yarn";
  auto* info = app.add_subcommand("info", "Print DoFs, nodes, terms and pattern of a scene's model");
  info->add_option("scene", info_scene, "Scene file (TOML)")->required();
  info->add_option("--model", info_model, "Model: " + joined(wl::model_names()))->capture_default_str();
  std::string info_params;
  info->add_option("--fem-params", info_params, "FEM parameter file (from `calibrate` or `fit`) for the continuum");

  ExperimentArgs wp_args;
  std::string wp_rtols, wp_ref_rtols, ref_dir = "results/reference";
  double wp_dt_max = 4e-3, wp_dt_min = 4e-3 / 256, wp_budget = 30.0;
  auto* wp = app.add_subcommand("work-precision",
                                "Error against CPU time: per model and integrator a ladder of tolerances (adaptive) or "
                                "step sizes (fixed-step), error against a cached IDA reference; CSV + JSON");
  add_experiment_options(wp, wp_args, "results/work_precision");
  wp->add_option("--rtols", wp_rtols, "Tolerance ladder of the adaptive methods (default 1e-3,1e-4,...,1e-8)");
  wp->add_option("--dt-max", wp_dt_max, "Largest fixed step [s]; the ladder halves it")->capture_default_str();
  wp->add_option("--dt-min", wp_dt_min, "Smallest fixed step [s]")->capture_default_str();
  wp->add_option("--budget", wp_budget, "CPU seconds a single run may be predicted to take before a ladder stops")
      ->capture_default_str();
  wp->add_option("--reference-rtols", wp_ref_rtols, "Reference tolerances, tried in order (default 1e-10,1e-9,1e-8)");
  wp->add_option("--reference-dir", ref_dir, "Reference cache folder")->capture_default_str();

  ExperimentArgs st_args;
  std::string st_mults = "1,10,100,1000";
  double st_dt_min = 1e-6, st_dt_max = 1e-2, st_bound = 10.0;
  int st_bisections = 8;
  auto* st = app.add_subcommand("stability",
                                "Largest bounded fixed step per integrator x model x stretch-modulus multiplier "
                                "(bisection on log dt) and the failure mode above it; CSV + JSON");
  add_experiment_options(st, st_args, "results/stability");
  st->add_option("--multipliers", st_mults, "Stretch-modulus multipliers")->capture_default_str();
  st->add_option("--dt-min", st_dt_min, "Smallest step probed [s]")->capture_default_str();
  st->add_option("--dt-max", st_dt_max, "Largest step probed [s]")->capture_default_str();
  st->add_option("--bisections", st_bisections, "Bisections on log dt")->capture_default_str();
  st->add_option("--speed-bound", st_bound, "Max node speed of a bounded run [m/s]")->capture_default_str();

  wl::CalibrateConfig cal;
  std::string cal_scene, cal_tests, cal_free, cal_out, cal_shear_spline;
  std::vector<std::string> cal_ladders, cal_validate;
  bool cal_quiet = false;
  auto* calibrate = app.add_subcommand(
      "calibrate",
      "Fit the continuum's [fem] parameters to virtual material tests of the scene's fabric at yarn "
      "level (Ceres), validate on motion; writes params.toml, calibration.json, curves.csv, validation.csv");
  calibrate->add_option("scene", cal_scene, "Scene file (TOML) whose fabric is calibrated")->required();
  calibrate->add_option(
      "--tests", cal_tests,
      "Comma-separated tests (default the first six): " + joined(wl::test_names()) +
          "; each also as rotated-NAME (the patch turned rigidly); knits: warp = course, weft = wale");
  calibrate->add_option("--patch", cal.patch,
                        "Crossings per side of the test patch, knits: courses = wales (default: the scene's, at most "
                        "33)");
  calibrate->add_option(
      "--ladder", cal_ladders,
      "TEST=λ1,λ2,... load ladder of a test (strain, shear angle [rad] or curvature [1/m]); repeatable");
  calibrate->add_option(
      "--free", cal_free,
      "Comma-separated [fem] keys to fit (default: all the tests inform): " + joined(wl::fittable_parameters()));
  calibrate->add_option("--starts", cal.fit.starts, "Fit starts (the first guess, then seeded draws)")
      ->capture_default_str();
  calibrate->add_option("--seed", cal.fit.seed, "Seed of the start draws")->capture_default_str();
  calibrate
      ->add_option("--residuals", cal.fit.residuals,
                   "Scale of each point's residual: range (the curve's largest response) or relative (the "
                   "yarn level's response at that load, so small loads weigh as much as large ones)")
      ->capture_default_str();
  calibrate->add_option("--loss", cal.fit.loss, "Robust loss per test curve: none, huber, cauchy")
      ->capture_default_str();
  calibrate->add_flag("--sliding", cal.sliding,
                      "Leave the yarn sliding coordinates free in the tests (default frozen)");
  calibrate->add_flag("--border-strip", cal.border_strip,
                      "Continuum with bars for the border yarns' outer half spacing ([fem] border_strip)");
  calibrate->add_flag("--grid-line-bending", cal.grid_line_bending,
                      "Continuum whose grid lines bend like yarns instead of hinges ([fem] grid_line_bending)");
  calibrate->add_flag("--diagonal-bending", cal.diagonal_bending,
                      "Fit the 45° hinges' own bending stiffness ([fem] diagonal_bending_N_m, informed by the "
                      "bending-diagonal and bending-antidiagonal tests)");
  calibrate->add_flag("--stretch-coupling", cal.stretch_coupling,
                      "Fit a warp–weft coupling of the stretch ([fem] stretch_coupling_N_per_m, informed by the "
                      "biaxial test; first guess from the biaxial and uniaxial curves)");
  calibrate->add_flag("--stretch-stiffening", cal.stretch_stiffening,
                      "Fit a quartic stiffening of the stretch ([fem] warp_stretch_quartic_N_per_m, "
                      "weft_stretch_quartic_N_per_m, and with the biaxial and both uniaxial tests "
                      "areal_stretch_quartic_N_per_m; first guess from the stretch curves' cubic parts)");
  calibrate->add_option("--shear-spline", cal_shear_spline,
                        "ANGLES: fit the spline shear law ([fem] shear_law = \"spline\", shear_knots_rad = ANGLES, "
                        "comma-separated increasing shear angles in (0, 1.5] rad, e.g. 0.1,0.2,0.3,0.4); its knot "
                        "values start at shear_N_per_m");
  calibrate->add_option("--validate", cal_validate, "Scene to validate the calibrated continuum on (repeatable)");
  std::string cal_resolution = "controlled";
  double cal_rtol = 1e-4;
  calibrate->add_option("--resolution", cal_resolution, kResolutionHelp)->capture_default_str();
  calibrate->add_option("--rtol", cal_rtol, "Tolerance of the controlled resolution")->capture_default_str();
  calibrate->add_option("--out", cal_out, "Output folder (default results/calibration/<scene name>)");
  calibrate->add_flag("--quiet", cal_quiet, "No progress on stderr");

  wl::FidelityConfig fid;
  std::string fid_scene, fid_variants, fid_params, fid_out;
  double fid_tolerance = 0, fid_duration = 0;
  bool fid_quiet = false;
  auto* fidelity = app.add_subcommand(
      "fidelity",
      "Run the scene at a ladder of model fidelities (yarn without one term, frozen sliding, continuum "
      "at strides 1, 2, 4) and measure each against the full yarn model; writes fidelity.csv and .json");
  fidelity->add_option("scene", fid_scene, "Scene file (TOML)")->required();
  fidelity->add_option("--tolerance", fid_tolerance,
                       "Worst-frame RMS distance a variant may have to count as good enough [m] (default 1 % of the "
                       "cloth size)");
  fidelity->add_option(
      "--variants", fid_variants,
      "Comma-separated variants (default: all the scene allows): " + joined(wl::fidelity_variant_names()));
  fidelity->add_option("--reference", fid.reference, "Yarn-level variant the others are measured against")
      ->capture_default_str();
  fidelity->add_option("--fem-params", fid_params,
                       "Calibrated FEM parameter file (from `calibrate`); without it (or a scene parameter_file) the "
                       "calibrated continuum variants are left out");
  fidelity->add_option("--repeats", fid.repeats, "Runs per variant; CPU and wall time are their medians")
      ->capture_default_str();
  fidelity->add_option("--duration", fid_duration, "Simulated time [s] (overrides the scene)");
  std::string fid_resolution = "controlled";
  double fid_rtol = 1e-4;
  bool fid_no_estimate = false;
  fidelity->add_option("--resolution", fid_resolution, kResolutionHelp + " (the reference and the model rungs)")
      ->capture_default_str();
  fidelity->add_option("--rtol", fid_rtol, "Tolerance of the controlled resolution")->capture_default_str();
  fidelity->add_flag("--no-error-estimate", fid_no_estimate,
                     "Do not estimate each run's time error (halves the cost; no time-error column)");
  fidelity->add_option("--out", fid_out, "Output folder (default results/fidelity/<scene name>)");
  fidelity->add_flag("--quiet", fid_quiet, "No progress on stderr");
  std::string fid_reference_from;
  bool fid_list = false;
  fidelity->add_flag("--reference-only", fid.reference_only,
                     "Run only the reference, and keep it in OUT/reference.bin for --reference-from");
  fidelity->add_option("--reference-from", fid_reference_from,
                       "Folder of a --reference-only run with the same scene and options: its reference is read, "
                       "not run again (the ladder as separate jobs, experiments/fidelity/Snakefile)");
  fidelity->add_flag("--list-variants", fid_list,
                     "Print the variants the ladder would run, one per line, and exit (nothing is run or written)");
  wl::FitCommandConfig fitc;
  std::string fit_scene, fit_target, fit_free, fit_out;
  std::vector<std::string> fit_starts, fit_start_sets;
  int fit_jobs = 1;
  bool fit_quiet = false;
  auto* fit = app.add_subcommand(
      "fit",
      "Fit scene parameters to a recorded run's node trajectory (Ceres least squares with exact forward "
      "sensitivities); fit.json, convergence.csv, frames.csv");
  fit->add_option("scene", fit_scene, "Scene file (TOML) to simulate")->required();
  fit->add_option("--target", fit_target, "Output folder of a `weavelab run` whose frames are fitted")->required();
  fit->add_option("--free", fit_free,
                  "Comma-separated scene keys to fit, e.g. contact.shear_modulus_Pa,yarn_types.yarn1.density_kg_per_m")
      ->required();
  fit->add_option("--start", fit_starts, "Start value KEY=VALUE of a fitted key (repeatable; default the scene's)");
  fit->add_option("--start-set", fit_start_sets,
                  "One more fit from these starts, KEY=VALUE,KEY=VALUE over --start (repeatable; the fits are "
                  "written to OUT/start_1, start_2, ...)");
  fit->add_option("--jobs", fit_jobs, "Fits of --start-set run at once (each on its own models; same results)")
      ->capture_default_str();
  fit->add_option("--frames", fitc.frames, "Fit the target's first N frames after t = 0 (default all)");
  std::string fit_window;
  fit->add_option("--growing-window", fit_window,
                  "N1,N2,...: fit the first N1 frames, then the first N2 from that result, ...; increasing, the "
                  "last equal to --frames (each stage at most --max-iterations)");
  fit->add_option("--model", fitc.fit.model, "Model that is fitted: yarn, fem")->capture_default_str();
  fit->add_option("--integrator", fitc.fit.integrator,
                  "An integrator with parameter sensitivities: be-linear, be-newton or sdirk2 (default the scene's)");
  fit->add_option("--bound-factor", fitc.fit.bound_factor, "Bounds start/b ... start*b")->capture_default_str();
  fit->add_option("--max-iterations", fitc.fit.max_iterations, "Ceres iterations")->capture_default_str();
  fit->add_option("--fem-params", fitc.fem_params,
                  "FEM parameter file (as written by `calibrate` or `fit --model fem`): the continuum's values "
                  "where --start does not set them");
  std::string fit_resolution = "scene";
  double fit_rtol = 1e-4;
  fit->add_option("--resolution", fit_resolution,
                  "Resolution of the fitted simulations: scene (the scene's integrator and step, as the published "
                  "fit) or controlled (sdirk2 under error control at --rtol, atol = 1e-3 rtol)")
      ->capture_default_str();
  fit->add_option("--rtol", fit_rtol, "Tolerance of the controlled resolution")->capture_default_str();
  fit->add_option("--out", fit_out, "Output folder (default results/fit/<scene name>)");
  fit->add_flag("--quiet", fit_quiet, "No progress on stderr");

  wl::DiagnoseConfig diag;
  std::string diag_scene, diag_params, diag_out, diag_resolution = "controlled";
  double diag_duration = 0, diag_rtol = 1e-4;
  bool diag_quiet = false, diag_no_estimate = false;
  auto* diagnose = app.add_subcommand(
      "diagnose",
      "Run the yarn level and the continuum on one scene and show where and when they part: energies per "
      "term, distance per crossing (VTU), by row and over time, each side's time error");
  diagnose->add_option("scene", diag_scene, "Scene file (TOML)")->required();
  diagnose->add_option("--fem-params", diag_params,
                       "Continuum parameter file (default: the scene's, or the first guess)");
  diagnose->add_option("--duration", diag_duration, "Simulated time [s] (overrides the scene)");
  diagnose->add_option("--resolution", diag_resolution, kResolutionHelp)->capture_default_str();
  diagnose->add_option("--rtol", diag_rtol, "Tolerance of the controlled resolution")->capture_default_str();
  diagnose->add_flag("--no-error-estimate", diag_no_estimate, "Do not estimate the runs' time errors");
  diagnose->add_option("--out", diag_out, "Output folder (default results/diagnose/<scene name>)");
  diagnose->add_flag("--quiet", diag_quiet, "No progress on stderr");

  wl::ModesConfig modc;
  std::string modes_scene, modes_params, modes_out;
  bool modes_quiet = false;
  auto* modes = app.add_subcommand(
      "modes",
      "Lowest vibration modes of the yarn level and the continuum about the same hanging equilibrium (wind "
      "off), matched by shape (MAC): frequencies, MAC matrix, mode shapes (VTU)");
  modes->add_option("scene", modes_scene, "Scene file (TOML)")->required();
  modes->add_option("--fem-params", modes_params,
                    "Continuum parameter file (default: the scene's, or the first guess)");
  modes->add_option("--count", modc.count, "Modes per model")->capture_default_str();
  modes
      ->add_option("--lean", modc.lean_m,
                   "Out-of-plane lean [m] at the bottom row from which a cloth whose planar hang is unstable "
                   "settles (0: keep the planar hang)")
      ->capture_default_str();
  modes->add_flag("--fd-check", modc.fd_check,
                  "Also form K by central differences of the full force (frozen contact forces recomputed) and "
                  "report its asymmetry, its distance from the assembled K and its lowest frequencies");
  modes->add_option("--out", modes_out, "Output folder (default results/modes/<scene name>)");
  modes->add_flag("--quiet", modes_quiet, "No progress on stderr");

  std::string pull_scene, pull_strains = "0.01,0.02,0.05,0.1", pull_direction = "y", pull_out;
  auto* pull = app.add_subcommand("pull", "Uniaxial strip test of a flat cloth at yarn level: pull.csv, pull.json");
  pull->add_option("scene", pull_scene, "Scene file (TOML), flat pose")->required();
  pull->add_option("--strains", pull_strains, "Increasing strain ladder")->capture_default_str();
  pull->add_option("--direction", pull_direction, "Pull along x (knit: course-wise) or y (knit: wale-wise)")
      ->check(CLI::IsMember({"x", "y"}))
      ->capture_default_str();
  pull->add_option("--out", pull_out, "Output folder (default results/pull/<scene name>)");
  bool pull_hold_z = false;
  pull->add_flag("--hold-z", pull_hold_z, "Hold every node's z at rest: an in-plane test (no buckling or curl)");

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? 0 : 2;
  }

  try {
    if (*info) {
      wl::Scene scene = wl::load_scene(info_scene);
      if (!info_params.empty()) scene.fem.parameter_file = info_params;
      auto m = wl::make_model(scene, info_model);
      std::cout << "scene: " << info_scene << "\n";
      for (const auto& [k, v] : m->describe()) std::cout << k << ": " << v << "\n";
      return 0;
    }
    if (*wp) {
      wl::WorkPrecisionConfig c;
      load_experiment_scene(wp_args, wp, c);
      if (c.integrators.empty()) c.integrators = wl::integrator_names();
      if (!wp_rtols.empty()) c.rtols = split_numbers(wp_rtols, "--rtols");
      if (!wp_ref_rtols.empty()) c.reference.rtols = split_numbers(wp_ref_rtols, "--reference-rtols");
      if (wl::positive_option("--dt-min", wp_dt_min) > wl::positive_option("--dt-max", wp_dt_max))
        throw std::invalid_argument("--dt-min/--dt-max: need 0 < dt-min <= dt-max");
      wl::positive_option("--budget", wp_budget);
      c.dt_max = wp_dt_max;
      c.dt_min = wp_dt_min;
      c.run_budget_cpu_s = wp_budget;
      c.reference.cache_dir = ref_dir;
      c.reference.progress = c.progress;
      c.out_dir =
          wl::output_folder(wp->count("--out") ? std::optional(wp_args.out) : std::nullopt, "results/work_precision");
      const auto r = wl::run_work_precision(c);
      std::cerr << "weavelab: work-precision: " << r.rows.size() << " runs in " << r.wall_s << " s; results in "
                << c.out_dir.string() << "\n";
      return 0;
    }
    if (*st) {
      wl::StabilityConfig c;
      load_experiment_scene(st_args, st, c);
      c.multipliers = split_numbers(st_mults, "--multipliers");
      c.dt_min = wl::positive_option("--dt-min", st_dt_min);
      c.dt_max = wl::positive_option("--dt-max", st_dt_max);
      c.bisections = st_bisections;
      c.speed_bound = wl::positive_option("--speed-bound", st_bound);
      c.out_dir =
          wl::output_folder(st->count("--out") ? std::optional(st_args.out) : std::nullopt, "results/stability");
      const auto r = wl::run_stability(c);
      std::cerr << "weavelab: stability: " << r.rows.size() << " cells in " << r.wall_s << " s; results in "
                << c.out_dir.string() << "\n";
      return 0;
    }
    if (*calibrate) {
      cal.scene_path = cal_scene;
      cal.tests = split_list(cal_tests);
      if (calibrate->count("--tests") && cal.tests.empty()) throw std::invalid_argument("--tests: empty list");
      cal.fit.free = split_list(cal_free);
      for (const std::string& l : cal_ladders) {
        const auto eq = l.find('=');
        if (eq == std::string::npos)
          throw std::invalid_argument("--ladder: got '" + l + "', expected TEST=λ1,λ2,... (e.g. shear=0.1,0.2,0.4)");
        cal.ladders[l.substr(0, eq)] = split_numbers(l.substr(eq + 1), "--ladder " + l.substr(0, eq));
      }
      if (calibrate->count("--shear-spline")) cal.shear_knots_rad = split_numbers(cal_shear_spline, "--shear-spline");
      if (calibrate->count("--patch") && cal.patch < 1)
        throw std::invalid_argument("--patch: got " + std::to_string(cal.patch) + ", expected a number of crossings");
      for (const auto& v : cal_validate) cal.validate.emplace_back(v);
      cal.resolution = wl::parse_resolution("--resolution", cal_resolution, cal_rtol);
      cal.out_dir = cal_out.empty()
                        ? std::filesystem::path("results/calibration") / std::filesystem::path(cal_scene).stem()
                        : std::filesystem::path(cal_out);
      cal.progress = !cal_quiet;
      const wl::CalibratePlan plan = wl::plan_calibration(cal);  // every input checked; nothing written yet
      try {
        const wl::CalibrateSummary r = wl::run_calibration(cal, plan);
        std::cerr << "weavelab: calibrate: yarn tests " << r.yarn_tests_s << " s, continuum tests " << r.fem_tests_s
                  << " s, fit " << r.fit_s << " s, validation " << r.validation_s << " s; results in "
                  << cal.out_dir.string() << "\n";
        return r.fit.converged ? 0 : 1;
      } catch (const std::filesystem::filesystem_error&) {
        throw;
      } catch (const std::runtime_error& e) {
        std::cerr << "weavelab: calibrate: " << e.what() << "\n";
        return 1;
      }
    }
    if (*fidelity) {
      fid.scene_path = fid_scene;
      fid.scene = wl::load_scene(fid_scene);
      if (fidelity->count("--duration")) wl::apply_duration_override(fid.scene, fid_duration, fid.overrides);
      wl::check_run_settings(fid.scene, fid.overrides);
      if (fidelity->count("--tolerance")) fid.tolerance_m = wl::positive_option("--tolerance", fid_tolerance);
      fid.variants = split_list(fid_variants);
      if (fidelity->count("--variants") && fid.variants.empty()) throw std::invalid_argument("--variants: empty list");
      if (!fid_params.empty()) fid.fem_params = fid_params;
      fid.resolution = wl::parse_resolution("--resolution", fid_resolution, fid_rtol);
      fid.error_estimate = !fid_no_estimate;
      fid.out_dir =
          wl::output_folder(fidelity->count("--out") ? std::optional(fid_out) : std::nullopt,
                            std::filesystem::path("results/fidelity") / std::filesystem::path(fid_scene).stem());
      fid.progress = !fid_quiet;
      if (!fid_reference_from.empty()) fid.reference_from = fid_reference_from;
      if (fid.reference_only && (fid.reference_from || fidelity->count("--variants")))
        throw std::invalid_argument(
            "--reference-only: runs no variant; --variants and --reference-from "
            "do not go with it");
      const wl::FidelityPlan plan = wl::plan_fidelity(fid);  // every input checked; nothing written yet
      if (fid_list) {
        for (const wl::PlannedVariant& v : plan.variants) std::printf("%s\n", v.name.c_str());
        return 0;
      }
      // a missing or mismatched reference file is bad input: exit 2 before anything is written
      if (fid.reference_from) wl::read_fidelity_reference(*fid.reference_from, wl::fidelity_reference_key(fid));
      try {
        const wl::FidelityResult r = wl::run_fidelity(fid, plan);
        const wl::FidelityChoice& c = r.within_tolerance;
        if (c.variant.empty()) {
          std::fprintf(stderr,
                       "weavelab: fidelity: no variant is within %.3g mm (%.3g %% of the %.3g mm cloth) with its own "
                       "time error; results in %s\n",
                       1e3 * c.tolerance_m, 100 * c.tolerance_m / plan.cloth_size_m, 1e3 * plan.cloth_size_m,
                       fid.out_dir.string().c_str());
          return 0;
        }
        std::fprintf(stderr,
                     "weavelab: fidelity: cheapest within %.3g mm (%.3g %% of the %.3g mm cloth): %s, %.3g x "
                     "faster than %s (CPU %.3g s against %.3g s); results in %s\n",
                     1e3 * c.tolerance_m, 100 * c.tolerance_m / plan.cloth_size_m, 1e3 * plan.cloth_size_m,
                     c.variant.c_str(), c.speedup, plan.reference.name.c_str(), c.cpu_s, r.rows.front().cpu_s,
                     fid.out_dir.string().c_str());
        return 0;
      } catch (const std::filesystem::filesystem_error&) {
        throw;
      } catch (const std::runtime_error& e) {
        std::cerr << "weavelab: fidelity: " << e.what() << "\n";
        return 1;
      }
    }
    if (*diagnose) {
      diag.scene_path = diag_scene;
      diag.scene = wl::load_scene(diag_scene);
      if (diagnose->count("--duration")) wl::apply_duration_override(diag.scene, diag_duration, diag.overrides);
      wl::check_run_settings(diag.scene, diag.overrides);
      if (!diag_params.empty()) diag.fem_params = diag_params;
      diag.resolution = wl::parse_resolution("--resolution", diag_resolution, diag_rtol);
      diag.error_estimate = !diag_no_estimate;
      diag.out_dir =
          wl::output_folder(diagnose->count("--out") ? std::optional(diag_out) : std::nullopt,
                            std::filesystem::path("results/diagnose") / std::filesystem::path(diag_scene).stem());
      diag.progress = !diag_quiet;
      try {
        const wl::DiagnoseResult r = wl::run_diagnosis(diag);
        std::fprintf(stderr,
                     "weavelab: diagnose: distance %.3g mm mean RMS (border %.3g mm, interior %.3g mm); time error "
                     "yarn %.3g mm, continuum %.3g mm: %s; results in %s\n",
                     1e3 * r.mean_rms_m, 1e3 * r.border_rms_m, 1e3 * r.interior_rms_m, 1e3 * r.yarn_time_error_m,
                     1e3 * r.fem_time_error_m, r.verdict.c_str(), diag.out_dir.string().c_str());
        return 0;
      } catch (const std::filesystem::filesystem_error&) {
        throw;
      } catch (const std::runtime_error& e) {
        std::cerr << "weavelab: diagnose: " << e.what() << "\n";
        return 1;
      }
    }
    if (*modes) {
      modc.scene_path = modes_scene;
      modc.scene = wl::load_scene(modes_scene);
      if (!modes_params.empty()) modc.fem_params = modes_params;
      modc.out_dir =
          wl::output_folder(modes->count("--out") ? std::optional(modes_out) : std::nullopt,
                            std::filesystem::path("results/modes") / std::filesystem::path(modes_scene).stem());
      modc.progress = !modes_quiet;
      try {
        const wl::ModesResult r = wl::run_modes(modc);
        double lowest_mac = 1.0;
        for (const wl::ModePair& p : r.pairs) lowest_mac = std::min(lowest_mac, p.mac);
        std::fprintf(stderr,
                     "weavelab: modes: equilibria %.3g mm apart (RMS over the crossings); lowest %.4g Hz (yarn), "
                     "%.4g Hz (continuum); %zu pairs, lowest MAC %.3g; results in %s\n",
                     1e3 * r.equilibrium_rms_m, wl::frequency_hz(r.yarn.modes.eigenvalues.front()),
                     wl::frequency_hz(r.fem.modes.eigenvalues.front()), r.pairs.size(), lowest_mac,
                     modc.out_dir.string().c_str());
        return 0;
      } catch (const std::filesystem::filesystem_error&) {
        throw;
      } catch (const std::runtime_error& e) {
        std::cerr << "weavelab: modes: " << e.what() << "\n";
        return 1;
      }
    }
    if (*pull) {
      wl::PullConfig pc;
      pc.strains = split_numbers(pull_strains, "--strains");
      pc.direction = pull_direction[0];
      pc.hold_z = pull_hold_z;
      pc.out_dir = wl::output_folder(pull->count("--out") ? std::optional(pull_out) : std::nullopt,
                                     std::filesystem::path("results/pull") / std::filesystem::path(pull_scene).stem());
      const wl::Scene scene = wl::load_scene(pull_scene);
      const wl::PullResult r = wl::pull_command(scene, pc);
      std::fprintf(stderr, "weavelab: pull: %zu of %zu rungs, yarn length per area %.6g 1/m; results in %s%s%s\n",
                   r.points.size(), pc.strains.size() + 1, r.yarn_length_per_area_per_m, pc.out_dir.string().c_str(),
                   r.complete ? "" : "; stopped: ", r.message.c_str());
      return r.complete ? 0 : 1;
    }
    if (*fit) {
      fitc.scene_path = fit_scene;
      fitc.target_dir = fit_target;
      fitc.fit.free = split_list(fit_free);
      if (fitc.fit.free.empty()) throw std::invalid_argument("--free: empty list");
      auto read_start = [](const std::string& s, std::map<std::string, double>& start) {
        const auto eq = s.find('=');
        const std::vector<double> v = eq == std::string::npos
                                          ? std::vector<double>{}
                                          : split_numbers(s.substr(eq + 1), "--start " + s.substr(0, eq));
        if (v.size() != 1) throw std::invalid_argument("--start: got '" + s + "', expected KEY=VALUE with VALUE > 0");
        start[s.substr(0, eq)] = v[0];
      };
      for (const std::string& s : fit_starts) read_start(s, fitc.fit.start);
      if (fit->count("--growing-window"))
        for (double x : split_numbers(fit_window, "--growing-window")) {
          if (x != std::floor(x) || x > 1e6)
            throw std::invalid_argument("--growing-window: got '" + fit_window +
                                        "', expected increasing frame counts N1,N2,... (e.g. 5,10,25)");
          fitc.fit.window.push_back(static_cast<int>(x));
        }
      if (fit_jobs < 1) throw std::invalid_argument("--jobs: got " + std::to_string(fit_jobs) + ", expected >= 1");
      if (fit->count("--max-iterations") && fitc.fit.max_iterations < 1)
        throw std::invalid_argument("--max-iterations: got " + std::to_string(fitc.fit.max_iterations) +
                                    ", expected >= 1");
      fitc.fit.progress = !fit_quiet;
      fitc.resolution = wl::parse_resolution("--resolution", fit_resolution, fit_rtol);
      fitc.out_dir = wl::output_folder(fit->count("--out") ? std::optional(fit_out) : std::nullopt,
                                       std::filesystem::path("results/fit") / std::filesystem::path(fit_scene).stem());
      std::vector<wl::FitCommandConfig> sets;
      for (const std::string& list : fit_start_sets) {
        wl::FitCommandConfig c = fitc;
        for (const std::string& s : split_list(list)) read_start(s, c.fit.start);
        c.out_dir = fitc.out_dir / ("start_" + std::to_string(sets.size() + 1));
        sets.push_back(std::move(c));
      }
      for (const wl::FitCommandConfig& c : sets) wl::plan_fit(c);  // every input checked; nothing written yet
      const wl::FitCommandPlan plan = wl::plan_fit(fitc);
      if (!sets.empty()) {
        bool all = true;
        const std::vector<wl::TrajectoryFitResult> rs = wl::run_fits(sets, plan, fit_jobs);
        for (size_t k = 0; k < rs.size(); ++k) {
          std::cerr << "weavelab: fit: " << sets[k].out_dir.string() << ": " << rs[k].iterations << " iterations, "
                    << rs[k].wall_s << " s wall, " << rs[k].cpu_s << " s CPU; " << rs[k].message << "\n";
          all = all && rs[k].converged;
        }
        return all ? 0 : 1;
      }
      const wl::TrajectoryFitResult r = wl::run_fit(fitc, plan);
      if (r.final_rms.empty()) {
        std::cerr << "weavelab: fit: " << r.message << "\n";
        return 1;
      }
      for (size_t k = 0; r.stages.size() > 1 && k < r.stages.size(); ++k)
        std::cerr << "weavelab: fit: stage " << k + 1 << ", " << r.stages[k].frames
                  << " frames: " << r.stages[k].iterations << " iterations, " << r.stages[k].simulations
                  << " simulations, " << r.stages[k].wall_s << " s wall, " << r.stages[k].cpu_s << " s CPU; "
                  << r.stages[k].message << "\n";
      std::cerr << "weavelab: fit: " << r.iterations << " iterations, " << r.simulations << " simulations, " << r.wall_s
                << " s; RMS distance " << 1e3 * r.start_rms.back() << " mm at the "
                << (r.stages.size() > 1 ? "last stage's " : "") << "start, " << 1e3 * r.final_rms.back()
                << " mm fitted (last frame); " << r.message << "; results in " << fitc.out_dir.string() << "\n";
      for (const auto& p : r.parameters)
        std::cerr << "  " << p.key << " = " << p.value << " +- " << p.std_error << " (start " << p.start << ")\n";
      return r.converged ? 0 : 1;
    }
    wl::Scene scene = wl::load_scene(scene_path);
    wl::RunOptions opt;
    opt.model = model;
    opt.progress = !quiet;
    wl::RunOverrides ov;
    if (run->count("--integrator")) ov.integrator = integrator;
    if (run->count("--linear-solver")) ov.linear_solver = linear_solver;
    if (run->count("--dt")) ov.dt_s = dt;
    if (run->count("--duration")) ov.duration_s = duration;
    if (run->count("--output-interval")) ov.output_interval_s = output_interval;
    if (run->count("--rtol")) ov.rtol = rtol;
    ov.adaptive = adaptive;
    ov.error_estimate = error_estimate;
    if (run->count("--accuracy")) ov.accuracy_m = accuracy;
    if (run->count("--fem-params")) ov.fem_parameter_file = fem_params;
    wl::apply_run_overrides(scene, ov, opt.overrides);  // every rule before anything is written
    opt.out_dir =
        wl::output_folder(run->count("--out") ? std::optional(out_dir) : std::nullopt,
                          std::filesystem::path("results") / std::filesystem::path(scene_path).stem() / model);
    wl::install_interrupt_handlers();
    wl::RunReport rep = wl::run_scene(scene, opt);
    if (rep.result.outcome == wl::Outcome::interrupted) {
      std::cerr << "weavelab: " << rep.result.message << " at t = " << rep.end_time
                << " s; frames, metrics and summary in " << opt.out_dir.string() << "\n";
      return wl::interrupted_exit_code(wl::interrupt_signal());
    }
    if (rep.result.outcome != wl::Outcome::ok) {
      std::cerr << "weavelab: run ended with outcome '" << wl::to_string(rep.result.outcome)
                << "' at t = " << rep.end_time << " s: " << rep.result.message << " (summary in "
                << opt.out_dir.string() << ")\n";
      return rep.result.outcome == wl::Outcome::not_offered ? 2 : 1;
    }
    if (rep.accuracy && !rep.accuracy->reached) {
      std::cerr << "weavelab: the time error target " << rep.accuracy->target_m << " m was not reached in "
                << rep.accuracy->trials.size() << " trials"
                << (rep.accuracy->note.empty() ? "" : ": " + rep.accuracy->note)
                << "; the run used the last one (summary in " << opt.out_dir.string() << ")\n";
      return 1;
    }
    return 0;
  } catch (const wl::SceneError& e) {
    std::cerr << "weavelab: bad scene: " << e.what() << "\n";
    return 2;
  } catch (const wl::RunReadError& e) {
    std::cerr << "weavelab: bad target run: " << e.what() << "\n";
    return 2;
  } catch (const wl::FemParameterError& e) {
    std::cerr << "weavelab: bad FEM parameters: " << e.what() << "\n";
    return 2;
  } catch (const std::invalid_argument& e) {
    std::cerr << "weavelab: " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "weavelab: " << e.what() << "\n";
    return 3;
  }
}
