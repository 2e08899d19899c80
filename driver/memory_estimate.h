// Memory a run needs, estimated from the scene before anything is allocated
// (docs/design.md §11): the DoF count from the grid, times a per-DoF cost
// that grows like log₂(DoFs) with the fill of a nested-dissection
// factorization of a 2D grid, fitted above the peak resident sizes of the
// hanging cloth measured at 257×257. A run whose estimate exceeds the memory
// available is refused (check_run_memory in run_settings.h).
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
// MemAvailable of /proc/meminfo (bytes); the physical memory where it cannot be read.
double available_memory_bytes();
// Largest resident size of this process so far (bytes).
double peak_resident_bytes();

}  // namespace wl
