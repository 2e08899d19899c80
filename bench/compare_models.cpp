// Benchmark (not a test): FEM and yarn be-linear steps on the same scene, and
// the FEM step against its own factor+solve, in one run (target: at most 2×;
// docs/design.md §11). See compare_models.h for the command line.
//
// Per timed step k of a model: the whole BackwardEuler::step (assembly of
// f, ∂f/∂q, ∂f/∂v, M; forming M − h∂f/∂v − h²∂f/∂q; factorize; solve; state
// check), then — for the FEM — the factor+solve of that very step matrix with
// a second solver whose symbolic analysis is done before timing, and the
// assembly alone at the new state. Medians over the timed steps, as wall and
// process CPU time (the CPU time is steadier on a shared machine).
#include "bench/compare_models.h"

#include "bench/step_timing.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "integrators/backward_euler.h"
#include "integrators/sparse_solver.h"
#include "models/model_factory.h"
#include "models/scene/scene.h"

namespace wl::bench {
namespace {

std::string load_average() {
  std::ifstream in("/proc/loadavg");
  std::string one;
  if (!(in >> one)) return "unknown";
  return one;
}

int positive_int(const char* flag, const char* value) {
  char* end = nullptr;
  const long n = std::strtol(value, &end, 10);
  if (!end || *end || n <= 0 || n > 100000)
    throw std::invalid_argument(std::string(flag) + ": got '" + value + "', expected a positive integer");
  return static_cast<int>(n);
}

void usage(std::FILE* to) {
  std::fprintf(to,
               "usage: weavelab_bench --compare-models [SCENE] [--steps N] [--yarn-steps M]\n"
               "  SCENE          scene file (default experiments/scenes/hanging_wind_65.toml)\n"
               "  --steps N      timed FEM steps (default 20; 3 warm-up steps before)\n"
               "  --yarn-steps M timed yarn steps (default 3; 1 warm-up step before)\n");
}

}  // namespace

int compare_models_main(int argc, char** argv) {
  std::string scene_path = "experiments/scenes/hanging_wind_65.toml";
  int fem_steps = 20, yarn_steps = 3;
  try {
    bool scene_given = false;
    for (int i = 0; i < argc; ++i) {
      const char* a = argv[i];
      if (!std::strcmp(a, "--help")) {
        usage(stdout);
        return 0;
      } else if (!std::strcmp(a, "--steps") || !std::strcmp(a, "--yarn-steps")) {
        if (i + 1 >= argc) throw std::invalid_argument(std::string(a) + ": missing value");
        (!std::strcmp(a, "--steps") ? fem_steps : yarn_steps) = positive_int(a, argv[++i]);
      } else if (a[0] == '-' || scene_given) {
        throw std::invalid_argument(std::string("unexpected argument '") + a + "'");
      } else {
        scene_path = a;
        scene_given = true;
      }
    }
  } catch (const std::invalid_argument& e) {
    std::fprintf(stderr, "weavelab_bench --compare-models: %s\n", e.what());
    usage(stderr);
    return 2;
  }

  Scene scene;
  try {
    scene = load_scene(scene_path);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "weavelab_bench --compare-models: %s\n", e.what());
    return 2;
  }
  std::printf("compare-models: %s, be-linear, h = %g s; %u hardware threads, load average %s at start\n",
              scene_path.c_str(), scene.dt_s, std::thread::hardware_concurrency(), load_average().c_str());
  std::printf("medians over the timed steps, ms (wall / process CPU)\n");
  std::fflush(stdout);

  std::vector<Figures> rows;
  try {
    rows.push_back(measure(scene, "fem", "be-linear", 3, fem_steps, true));
    rows.push_back(measure(scene, "yarn", "be-linear", 1, yarn_steps, false));
  } catch (const std::exception& e) {
    std::fprintf(stderr, "weavelab_bench --compare-models: %s: %s\n", scene_path.c_str(), e.what());
    return 1;
  }

  std::printf("%-5s %7s %9s %6s %21s %21s %21s\n", "model", "dofs", "nnz", "steps", "step", "factor+solve", "assembly");
  auto pair = [](double w, double c) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%9.2f / %9.2f", w, c);
    return std::string(buf);
  };
  for (const Figures& f : rows)
    std::printf("%-5s %7d %9ld %6d %21s %21s %21s\n", f.model.c_str(), f.dofs, f.nnz, f.steps,
                pair(f.step.wall_ms(), f.step.cpu_ms()).c_str(),
                f.parts ? pair(f.factor_solve.wall_ms(), f.factor_solve.cpu_ms()).c_str() : "-",
                f.parts ? pair(f.assembly.wall_ms(), f.assembly.cpu_ms()).c_str() : "-");
  const Figures& fem = rows[0];
  const Figures& yarn = rows[1];
  const double ratio_wall = fem.step.wall_ms() / fem.factor_solve.wall_ms();
  const double ratio_cpu = fem.step.cpu_ms() / fem.factor_solve.cpu_ms();
  std::printf("FEM step / its own factor+solve: %.2f wall, %.2f CPU (target: at most 2) -> %s\n", ratio_wall, ratio_cpu,
              std::max(ratio_wall, ratio_cpu) <= 2.0 ? "ok" : "ABOVE 2");
  std::printf("yarn step / FEM step: %.1f wall, %.1f CPU\n", yarn.step.wall_ms() / fem.step.wall_ms(),
              yarn.step.cpu_ms() / fem.step.cpu_ms());
  return 0;
}

}  // namespace wl::bench
