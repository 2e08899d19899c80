// `weavelab info SCENE`: DoFs, nodes, terms and pattern of a scene's model.
#include <iostream>
#include <memory>

#include "cli/commands.h"
#include "cli/options.h"
#include "models/model_factory.h"

namespace wl::cli {
namespace {

struct InfoArgs {
  std::string scene, model, fem_params;
};

int run(const InfoArgs& a) {
  Scene scene = load_scene(a.scene);
  if (!a.fem_params.empty()) scene.fem.parameter_file = a.fem_params;
  auto m = make_model(scene, model_for_scene(scene, a.model));
  std::cout << "scene: " << a.scene << "\n";
  for (const auto& [k, v] : m->describe()) std::cout << k << ": " << v << "\n";
  return 0;
}

}  // namespace

Command add_info_command(CLI::App& app) {
  auto args = std::make_shared<InfoArgs>();
  CLI::App* command = app.add_subcommand("info", "Print DoFs, nodes, terms and pattern of a scene's model");
  command->add_option("scene", args->scene, "Scene file (TOML)")->required();
  command->add_option("--model", args->model, model_help("Model"));
  command->add_option("--fem-params", args->fem_params,
                      "FEM parameter file (from `calibrate` or `fit`) for the continuum");
  return {command, [args] { return run(*args); }};
}

}  // namespace wl::cli
