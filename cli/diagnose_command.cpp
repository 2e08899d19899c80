// `weavelab diagnose SCENE`: where and when the yarn level and the continuum part on one scene.
#include <cstdio>
#include <filesystem>
#include <memory>

#include "cli/commands.h"
#include "cli/exit_codes.h"
#include "cli/options.h"
#include "driver/diagnose.h"
#include "driver/run_settings.h"

namespace wl::cli {
namespace {

struct DiagnoseArgs {
  std::string scene, fem_params, out;
  double duration = 0;
  TimeStepsArgs time_steps;
  bool quiet = false, no_estimate = false;
};

void add_options(CLI::App* diagnose, DiagnoseArgs& a) {
  diagnose->add_option("scene", a.scene, "Scene file (TOML)")->required();
  diagnose->add_option("--fem-params", a.fem_params,
                       "Continuum parameter file (default: the scene's, or the first guess)");
  diagnose->add_option("--duration", a.duration, "Simulated time [s] (overrides the scene)");
  add_time_steps_options(diagnose, a.time_steps, "controlled", kTimeStepsHelp);
  diagnose->add_flag("--no-error-estimate", a.no_estimate, "Do not estimate the runs' time errors");
  diagnose->add_option("--out", a.out, "Output folder (default results/diagnose/<scene name>)");
  diagnose->add_flag("--quiet", a.quiet, "No progress on stderr");
}

int run(const CLI::App* diagnose, const DiagnoseArgs& a) {
  DiagnoseConfig diag;
  diag.scene_path = a.scene;
  diag.scene = load_scene(a.scene);
  check_comparison_memory(diag.scene);  // before any allocation: exit 2
  if (diagnose->count("--duration")) apply_duration_override(diag.scene, a.duration, diag.overrides);
  check_run_settings(diag.scene, diag.overrides);
  if (!a.fem_params.empty()) diag.fem_params = a.fem_params;
  diag.time_steps = time_steps_of(a.time_steps);
  diag.error_estimate = !a.no_estimate;
  diag.out_dir = output_folder(diagnose->count("--out") ? std::optional(a.out) : std::nullopt,
                               std::filesystem::path("results/diagnose") / std::filesystem::path(a.scene).stem());
  diag.progress = !a.quiet;
  return interruptible("diagnose", diag.out_dir, [&] {
    return numerical_failure_is_exit_1("diagnose", [&] {
      const DiagnoseResult r = run_diagnosis(diag);
      std::fprintf(stderr,
                   "weavelab: diagnose: distance %.3g mm mean RMS (border %.3g mm, interior %.3g mm); time error "
                   "yarn %.3g mm, continuum %.3g mm: %s; results in %s\n",
                   1e3 * r.mean_rms_m, 1e3 * r.border_rms_m, 1e3 * r.interior_rms_m, 1e3 * r.yarn_time_error_m,
                   1e3 * r.fem_time_error_m, r.verdict.c_str(), diag.out_dir.string().c_str());
      return 0;
    });
  });
}

}  // namespace

Command add_diagnose_command(CLI::App& app) {
  auto args = std::make_shared<DiagnoseArgs>();
  CLI::App* command = app.add_subcommand(
      "diagnose",
      "Run the yarn level and the continuum on one scene and show where and when they part: energies per "
      "term, distance per crossing (VTU), by row and over time, each side's time error");
  add_options(command, *args);
  return {command, [command, args] { return run(command, *args); }};
}

}  // namespace wl::cli
