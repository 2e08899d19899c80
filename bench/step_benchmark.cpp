// Benchmark (not a test): the backward-Euler step against the factor+solve of
// the same step matrix, measured in one run (docs/design.md §11).
//   weavelab_bench [--model yarn|fem] [--integrator be-linear] [--linear-solvers umfpack,auto] [scene ...]
// Default scenes: the hanging cloth at 17×17, 65×65 and 129×129; each with
// every listed step solver, against UMFPACK and CHOLMOD references.
//   weavelab_bench --compare-models [SCENE] [--steps N] [--yarn-steps M]
// FEM and yarn steps on one scene (compare_models.cpp).
//   weavelab_bench --scale SCENE [--model M] [--linear-solver NAME] [--steps N] [--warmup W]
// Time and memory of one scene's step with one solver (scale_memory.cpp).
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <sstream>
#include <string>
#include <vector>

#include "bench/compare_models.h"
#include "bench/scale_memory.h"
#include "bench/step_timing.h"

int main(int argc, char** argv) {
  if (argc > 1 && !std::strcmp(argv[1], "--compare-models")) return wl::bench::compare_models_main(argc - 2, argv + 2);
  if (argc > 1 && !std::strcmp(argv[1], "--scale")) return wl::bench::scale_main(argc - 2, argv + 2);
  std::string model = "yarn", integrator = "be-linear";
  std::vector<std::string> scenes, solvers = {"umfpack", "auto"};
  int steps_override = 0;
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--model") && i + 1 < argc) model = argv[++i];
    else if (!std::strcmp(argv[i], "--integrator") && i + 1 < argc) integrator = argv[++i];
    else if (!std::strcmp(argv[i], "--steps") && i + 1 < argc) steps_override = std::atoi(argv[++i]);
    else if (!std::strcmp(argv[i], "--linear-solvers") && i + 1 < argc) {
      solvers.clear();
      std::stringstream list(argv[++i]);
      for (std::string name; std::getline(list, name, ',');) solvers.push_back(name);
    } else if (!std::strcmp(argv[i], "--help")) {
      std::printf(
          "usage: weavelab_bench [--model yarn|fem] [--integrator be-linear|be-newton]\n"
          "                      [--linear-solvers umfpack,auto,...] [--steps N] [scene.toml ...]\n"
          "       weavelab_bench --compare-models [SCENE] [--steps N] [--yarn-steps M]\n"
          "       weavelab_bench --scale SCENE [--model yarn|fem] [--linear-solver NAME] [--steps N] [--warmup W]\n");
      return 0;
    } else scenes.push_back(argv[i]);
  }
  if (scenes.empty())
    scenes = {"experiments/scenes/hanging_wind.toml", "experiments/scenes/hanging_wind_65.toml",
              "experiments/scenes/hanging_wind_129.toml"};
  // Bad input is refused (exit 2) before anything is printed or timed.
  std::vector<wl::Scene> loaded;
  std::vector<wl::LinearSolverMethod> methods;
  try {
    for (const auto& s : scenes) loaded.push_back(wl::load_scene(s));
    for (const auto& solver : solvers) methods.push_back(wl::parse_linear_solver(solver));
  } catch (const wl::SceneError& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 2;
  } catch (const std::invalid_argument& e) {
    std::fprintf(stderr, "--linear-solvers: %s\n", e.what());
    return 2;
  }
  std::printf(
      "model %s, integrator %s; times in ms, medians over the timed steps (step_mean: mean); wall unless _cpu\n"
      "umfpack = factor+solve of the step matrix A with UMFPACK LU (the reference);\n"
      "chol(S) = CHOLMOD LLT factor+solve of S = (A + A^T)/2 of the same matrix\n",
      model.c_str(), integrator.c_str());
  std::printf("%-40s %-8s %7s %9s %9s %9s %9s %9s %9s %9s %9s %7s %7s %6s %6s %7s  %s\n", "scene", "solver", "dofs",
              "nnz", "step_mean", "step", "step_cpu", "umfpack", "chol(S)", "chol_cpu", "assembly", "/umfp", "/chol",
              "fact", "krylov", "peak_MB", "chosen");
  for (size_t k = 0; k < scenes.size(); ++k) {
    const std::string& s = scenes[k];
    const wl::Scene& scene = loaded[k];
    for (size_t m = 0; m < solvers.size(); ++m) {
      const std::string& solver = solvers[m];
      try {
        // Fewer timed steps where one factorization takes seconds.
        const int n = scene.nodes_u() * scene.nodes_v();
        const int steps = steps_override > 0 ? steps_override : n < 1000 ? 100 : n < 10000 ? 20 : 8;
        const wl::bench::Figures f = wl::bench::measure(scene, model, integrator, 3, steps, true, methods[m]);
        std::printf("%-40s %-8s %7d %9ld %9.3f %9.3f %9.3f %9.3f %9.3f %9.3f %9.3f %7.2f %7.2f %6.2f %6.1f %7.0f  %s\n",
                    s.c_str(), solver.c_str(), f.dofs, f.nnz, f.step.mean_wall_ms(), f.step.wall_ms(), f.step.cpu_ms(),
                    f.factor_solve.wall_ms(), f.cholmod_reference.wall_ms(), f.cholmod_reference.cpu_ms(),
                    f.assembly.wall_ms(), f.step.wall_ms() / f.factor_solve.wall_ms(),
                    f.step.wall_ms() / f.cholmod_reference.wall_ms(), f.factorizations_per_step, f.krylov_per_step,
                    f.peak_mb, f.solver.c_str());
        std::fflush(stdout);
      } catch (const std::invalid_argument& e) {  // a bad option or scene value
        std::fprintf(stderr, "%s: %s\n", s.c_str(), e.what());
        return 2;
      } catch (const std::exception& e) {
        std::fprintf(stderr, "%s: %s\n", s.c_str(), e.what());
        return 1;
      }
    }
  }
  std::printf(
      "/umfp, /chol = median step / median umfpack, chol(S); fact = factorizations per step; krylov = GMRES\n"
      "iterations per step; peak_MB = peak resident size of the benchmark process so far\n");
  return 0;
}
