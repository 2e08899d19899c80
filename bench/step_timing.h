// One measurement shared by the benchmarks: a model's backward-Euler steps
// with a given linear solver, each followed by two references on that very
// step matrix A (second solvers, symbolic analyses untimed): the UMFPACK
// factor+solve of A, and the CHOLMOD LLᵀ factor+solve of its symmetric part
// (A + Aᵀ)/2 (forming it untimed); then the assembly alone. Wall and
// process-CPU medians (docs/design.md §11: ratios measured in one run).
#pragma once
#include <chrono>
#include <string>
#include <vector>

#include "integrators/sparse_solver.h"
#include "models/scene/scene.h"

namespace wl::bench {

// Wall and process-CPU durations of repeated timed sections.
struct Timing {
  std::vector<double> wall, cpu;
  template <class F>
  void time(F&& f);
  double wall_ms() const;
  double cpu_ms() const;
  double mean_wall_ms() const;
};

struct Figures {
  std::string model;
  int dofs = 0;
  long nnz = 0;
  int steps = 0;
  bool parts = false;  // references and assembly measured
  std::string solver;  // the step's solver (SparseSolver::description())
  double factorizations_per_step = 0.0, krylov_per_step = 0.0;
  double peak_mb = 0.0;                                    // peak resident size of the process after the measurement
  Timing step, factor_solve, cholmod_reference, assembly;  // factor_solve: UMFPACK of A
};

// `warmup` untimed steps, then `steps` timed ones (with factor+solve and
// assembly when `parts`). Throws std::invalid_argument for an integrator that
// is not backward Euler, std::runtime_error when a step fails.
Figures measure(const Scene& scene, const std::string& model_name, const std::string& integrator, int warmup, int steps,
                bool parts, LinearSolverMethod method = LinearSolverMethod::automatic);

double process_cpu_s();

template <class F>
void Timing::time(F&& f) {
  const auto w0 = std::chrono::steady_clock::now();
  const double c0 = process_cpu_s();
  f();
  cpu.push_back(process_cpu_s() - c0);
  wall.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - w0).count());
}

}  // namespace wl::bench
