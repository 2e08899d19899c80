// `weavelab work-precision SCENE`: error against CPU time per model and integrator.
#include <iostream>
#include <memory>

#include "cli/commands.h"
#include "cli/exit_codes.h"
#include "cli/options.h"
#include "driver/run_settings.h"
#include "driver/work_precision.h"

namespace wl::cli {
namespace {

struct WorkPrecisionArgs {
  ExperimentArgs experiment;
  std::string rtols, reference_rtols, reference_dir = "results/reference";
  double dt_max = 4e-3, dt_min = 4e-3 / 256, budget = 30.0;
};

void add_options(CLI::App* wp, WorkPrecisionArgs& a) {
  add_experiment_options(wp, a.experiment, "results/work_precision");
  wp->add_option("--rtols", a.rtols, "Tolerance ladder of the adaptive methods (default 1e-3,1e-4,...,1e-8)");
  wp->add_option("--dt-max", a.dt_max, "Largest fixed step [s]; the ladder halves it")->capture_default_str();
  wp->add_option("--dt-min", a.dt_min, "Smallest fixed step [s]")->capture_default_str();
  wp->add_option("--budget", a.budget, "CPU seconds a single run may be predicted to take before a ladder stops")
      ->capture_default_str();
  wp->add_option("--reference-rtols", a.reference_rtols,
                 "Reference tolerances, tried in order (default 1e-10,1e-9,1e-8)");
  wp->add_option("--reference-dir", a.reference_dir, "Reference cache folder")->capture_default_str();
}

int run(CLI::App* wp, const WorkPrecisionArgs& a) {
  WorkPrecisionConfig c;
  load_experiment_scene(a.experiment, wp, c);
  if (c.integrators.empty()) c.integrators = integrator_names();
  if (!a.rtols.empty()) c.rtols = split_numbers(a.rtols, "--rtols");
  if (!a.reference_rtols.empty()) c.reference.rtols = split_numbers(a.reference_rtols, "--reference-rtols");
  for (double rtol : c.rtols) check_rtol("--rtols", rtol);
  for (double rtol : c.reference.rtols) check_rtol("--reference-rtols", rtol);
  if (positive_option("--dt-min", a.dt_min) > positive_option("--dt-max", a.dt_max))
    throw std::invalid_argument("--dt-min/--dt-max: need 0 < dt-min <= dt-max");
  positive_option("--budget", a.budget);
  c.dt_max = a.dt_max;
  c.dt_min = a.dt_min;
  c.run_budget_cpu_s = a.budget;
  c.reference.cache_dir = a.reference_dir;
  c.reference.progress = c.progress;
  c.out_dir =
      output_folder(wp->count("--out") ? std::optional(a.experiment.out) : std::nullopt, "results/work_precision");
  return interruptible("work-precision", c.out_dir, [&] {
    return numerical_failure_is_exit_1("work-precision", [&] {  // e.g. a reference that does not reach its end
      const auto r = run_work_precision(c);
      std::cerr << "weavelab: work-precision: " << r.rows.size() << " runs in " << r.wall_s << " s; results in "
                << c.out_dir.string() << "\n";
      return 0;
    });
  });
}

}  // namespace

Command add_work_precision_command(CLI::App& app) {
  auto args = std::make_shared<WorkPrecisionArgs>();
  CLI::App* command =
      app.add_subcommand("work-precision",
                         "Error against CPU time: per model and integrator a ladder of tolerances (adaptive) or "
                         "step sizes (fixed-step), error against a cached IDA reference; CSV + JSON");
  add_options(command, *args);
  return {command, [command, args] { return run(command, *args); }};
}

}  // namespace wl::cli
