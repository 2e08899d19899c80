#include "cli/options.h"

#include <iostream>
#include <stdexcept>

#include "driver/run_settings.h"
#include "integrators/integrator.h"
#include "models/model_factory.h"

namespace wl::cli {

const std::string kTimeStepsHelp =
    "Time steps of the comparison: controlled (sdirk2 under error control at --rtol) or scene (each "
    "scene's own integrator and fixed step)";

void check_comparison_memory(const Scene& scene) {
  check_run_memory(scene, yarn_level_model(scene));
  check_run_memory(scene, "fem");
}

std::string joined(const std::vector<std::string>& names) {
  std::string s;
  for (const auto& n : names) s += (s.empty() ? "" : ", ") + n;
  return s;
}

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

std::string model_help(const std::string& lead) {
  return lead + ": " + joined(model_names()) +
         " (default: the scene's yarn level, yarn for a woven and knit for a knitted cloth)";
}

std::string model_for_scene(const Scene& scene, const std::string& given) {
  const std::string model = given.empty() ? yarn_level_model(scene) : given;
  check_model_for_scene(scene, model);
  return model;
}

void add_experiment_options(CLI::App* command, ExperimentArgs& args, const std::string& default_out) {
  command->add_option("scene", args.scene, "Scene file (TOML)")->required();
  command->add_option("--models", args.models,
                      "Comma-separated models: " + joined(model_names()) +
                          " (default: the scene's yarn level and fem, yarn,fem for a woven cloth)");
  command->add_option("--integrators", args.integrators,
                      "Comma-separated integrators (default: all that apply): " + joined(integrator_names()));
  command->add_option("--duration", args.duration, "Simulated time [s] (overrides the scene)");
  command->add_option("--out", args.out, "Output folder (default " + default_out + ")");
  command->add_flag("--quiet", args.quiet, "No progress on stderr");
}

void add_time_steps_options(CLI::App* command, TimeStepsArgs& args, const std::string& default_value,
                            const std::string& help) {
  args.value = default_value;
  args.time_steps = command->add_option("--time-steps", args.value, help)->capture_default_str();
  args.resolution =
      command->add_option("--resolution", args.old_name_value, "Deprecated: the old name of --time-steps");
  command->add_option("--rtol", args.rtol, "Tolerance of --time-steps controlled")->capture_default_str();
}

TimeSteps time_steps_of(const TimeStepsArgs& args) {
  if (args.resolution->count() == 0) return parse_time_steps("--time-steps", args.value, args.rtol);
  if (args.time_steps->count() > 0)
    throw std::invalid_argument("--resolution: the old name of --time-steps, expected only one of the two");
  std::cerr << "weavelab: --resolution is deprecated: use --time-steps\n";
  return parse_time_steps("--resolution", args.old_name_value, args.rtol);
}

}  // namespace wl::cli
