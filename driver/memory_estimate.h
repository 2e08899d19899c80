// Memory a run needs, estimated from the scene before anything is allocated
// (docs/design.md §6.3, §11.1): the DoF count from the grid, times a per-DoF
// cost fitted above the peak resident sizes the scale study measures
// (experiments/scale/RESULTS.md): constant on the woven cloth's AMG route
// (its hierarchy grows with the matrix), growing like log₂(DoFs) with the fill
// of a nested-dissection factorization on the factor routes. A run whose
// estimate exceeds the memory available is refused (check_run_memory in
// run_settings.h).
#pragma once
#include <string>

#include "models/scene/scene.h"

namespace wl {

struct MemoryEstimate {
  long dofs = 0;
  double bytes = 0.0;
};

// DoFs of `model_name` ("yarn", "knit" or "fem") on the scene's grid (a knit's: its loops' contact nodes),
// and the estimated peak memory.
MemoryEstimate estimate_run_memory(const Scene& scene, const std::string& model_name);
// Whether the estimate takes the AMG route's fit: the woven yarn-level cloth
// with linear_solver amg, or auto where hypre is built and `dofs` is at least
// 2·kAmgMinFree (auto's amg from kAmgMinFree free DoFs on, whatever the
// handles pin). Every other case takes the factor routes' fit.
bool takes_amg_route(const Scene& scene, const std::string& model_name, long dofs);
// MemAvailable of /proc/meminfo (bytes); the physical memory where it cannot be read.
double available_memory_bytes();
// Largest resident size of this process so far (bytes).
double peak_resident_bytes();

}  // namespace wl
