// One measurement shared by the benchmarks: a model's backward-Euler steps,
// each followed by the factor+solve of that very step matrix (a second solver,
// symbolic analysis untimed) and the assembly alone, as wall and process-CPU
// medians (docs/design.md §11: ratios measured in one run).
#pragma once
#include <chrono>
#include <string>
#include <vector>

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
  bool parts = false;  // factor+solve and assembly measured
  Timing step, factor_solve, assembly;
};

// `warmup` untimed steps, then `steps` timed ones (with factor+solve and
// assembly when `parts`). Throws std::runtime_error when a step fails.
Figures measure(const Scene& scene, const std::string& model_name, const std::string& integrator, int warmup,
                int steps, bool parts);

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
