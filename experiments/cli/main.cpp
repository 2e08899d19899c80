// weavelab command line: `weavelab run SCENE`, `weavelab info SCENE`.
// Exit codes: 0 success, 1 numerical failure (outcome in the summary),
// 2 bad scene or bad arguments, 3 output could not be written.
#include <CLI/CLI.hpp>
#include <filesystem>
#include <iostream>

#include "experiments/driver/model_factory.h"
#include "experiments/driver/run.h"
#include "integrators/integrator.h"
#include "models/scene/scene.h"

namespace {

std::string joined(const std::vector<std::string>& names) {
  std::string s;
  for (const auto& n : names) s += (s.empty() ? "" : ", ") + n;
  return s;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"weavelab: yarn-level and continuum cloth under pluggable integrators"};
  app.require_subcommand(1);

  std::string scene_path, model = "yarn", integrator, out_dir;
  double dt = 0, duration = 0;
  bool quiet = false;
  auto* run = app.add_subcommand("run", "Simulate a scene and write frames (VTU/PVD), metrics.csv and summary.json");
  run->add_option("scene", scene_path, "Scene file (TOML)")->required();
  run->add_option("--model", model, "Model: " + joined(wl::model_names()))->capture_default_str();
  run->add_option("--integrator", integrator, "Integrator (overrides the scene): " + joined(wl::integrator_names()));
  run->add_option("--dt", dt, "Time step [s] (overrides the scene)");
  run->add_option("--duration", duration, "Simulated time [s] (overrides the scene)");
  run->add_option("--out", out_dir, "Output folder (default results/<scene name>/<model>)");
  run->add_flag("--quiet", quiet, "No progress on stderr");

  std::string info_scene, info_model = "yarn";
  auto* info = app.add_subcommand("info", "Print DoFs, nodes, terms and pattern of a scene's model");
  info->add_option("scene", info_scene, "Scene file (TOML)")->required();
  info->add_option("--model", info_model, "Model: " + joined(wl::model_names()))->capture_default_str();

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? 0 : 2;
  }

  try {
    if (*info) {
      wl::Scene scene = wl::load_scene(info_scene);
      auto m = wl::make_model(scene, info_model);
      std::cout << "scene: " << info_scene << "\n";
      for (const auto& [k, v] : m->describe()) std::cout << k << ": " << v << "\n";
      return 0;
    }
    wl::Scene scene = wl::load_scene(scene_path);
    wl::RunOptions opt;
    opt.model = model;
    opt.progress = !quiet;
    if (!integrator.empty()) {
      scene.integrator = integrator;
      opt.overrides["integrator"] = integrator;
    }
    if (dt > 0) {
      scene.dt_s = dt;
      opt.overrides["dt_s"] = std::to_string(dt);
    }
    if (duration > 0) {
      scene.duration_s = duration;
      opt.overrides["duration_s"] = std::to_string(duration);
    }
    if (run->count("--dt") && dt <= 0) throw std::invalid_argument("--dt must be > 0, got " + std::to_string(dt));
    if (run->count("--duration") && duration <= 0)
      throw std::invalid_argument("--duration must be > 0, got " + std::to_string(duration));
    (void)wl::make_integrator(scene.integrator);  // validates the name before anything is written
    opt.out_dir = out_dir.empty()
                      ? std::filesystem::path("results") / std::filesystem::path(scene_path).stem() / model
                      : std::filesystem::path(out_dir);
    wl::RunReport rep = wl::run_scene(scene, opt);
    if (rep.result.outcome != wl::Outcome::ok) {
      std::cerr << "weavelab: run ended with outcome '" << wl::to_string(rep.result.outcome) << "' at t = " << rep.end_time
                << " s: " << rep.result.message << " (summary in " << opt.out_dir.string() << ")\n";
      return rep.result.outcome == wl::Outcome::not_offered ? 2 : 1;
    }
    return 0;
  } catch (const wl::SceneError& e) {
    std::cerr << "weavelab: bad scene: " << e.what() << "\n";
    return 2;
  } catch (const std::invalid_argument& e) {
    std::cerr << "weavelab: " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "weavelab: " << e.what() << "\n";
    return 3;
  }
}
