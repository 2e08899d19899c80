// `weavelab fit SCENE --target RUN_DIR`: scene parameters fitted to a recorded run's trajectory.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <map>
#include <memory>
#include <sstream>

#include "cli/commands.h"
#include "cli/options.h"
#include "driver/fit_command.h"
#include "driver/interrupt.h"
#include "driver/run_settings.h"

namespace wl::cli {
namespace {

struct FitArgs {
  FitCommandConfig config;
  std::string scene, target, free, out, window;
  std::vector<std::string> starts, start_sets;
  int jobs = 1;
  TimeStepsArgs time_steps;
  bool quiet = false;
};

void add_options(CLI::App* fit, FitArgs& a) {
  FitCommandConfig& fitc = a.config;
  fit->add_option("scene", a.scene, "Scene file (TOML) to simulate")->required();
  fit->add_option("--target", a.target, "Output folder of a `weavelab run` whose frames are fitted")->required();
  fit->add_option("--free", a.free,
                  "Comma-separated scene keys to fit, e.g. contact.shear_modulus_Pa,yarn_types.yarn1.density_kg_per_m")
      ->required();
  fit->add_option("--start", a.starts, "Start value KEY=VALUE of a fitted key (repeatable; default the scene's)");
  fit->add_option("--start-set", a.start_sets,
                  "One more fit from these starts, KEY=VALUE,KEY=VALUE over --start (repeatable; the fits are "
                  "written to OUT/start_1, start_2, ...)");
  fit->add_option("--jobs", a.jobs, "Fits of --start-set run at once (each on its own models; same results)")
      ->capture_default_str();
  fit->add_option("--frames", fitc.frames, "Fit the target's first N frames after t = 0 (default all)");
  fit->add_option("--growing-window", a.window,
                  "N1,N2,...: fit the first N1 frames, then the first N2 from that result, ...; increasing, the "
                  "last equal to --frames (each stage at most --max-iterations). Default: a doubling window "
                  "(5,10,20,...) for more than 10 frames; off: one plain fit");
  fit->add_option("--model", fitc.fit.model, model_help("Model that is fitted"));
  fit->add_option("--integrator", fitc.fit.integrator,
                  "An integrator with parameter sensitivities: be-linear, be-newton or sdirk2 (default the scene's)");
  fit->add_option("--bound-factor", fitc.fit.bound_factor, "Bounds start/b ... start*b")->capture_default_str();
  fit->add_option("--max-iterations", fitc.fit.max_iterations, "Ceres iterations")->capture_default_str();
  fit->add_option("--fem-params", fitc.fem_params,
                  "FEM parameter file (as written by `calibrate` or `fit --model fem`): the continuum's values "
                  "where --start does not set them");
  add_time_steps_options(fit, a.time_steps, "scene",
                         "Time steps of the fitted simulations: scene (the scene's integrator and fixed step, as the "
                         "published fit) or controlled (sdirk2 under error control at --rtol, atol = 1e-3 rtol)");
  fit->add_option("--out", a.out, "Output folder (default results/fit/<scene name>)");
  fit->add_flag("--quiet", a.quiet, "No progress on stderr");
}

// KEY=VALUE into `start`; std::invalid_argument otherwise.
void read_start(const std::string& s, std::map<std::string, double>& start) {
  const auto eq = s.find('=');
  const std::vector<double> v =
      eq == std::string::npos ? std::vector<double>{} : split_numbers(s.substr(eq + 1), "--start " + s.substr(0, eq));
  if (v.size() != 1) throw std::invalid_argument("--start: got '" + s + "', expected KEY=VALUE with VALUE > 0");
  start[s.substr(0, eq)] = v[0];
}

// The configuration from the parsed options; std::invalid_argument for a bad value.
FitCommandConfig config_of(const CLI::App* fit, const FitArgs& a) {
  FitCommandConfig fitc = a.config;
  fitc.scene_path = a.scene;
  fitc.target_dir = a.target;
  fitc.fit.free = split_list(a.free);
  if (fitc.fit.free.empty()) throw std::invalid_argument("--free: empty list");
  for (const std::string& s : a.starts) read_start(s, fitc.fit.start);
  if (a.window == "off") fitc.default_window = false;
  else if (fit->count("--growing-window"))
    for (double x : split_numbers(a.window, "--growing-window")) {
      if (x != std::floor(x) || x > 1e6)
        throw std::invalid_argument("--growing-window: got '" + a.window +
                                    "', expected increasing frame counts N1,N2,... (e.g. 5,10,25) or off");
      fitc.fit.window.push_back(static_cast<int>(x));
    }
  if (a.jobs < 1) throw std::invalid_argument("--jobs: got " + std::to_string(a.jobs) + ", expected >= 1");
  if (fit->count("--frames") && fitc.frames < 1)
    throw std::invalid_argument("--frames: got " + std::to_string(fitc.frames) +
                                ", expected a count >= 1 (without --frames, all frames are fitted)");
  if (!(fitc.fit.bound_factor > 1.0 && std::isfinite(fitc.fit.bound_factor))) {
    std::ostringstream got;
    got << fitc.fit.bound_factor;
    throw std::invalid_argument("--bound-factor: got " + got.str() + ", expected a finite number > 1");
  }
  if (fit->count("--max-iterations") && fitc.fit.max_iterations < 1)
    throw std::invalid_argument("--max-iterations: got " + std::to_string(fitc.fit.max_iterations) + ", expected >= 1");
  fitc.fit.progress = !a.quiet;
  fitc.time_steps = time_steps_of(a.time_steps);
  fitc.out_dir = output_folder(fit->count("--out") ? std::optional(a.out) : std::nullopt,
                               std::filesystem::path("results/fit") / std::filesystem::path(a.scene).stem());
  return fitc;
}

// One more fit per --start-set, each into OUT/start_K.
std::vector<FitCommandConfig> start_sets_of(const FitCommandConfig& fitc, const FitArgs& a) {
  std::vector<FitCommandConfig> sets;
  for (const std::string& list : a.start_sets) {
    FitCommandConfig c = fitc;
    for (const std::string& s : split_list(list)) read_start(s, c.fit.start);
    c.out_dir = fitc.out_dir / ("start_" + std::to_string(sets.size() + 1));
    sets.push_back(std::move(c));
  }
  return sets;
}

int run_start_sets(const std::vector<FitCommandConfig>& sets, const FitCommandPlan& plan, int jobs) {
  bool all = true;
  const std::vector<TrajectoryFitResult> rs = run_fits(sets, plan, jobs);
  if (std::any_of(rs.begin(), rs.end(), [](const TrajectoryFitResult& r) { return r.interrupted; })) {
    std::cerr << "weavelab: fit: " << interrupted_message(interrupt_signal())
              << "; each start's record so far in its folder\n";
    return interrupted_exit_code(interrupt_signal());
  }
  for (size_t k = 0; k < rs.size(); ++k) {
    std::cerr << "weavelab: fit: " << sets[k].out_dir.string() << ": " << rs[k].iterations << " iterations, "
              << rs[k].wall_s << " s wall, " << rs[k].cpu_s << " s CPU; " << rs[k].message << "\n";
    all = all && rs[k].converged;
  }
  return all ? 0 : 1;
}

// The growing window when the rule chose it (before the fit runs).
void print_default_window(const FitCommandPlan& plan) {
  if (plan.window_rule != "default") return;
  std::string w;
  for (int f : plan.window) w += (w.empty() ? "" : ",") + std::to_string(f);
  std::cerr << "weavelab: fit: " << plan.target.size() << " frames, fitted through the growing window " << w
            << " (the default for a long window; --growing-window off for one plain fit)\n";
}

// The keys each stage held at their start.
void print_frozen(const TrajectoryFitResult& r) {
  for (size_t k = 0; k < r.stages.size(); ++k)
    for (const std::string& key : r.stages[k].frozen)
      std::cerr << "weavelab: fit: " << key << " held at its start in stage " << k + 1 << " (" << r.stages[k].frames
                << " frames): the frames do not depend on it there\n";
}

int run_one(const FitCommandConfig& fitc, const FitCommandPlan& plan) {
  print_default_window(plan);
  const TrajectoryFitResult r = run_fit(fitc, plan);
  if (r.interrupted) {
    std::cerr << "weavelab: fit: " << interrupted_message(interrupt_signal()) << " (" << r.message
              << "); the record so far in " << fitc.out_dir.string() << "\n";
    return interrupted_exit_code(interrupt_signal());
  }
  print_frozen(r);
  if (r.final_rms.empty()) {
    std::cerr << "weavelab: fit: " << r.message << "\n";
    return 1;
  }
  for (size_t k = 0; r.stages.size() > 1 && k < r.stages.size(); ++k)
    std::cerr << "weavelab: fit: stage " << k + 1 << ", " << r.stages[k].frames << " frames: " << r.stages[k].iterations
              << " iterations, " << r.stages[k].simulations << " simulations, " << r.stages[k].wall_s << " s wall, "
              << r.stages[k].cpu_s << " s CPU; " << r.stages[k].message << "\n";
  std::cerr << "weavelab: fit: " << r.iterations << " iterations, " << r.simulations << " simulations, " << r.wall_s
            << " s; RMS distance " << 1e3 * r.start_rms.back() << " mm at the "
            << (r.stages.size() > 1 ? "last stage's " : "") << "start, " << 1e3 * r.final_rms.back()
            << " mm fitted (last frame); " << r.message << "; results in " << fitc.out_dir.string() << "\n";
  for (const auto& p : r.parameters)
    std::cerr << "  " << p.key << " = " << p.value << " +- " << p.std_error << " (start " << p.start << ")"
              << (p.frozen          ? ", held at its start"
                  : !p.identifiable ? ", not identifiable"
                                    : "")
              << "\n";
  return r.converged ? 0 : 1;
}

int run(const CLI::App* fit, const FitArgs& a) {
  const FitCommandConfig fitc = config_of(fit, a);
  const std::vector<FitCommandConfig> sets = start_sets_of(fitc, a);
  for (const FitCommandConfig& c : sets) plan_fit(c);  // every input checked; nothing written yet
  const FitCommandPlan plan = plan_fit(fitc);
  if (!sets.empty()) print_default_window(plan);
  install_interrupt_handlers();
  return sets.empty() ? run_one(fitc, plan) : run_start_sets(sets, plan, a.jobs);
}

}  // namespace

Command add_fit_command(CLI::App& app) {
  auto args = std::make_shared<FitArgs>();
  CLI::App* command = app.add_subcommand(
      "fit",
      "Fit scene parameters to a recorded run's node trajectory (Ceres least squares with exact forward "
      "sensitivities); fit.json, convergence.csv, frames.csv");
  add_options(command, *args);
  return {command, [command, args] { return run(command, *args); }};
}

}  // namespace wl::cli
