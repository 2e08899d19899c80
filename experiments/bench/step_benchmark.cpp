// Benchmark (not a test): the backward-Euler step against the factor+solve of
// the same step matrix, measured in one run (design.md "Performance stance").
//   weavelab_bench [--model yarn|fem] [--integrator be-linear] [scene ...]
// Default scenes: the hanging cloth at 17×17, 65×65 and 129×129.
//   weavelab_bench --compare-models [SCENE] [--steps N] [--yarn-steps M]
// FEM and yarn steps on one scene (compare_models.cpp).
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "experiments/bench/compare_models.h"
#include "experiments/driver/model_factory.h"
#include "integrators/backward_euler.h"
#include "models/scene/scene.h"

namespace {

using clock_type = std::chrono::steady_clock;

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

double mean(const std::vector<double>& v) {
  double s = 0;
  for (double x : v) s += x;
  return s / v.size();
}

struct Row {
  std::string scene;
  int dofs;
  long nnz;
  double step_mean, step_median, fs_median, assembly_median;
};

Row measure(const std::string& path, const std::string& model_name, const std::string& integrator) {
  wl::Scene scene = wl::load_scene(path);
  auto model = wl::make_model(scene, model_name);
  wl::BackwardEuler be(integrator == "be-newton" ? wl::BackwardEuler::Variant::newton
                                                 : wl::BackwardEuler::Variant::linear);
  wl::IntegratorOptions opt;
  opt.dt = scene.dt_s;
  be.initialize(*model, 0.0, model->initial_q(), model->initial_v(), opt);
  const int n = model->num_dofs();
  const int warmup = 3;
  const int steps = n < 5000 ? 100 : n < 50000 ? 20 : 8;
  for (int k = 0; k < warmup; ++k) be.step(opt.dt);
  std::vector<double> step_times;
  for (int k = 0; k < steps; ++k) {
    const auto t0 = clock_type::now();
    auto r = be.step(opt.dt);
    step_times.push_back(std::chrono::duration<double>(clock_type::now() - t0).count());
    if (r.outcome != wl::Outcome::ok) {
      std::fprintf(stderr, "%s: step failed: %s\n", path.c_str(), r.message.c_str());
      break;
    }
  }
  // The same step matrix, factorized and solved by a solver with its own
  // (untimed) symbolic analysis.
  const wl::SparseMatrix a = be.step_matrix();
  wl::SparseSolver solver(model->pattern(), model->fixed_dofs());
  wl::Vec b = wl::Vec::Ones(n), x;
  solver.factorize(a);  // the symbolic analysis, once, outside the timings
  std::vector<double> fs_times, asm_times;
  wl::Evaluation ev;
  wl::allocate_evaluation(*model, ev);
  for (int k = 0; k < steps; ++k) {
    const auto t0 = clock_type::now();
    solver.factorize(a);
    solver.solve(b, x);
    fs_times.push_back(std::chrono::duration<double>(clock_type::now() - t0).count());
    const auto t1 = clock_type::now();
    model->evaluate(be.t(), be.q(), be.v(), wl::kForce | wl::kDfdq | wl::kDfdv | wl::kMass, ev);
    asm_times.push_back(std::chrono::duration<double>(clock_type::now() - t1).count());
  }
  return {path, n, static_cast<long>(a.nonZeros()), mean(step_times), median(step_times), median(fs_times),
          median(asm_times)};
}

}  // namespace

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
      Row r = measure(s, model, integrator);
      std::printf("%-44s %8d %10ld %10.3f %10.3f %12.3f %12.3f %8.2f\n", r.scene.c_str(), r.dofs, r.nnz,
                  1e3 * r.step_mean, 1e3 * r.step_median, 1e3 * r.fs_median, 1e3 * r.assembly_median,
                  r.step_mean / r.fs_median);
      std::fflush(stdout);
    } catch (const std::exception& e) {
      std::fprintf(stderr, "%s: %s\n", s.c_str(), e.what());
      return 1;
    }
  }
  std::printf("ratio = mean step / median factor+solve of the same step matrix\n");
  return 0;
}
