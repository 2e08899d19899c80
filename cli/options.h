// What several subcommands share: list parsing, the options of the two
// experiments (work-precision, stability), --time-steps with its old name
// --resolution, and the model a subcommand builds.
#pragma once
#include <CLI/CLI.hpp>
#include <string>
#include <vector>

#include "driver/run_settings.h"
#include "driver/time_steps.h"
#include "models/model_factory.h"
#include "models/scene/scene.h"

namespace wl::cli {

// "a, b, c"
std::string joined(const std::vector<std::string>& names);

// "a,b,c" → {"a", "b", "c"} (spaces and empty items dropped).
std::vector<std::string> split_list(const std::string& text);

// "1e-3,2e-3" → {1e-3, 2e-3}; each a number > 0, else std::invalid_argument naming `option`.
std::vector<double> split_numbers(const std::string& text, const std::string& option);

// Help of --model: the model names and the default, the scene's yarn level.
std::string model_help(const std::string& lead);

// The model `given` (--model, "" when not given) or the scene's yarn level
// (yarn_level_model); std::invalid_argument (exit 2) for a model the scene's
// cloth is not, naming the scene file and key.
std::string model_for_scene(const Scene& scene, const std::string& given);

// The comparisons (diagnose, modes, fidelity) build the scene's yarn level and
// its continuum: either one that would not fit in memory is refused before any
// work, as `run` refuses it (check_run_memory: SceneError, exit 2).
void check_comparison_memory(const Scene& scene);

// Options shared by the two experiments.
struct ExperimentArgs {
  std::string scene, models, integrators, out;
  double duration = 0;
  bool quiet = false;
};

void add_experiment_options(CLI::App* command, ExperimentArgs& args, const std::string& default_out);

// Loads the scene and applies --duration; fills path, text, scene, overrides,
// models (default the scene's yarn level and fem; each built once, so that a
// scene error only a model finds comes before any output), integrators and progress.
template <class Config>
void load_experiment_scene(const ExperimentArgs& args, CLI::App* command, Config& config) {
  config.scene_path = args.scene;
  config.scene = load_scene(args.scene);  // a missing or bad file is a SceneError (exit 2)
  config.scene_text = config.scene.text;
  if (command->count("--duration")) apply_duration_override(config.scene, args.duration, config.overrides);
  config.models =
      args.models.empty() ? std::vector<std::string>{yarn_level_model(config.scene), "fem"} : split_list(args.models);
  if (config.models.empty()) throw std::invalid_argument("--models: empty list");
  for (const std::string& m : config.models) {
    (void)model_for_scene(config.scene, m);
    // What only the model can refuse (a knit whose rest shape does not relax) is
    // refused before the study writes anything, as `run` refuses it.
    check_run_memory(config.scene, m);
    (void)make_model(config.scene, m);
  }
  config.integrators = split_list(args.integrators);
  config.progress = !args.quiet;
}

// --time-steps controlled|scene and --rtol; --resolution, the old name of
// --time-steps, still accepted with a notice on stderr.
struct TimeStepsArgs {
  std::string value, old_name_value;
  double rtol = 1e-4;
  CLI::Option *time_steps = nullptr, *resolution = nullptr;
};

// `default_value` "controlled" or "scene"; `help` describes --time-steps.
void add_time_steps_options(CLI::App* command, TimeStepsArgs& args, const std::string& default_value,
                            const std::string& help);

// The parsed --time-steps (or --resolution, with the notice); std::invalid_argument
// for a bad value, or for both names given.
TimeSteps time_steps_of(const TimeStepsArgs& args);

// Help of --time-steps for the comparisons (calibrate's validation, fidelity, diagnose).
extern const std::string kTimeStepsHelp;

}  // namespace wl::cli
