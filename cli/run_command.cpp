// `weavelab run SCENE`: one simulation, its frames (VTU/PVD), metrics.csv and summary.json.
#include <filesystem>
#include <iostream>
#include <memory>

#include "cli/commands.h"
#include "cli/options.h"
#include "driver/interrupt.h"
#include "driver/run.h"
#include "driver/run_settings.h"
#include "integrators/integrator.h"

namespace wl::cli {
namespace {

struct RunArgs {
  std::string scene_path, model, integrator, linear_solver, out_dir, fem_params;
  double dt = 0, duration = 0, output_interval = 0, rtol = 0, accuracy = 0;
  bool quiet = false, adaptive = false, error_estimate = false;
};

void add_options(CLI::App* run, RunArgs& a) {
  run->add_option("scene", a.scene_path, "Scene file (TOML)")->required();
  run->add_option("--model", a.model, model_help("Model"));
  run->add_option("--integrator", a.integrator, "Integrator (overrides the scene): " + joined(integrator_names()));
  run->add_option("--linear-solver", a.linear_solver,
                  "Step matrix solver (overrides the scene): " + joined(linear_solver_names()));
  run->add_option("--dt", a.dt, "Time step [s] (overrides the scene)");
  run->add_option("--duration", a.duration, "Simulated time [s] (overrides the scene)");
  run->add_option("--output-interval", a.output_interval, "Time between frames [s] (overrides the scene)");
  run->add_option("--out", a.out_dir, "Output folder (default results/<scene name>/<model>)");
  run->add_flag("--adaptive", a.adaptive,
                "Adaptive steps with error control (overrides the scene; --dt is the first step)");
  run->add_option("--rtol", a.rtol, "Relative tolerance of adaptive steps (implies --adaptive; atol = 1e-3 rtol m)");
  run->add_flag("--quiet", a.quiet, "No progress on stderr");
  run->add_flag("--error-estimate", a.error_estimate,
                "Estimate the run's time error per frame with a second run (summary.json: time_error)");
  run->add_option("--accuracy", a.accuracy,
                  "Time error target [m], mean over frames of the RMS over nodes: chooses the integrator and "
                  "tolerance (no --dt, --rtol, --adaptive or --integrator beside it)");
  run->add_option("--fem-params", a.fem_params,
                  "FEM parameter file (TOML, as written by `calibrate`); replaces the scene's parameter_file");
}

RunOverrides overrides_of(const CLI::App* run, const RunArgs& a) {
  RunOverrides ov;
  if (run->count("--integrator")) ov.integrator = a.integrator;
  if (run->count("--linear-solver")) ov.linear_solver = a.linear_solver;
  if (run->count("--dt")) ov.dt_s = a.dt;
  if (run->count("--duration")) ov.duration_s = a.duration;
  if (run->count("--output-interval")) ov.output_interval_s = a.output_interval;
  if (run->count("--rtol")) ov.rtol = a.rtol;
  ov.adaptive = a.adaptive;
  ov.error_estimate = a.error_estimate;
  if (run->count("--accuracy")) ov.accuracy_m = a.accuracy;
  if (run->count("--fem-params")) ov.fem_parameter_file = a.fem_params;
  return ov;
}

// The exit code of a finished run (README, "Exit codes"), with its message on stderr.
int exit_code_of_run(const RunReport& rep, const std::filesystem::path& out_dir) {
  if (rep.result.outcome == Outcome::interrupted) {
    std::cerr << "weavelab: " << rep.result.message << " at t = " << rep.end_time
              << " s; frames, metrics and summary in " << out_dir.string() << "\n";
    return interrupted_exit_code(interrupt_signal());
  }
  if (rep.result.outcome != Outcome::ok) {
    std::cerr << "weavelab: run ended with outcome '" << to_string(rep.result.outcome) << "' at t = " << rep.end_time
              << " s: " << rep.result.message << " (summary in " << out_dir.string() << ")\n";
    return rep.result.outcome == Outcome::not_offered ? 2 : 1;
  }
  if (rep.accuracy && !rep.accuracy->reached) {
    const AccuracyChoice& a = *rep.accuracy;
    std::cerr << "weavelab: the time error target " << a.target_m << " m was not reached in " << a.trials.size()
              << " trials (" << a.verdict << "): " << a.note << "; the folder holds the last trial, sdirk2 at rtol "
              << a.rtol;
    if (a.estimate.ok()) std::cerr << ", estimated " << a.estimate.mean_rms << " m";
    std::cerr << " (summary in " << out_dir.string() << ")\n";
    return 1;
  }
  return 0;
}

int run(const CLI::App* command, const RunArgs& a) {
  Scene scene = load_scene(a.scene_path);
  RunOptions opt;
  opt.model = model_for_scene(scene, a.model);  // a model the cloth is not: exit 2, nothing written
  opt.progress = !a.quiet;
  apply_run_overrides(scene, overrides_of(command, a), opt.overrides);  // every rule before anything is written
  opt.out_dir =
      output_folder(command->count("--out") ? std::optional(a.out_dir) : std::nullopt,
                    std::filesystem::path("results") / std::filesystem::path(a.scene_path).stem() / opt.model);
  install_interrupt_handlers();
  return exit_code_of_run(run_scene(scene, opt), opt.out_dir);
}

}  // namespace

Command add_run_command(CLI::App& app) {
  auto args = std::make_shared<RunArgs>();
  CLI::App* command =
      app.add_subcommand("run", "Simulate a scene and write frames (VTU/PVD), metrics.csv and summary.json");
  add_options(command, *args);
  return {command, [command, args] { return run(command, *args); }};
}

}  // namespace wl::cli
