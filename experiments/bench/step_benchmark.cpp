// Benchmark (not a test): the backward-Euler step against the factor+solve of
// the same step matrix, measured in one run (docs/design.md §11).
//   weavelab_bench [--model yarn|fem] [--integrator be-linear] [scene ...]
// Default scenes: the hanging cloth at 17×17, 65×65 and 129×129.
//   weavelab_bench --compare-models [SCENE] [--steps N] [--yarn-steps M]
// FEM and yarn steps on one scene (compare_models.cpp).
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "experiments/bench/compare_models.h"
#include "experiments/bench/step_timing.h"

int main(int argc, char** argv) {
  if (argc > 1 && !std::strcmp(argv[1], "--compare-models")) return wl::bench::compare_models_main(argc - 2, argv + 2);
  std::string model = "yarn", integrator = "be-linear";
  std::vector<std::string> scenes;
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--model") && i + 1 < argc) model = argv[++i];
    else if (!std::strcmp(argv[i], "--integrator") && i + 1 < argc) integrator = argv[++i];
    else if (!std::strcmp(argv[i], "--help")) {
      std::printf("usage: weavelab_bench [--model yarn|fem] [--integrator be-linear|be-newton] [scene.toml ...]\n"
                  "       weavelab_bench --compare-models [SCENE] [--steps N] [--yarn-steps M]\n");
      return 0;
    } else scenes.push_back(argv[i]);
  }
  if (scenes.empty())
    scenes = {"experiments/scenes/hanging_wind.toml", "experiments/scenes/hanging_wind_65.toml",
              "experiments/scenes/hanging_wind_129.toml"};
  std::printf("model %s, integrator %s; times in ms (step: mean and median over the timed steps)\n", model.c_str(),
              integrator.c_str());
  std::printf("%-44s %8s %10s %10s %10s %12s %12s %8s\n", "scene", "dofs", "nnz", "step_mean", "step_med",
              "factor+solve", "assembly", "ratio");
  for (const auto& s : scenes) {
    try {
      const wl::Scene scene = wl::load_scene(s);
      // Fewer timed steps where one factorization takes seconds.
      const int n = scene.nodes_u() * scene.nodes_v();
      const int steps = n < 1000 ? 100 : n < 10000 ? 20 : 8;
      const wl::bench::Figures f = wl::bench::measure(scene, model, integrator, 3, steps, true);
      std::printf("%-44s %8d %10ld %10.3f %10.3f %12.3f %12.3f %8.2f\n", s.c_str(), f.dofs, f.nnz,
                  f.step.mean_wall_ms(), f.step.wall_ms(), f.factor_solve.wall_ms(), f.assembly.wall_ms(),
                  f.step.mean_wall_ms() / f.factor_solve.wall_ms());
      std::fflush(stdout);
    } catch (const std::exception& e) {
      std::fprintf(stderr, "%s: %s\n", s.c_str(), e.what());
      return 1;
    }
  }
  std::printf("ratio = mean step / median factor+solve of the same step matrix\n");
  return 0;
}
