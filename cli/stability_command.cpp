// `weavelab stability SCENE`: the largest bounded fixed step per integrator, model and stiffness.
#include <iostream>
#include <memory>

#include "cli/commands.h"
#include "cli/exit_codes.h"
#include "cli/options.h"
#include "driver/run_settings.h"
#include "driver/stability.h"

namespace wl::cli {
namespace {

struct StabilityArgs {
  ExperimentArgs experiment;
  std::string multipliers = "1,10,100,1000";
  double dt_min = 1e-6, dt_max = 1e-2, speed_bound = 10.0;
  int bisections = 8;
};

void add_options(CLI::App* st, StabilityArgs& a) {
  add_experiment_options(st, a.experiment, "results/stability");
  st->add_option("--multipliers", a.multipliers, "Stretch-modulus multipliers")->capture_default_str();
  st->add_option("--dt-min", a.dt_min, "Smallest step probed [s]")->capture_default_str();
  st->add_option("--dt-max", a.dt_max, "Largest step probed [s]")->capture_default_str();
  st->add_option("--bisections", a.bisections, "Bisections on log dt")->capture_default_str();
  st->add_option("--speed-bound", a.speed_bound, "Max node speed of a bounded run [m/s]")->capture_default_str();
}

int run(CLI::App* st, const StabilityArgs& a) {
  StabilityConfig c;
  load_experiment_scene(a.experiment, st, c);
  c.multipliers = split_numbers(a.multipliers, "--multipliers");
  c.dt_min = positive_option("--dt-min", a.dt_min);
  c.dt_max = positive_option("--dt-max", a.dt_max);
  c.bisections = a.bisections;
  c.speed_bound = positive_option("--speed-bound", a.speed_bound);
  c.out_dir = output_folder(st->count("--out") ? std::optional(a.experiment.out) : std::nullopt, "results/stability");
  return interruptible("stability", c.out_dir, [&] {
    const auto r = run_stability(c);
    std::cerr << "weavelab: stability: " << r.rows.size() << " cells in " << r.wall_s << " s; results in "
              << c.out_dir.string() << "\n";
    return 0;
  });
}

}  // namespace

Command add_stability_command(CLI::App& app) {
  auto args = std::make_shared<StabilityArgs>();
  CLI::App* command = app.add_subcommand("stability",
                                         "Largest bounded fixed step per integrator x model x stretch-modulus "
                                         "multiplier (bisection on log dt) and the failure mode above it; CSV + JSON");
  add_options(command, *args);
  return {command, [command, args] { return run(command, *args); }};
}

}  // namespace wl::cli
