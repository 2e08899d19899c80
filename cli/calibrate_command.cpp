// `weavelab calibrate SCENE`: the continuum's [fem] parameters fitted to virtual material tests
// of the scene's fabric at yarn level, validated on motion.
#include <filesystem>
#include <iostream>
#include <memory>

#include "calibration/virtual_tests.h"
#include "cli/commands.h"
#include "cli/exit_codes.h"
#include "cli/options.h"
#include "driver/calibrate.h"
#include "driver/interrupt.h"
#include "driver/run_settings.h"

namespace wl::cli {
namespace {

struct CalibrateArgs {
  CalibrateConfig config;
  std::string scene, tests, free, out, shear_spline;
  std::vector<std::string> ladders, validate;
  TimeStepsArgs time_steps;
  bool quiet = false;
};

void add_test_options(CLI::App* calibrate, CalibrateArgs& a) {
  CalibrateConfig& cal = a.config;
  calibrate->add_option("scene", a.scene, "Scene file (TOML) whose fabric is calibrated")->required();
  calibrate->add_option(
      "--tests", a.tests,
      "Comma-separated tests (default the first six): " + joined(test_names()) +
          "; each also as rotated-NAME (the patch turned rigidly); knits: warp = course, weft = wale");
  calibrate->add_option("--patch", cal.patch,
                        "Crossings per side of the test patch, knits: courses = wales (default: the scene's, at most "
                        "33)");
  calibrate->add_option(
      "--ladder", a.ladders,
      "TEST=λ1,λ2,... load ladder of a test (strain, shear angle [rad] or curvature [1/m]); repeatable");
  calibrate->add_option(
      "--free", a.free,
      "Comma-separated [fem] keys to fit (default: all the tests inform): " + joined(fittable_parameters()));
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
}

void add_law_options(CLI::App* calibrate, CalibrateArgs& a) {
  CalibrateConfig& cal = a.config;
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
  calibrate->add_option("--shear-spline", a.shear_spline,
                        "ANGLES: fit the spline shear law ([fem] shear_law = \"spline\", shear_knots_rad = ANGLES, "
                        "comma-separated increasing shear angles in (0, 1.5] rad, e.g. 0.1,0.2,0.3,0.4); its knot "
                        "values start at shear_N_per_m");
}

void add_validation_options(CLI::App* calibrate, CalibrateArgs& a) {
  calibrate->add_option("--validate", a.validate, "Scene to validate the calibrated continuum on (repeatable)");
  add_time_steps_options(calibrate, a.time_steps, "controlled", kTimeStepsHelp);
  calibrate->add_option("--out", a.out, "Output folder (default results/calibration/<scene name>)");
  calibrate->add_flag("--quiet", a.quiet, "No progress on stderr");
}

// The configuration from the parsed options; std::invalid_argument for a bad value.
CalibrateConfig config_of(const CLI::App* calibrate, const CalibrateArgs& a) {
  CalibrateConfig cal = a.config;
  cal.scene_path = a.scene;
  cal.tests = split_list(a.tests);
  if (calibrate->count("--tests") && cal.tests.empty()) throw std::invalid_argument("--tests: empty list");
  cal.fit.free = split_list(a.free);
  for (const std::string& l : a.ladders) {
    const auto eq = l.find('=');
    if (eq == std::string::npos)
      throw std::invalid_argument("--ladder: got '" + l + "', expected TEST=λ1,λ2,... (e.g. shear=0.1,0.2,0.4)");
    cal.ladders[l.substr(0, eq)] = split_numbers(l.substr(eq + 1), "--ladder " + l.substr(0, eq));
  }
  if (calibrate->count("--shear-spline")) cal.shear_knots_rad = split_numbers(a.shear_spline, "--shear-spline");
  if (calibrate->count("--patch") && cal.patch < 1)
    throw std::invalid_argument("--patch: got " + std::to_string(cal.patch) + ", expected a number of crossings");
  for (const auto& v : a.validate) cal.validate.emplace_back(v);
  cal.time_steps = time_steps_of(a.time_steps);
  cal.out_dir = output_folder(calibrate->count("--out") ? std::optional(a.out) : std::nullopt,
                              std::filesystem::path("results/calibration") / std::filesystem::path(a.scene).stem());
  cal.progress = !a.quiet;
  return cal;
}

int run(const CLI::App* calibrate, const CalibrateArgs& a) {
  const CalibrateConfig cal = config_of(calibrate, a);
  const CalibratePlan plan = plan_calibration(cal);  // every input checked; nothing written yet
  install_interrupt_handlers();
  return numerical_failure_is_exit_1("calibrate", [&] {
    const CalibrateSummary r = run_calibration(cal, plan);
    if (!r.interrupted_in.empty()) {
      std::cerr << "weavelab: calibrate: " << interrupted_message(interrupt_signal()) << " in " << r.interrupted_in
                << "; the record so far in " << cal.out_dir.string() << "\n";
      return interrupted_exit_code(interrupt_signal());
    }
    std::cerr << "weavelab: calibrate: yarn tests " << r.yarn_tests_s << " s, continuum tests " << r.fem_tests_s
              << " s, fit " << r.fit_s << " s, validation " << r.validation_s << " s; results in "
              << cal.out_dir.string() << "\n";
    return r.fit.converged ? 0 : 1;
  });
}

}  // namespace

Command add_calibrate_command(CLI::App& app) {
  auto args = std::make_shared<CalibrateArgs>();
  CLI::App* command = app.add_subcommand(
      "calibrate",
      "Fit the continuum's [fem] parameters to virtual material tests of the scene's fabric at yarn "
      "level (Ceres), validate on motion; writes params.toml, calibration.json, curves.csv, validation.csv");
  add_test_options(command, *args);
  add_law_options(command, *args);
  add_validation_options(command, *args);
  return {command, [command, args] { return run(command, *args); }};
}

}  // namespace wl::cli
