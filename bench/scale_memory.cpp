#include "bench/scale_memory.h"

#include <malloc.h>
#include <unistd.h>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <stdexcept>
#include <string>

#include "bench/step_timing.h"
#include "driver/memory_estimate.h"
#include "integrators/backward_euler.h"
#include "integrators/sparse_solver.h"
#include "models/core/term_model.h"
#include "models/model_factory.h"

namespace wl::bench {
namespace {

// Resident size of this process now [MB] (/proc/self/statm: pages), after
// glibc has returned the freed heap it keeps (malloc_trim): what is held, not
// what was held and freed.
double resident_mb() {
  malloc_trim(0);
  std::ifstream statm("/proc/self/statm");
  long size = 0, resident = 0;
  statm >> size >> resident;
  return static_cast<double>(resident) * static_cast<double>(sysconf(_SC_PAGESIZE)) / 1e6;
}

// Bytes of the assembly's scatter plans as the terms' stencils fix them
// (models/core/assembly.h, TermPlan): per element a column start per stencil
// DoF (4 bytes), a row place per block entry (2 bytes), its place in the
// colour order (4 bytes), and the term's own stencil of n DoF indices (4
// bytes each). Zero for a model that is not a TermModel.
double scatter_plan_bytes(const Model& model) {
  const auto* terms = dynamic_cast<const TermModel*>(&model);
  if (!terms) return 0.0;
  double bytes = 0.0;
  for (const auto& t : terms->terms()) {
    const double n = t->stencil_size();
    bytes += (4.0 * n + 2.0 * n * n + 4.0 + 4.0 * n) * t->num_elements();
  }
  return bytes;
}

// Bytes of the model's sparsity pattern (8-byte values, 32-bit row indices
// and column starts); the step matrix A is one more of its size.
double pattern_bytes(const Model& model) {
  const SparseMatrix& p = model.pattern();
  return 12.0 * static_cast<double>(p.nonZeros()) + 4.0 * (p.outerSize() + 1.0);
}

struct Arguments {
  std::string scene, model = "yarn", solver = "auto";
  int steps = 5, warmup = 2;
};

// What `weavelab run` would estimate for the scene run with this solver
// (driver/memory_estimate.h), to set beside the peaks measured.
double run_estimate_bytes(Scene scene, const Arguments& a) {
  scene.linear_solver = a.solver;
  return estimate_run_memory(scene, a.model).bytes;
}

// Fills `a`; returns an error message for bad arguments (empty when fine).
std::string parse(int argc, char** argv, Arguments& a) {
  for (int i = 0; i < argc; ++i) {
    const bool has_value = i + 1 < argc;
    if (!std::strcmp(argv[i], "--model") && has_value) a.model = argv[++i];
    else if (!std::strcmp(argv[i], "--linear-solver") && has_value) a.solver = argv[++i];
    else if (!std::strcmp(argv[i], "--steps") && has_value) a.steps = std::atoi(argv[++i]);
    else if (!std::strcmp(argv[i], "--warmup") && has_value) a.warmup = std::atoi(argv[++i]);
    else if (argv[i][0] != '-' && a.scene.empty()) a.scene = argv[i];
    else return std::string("unexpected argument '") + argv[i] + "'";
  }
  if (a.scene.empty()) return "a scene file is needed";
  if (a.steps < 1 || a.warmup < 1) return "--steps and --warmup: at least 1";
  return {};
}

// The be-linear steps of one scene and solver; prints the CSV header and row.
void measure_scale(const Scene& scene, const Arguments& a, LinearSolverMethod method) {
  const double rss_start = resident_mb();
  auto model = make_model(scene, a.model);
  const double peak_model = peak_resident_bytes() / 1e6;
  const double rss_model = resident_mb();
  BackwardEuler be(BackwardEuler::Variant::linear);
  IntegratorOptions opt;
  opt.dt = scene.dt_s;
  opt.linear_solver = method;
  be.initialize(*model, 0.0, model->initial_q(), model->initial_v(), opt);
  const double rss_initialized = resident_mb();
  auto checked_step = [&]() {
    const StepResult r = be.step(opt.dt);
    if (r.outcome != Outcome::ok)
      throw std::runtime_error("step at t = " + std::to_string(be.t()) + " s failed (" + to_string(r.outcome) +
                               "): " + r.message);
  };
  for (int k = 0; k < a.warmup; ++k) checked_step();
  const SparseSolver::Statistics before = be.solver().statistics();
  Timing step;
  for (int k = 0; k < a.steps; ++k) step.time(checked_step);
  const SparseSolver::Statistics& after = be.solver().statistics();
  const SparseSolver::Memory mem = be.solver().memory();
  std::printf(
      "scene,model,requested,solver,dofs,nnz,steps,step_ms,step_cpu_ms,krylov_per_step,factorizations_per_step,"
      "rss_start_mb,peak_model_mb,rss_model_mb,rss_initialized_mb,rss_end_mb,peak_mb,solver_matrices_mb,preconditioner_"
      "mb,"
      "krylov_mb,scatter_plans_mb,pattern_mb,estimate_mb\n");
  std::printf(
      "%s,%s,%s,\"%s\",%d,%ld,%d,%.3f,%.3f,%.2f,%.2f,%.1f,%.1f,%.1f,%.1f,%.1f,%.1f,%.1f,%.1f,%.1f,%.1f,%.1f,%.1f\n",
      a.scene.c_str(), a.model.c_str(), a.solver.c_str(), be.solver().description().c_str(), model->num_dofs(),
      static_cast<long>(model->pattern().nonZeros()), a.steps, step.wall_ms(), step.cpu_ms(),
      double(after.krylov_iterations - before.krylov_iterations) / a.steps,
      double(after.factorizations - before.factorizations) / a.steps, rss_start, peak_model, rss_model, rss_initialized,
      resident_mb(), peak_resident_bytes() / 1e6, mem.matrices / 1e6, mem.preconditioner / 1e6, mem.krylov / 1e6,
      scatter_plan_bytes(*model) / 1e6, pattern_bytes(*model) / 1e6, run_estimate_bytes(scene, a) / 1e6);
}

}  // namespace

int scale_main(int argc, char** argv) {
  Arguments a;
  if (const std::string bad = parse(argc, argv, a); !bad.empty()) {
    std::fprintf(stderr, "--scale: %s\n", bad.c_str());
    return 2;
  }
  Scene scene;
  LinearSolverMethod method;
  try {
    scene = load_scene(a.scene);
    method = parse_linear_solver(a.solver);
  } catch (const SceneError& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 2;
  } catch (const std::invalid_argument& e) {
    std::fprintf(stderr, "--linear-solver: %s\n", e.what());
    return 2;
  }
  try {
    measure_scale(scene, a, method);
  } catch (const std::invalid_argument& e) {  // a bad model name, or amg without hypre
    std::fprintf(stderr, "%s: %s\n", a.scene.c_str(), e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s: %s\n", a.scene.c_str(), e.what());
    return 1;
  }
  return 0;
}

}  // namespace wl::bench
