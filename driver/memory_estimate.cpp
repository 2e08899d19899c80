#include "driver/memory_estimate.h"

#include "integrators/amg_preconditioner.h"
#include "integrators/sparse_solver.h"

#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

namespace wl {
namespace {

// The factor routes (gmres's LLᵀ, cholmod, umfpack): peak ≈ kProcess + DoFs ·
// (kBase + kPerLog2 · log₂ DoFs), the factor's fill growing like n log n; an
// upper fit to the peaks of `weavelab run` on the hanging cloth up to 257×257
// with those solvers, measured before the cuts of docs/design.md §11.1 (their
// peaks have only come down since).
constexpr double kProcess = 64e6;
constexpr double kBase = 4000.0;
constexpr double kPerLog2 = 700.0;
// The AMG route of the woven cloth: peak ≈ kProcess + DoFs · kAmgPerDof, the
// hierarchy growing with the entries of A as the matrix does; 20 % above the
// largest peak per DoF of the woven cloth's amg rows in the scale study
// (experiments/scale/RESULTS.md, whole runs and steps).
constexpr double kAmgPerDof = 6100.0;

// A knit's DoFs (docs/models.md §11.1): 4 contact nodes per loop and contact
// row (two sides, two ends) on courses + 1 contact rows, 3 coordinates each;
// when sliding, one sliding coordinate per yarn through the two-yarn nodes
// (courses − 1 inner contact rows) off the frozen first and last wale.
long knit_dofs(const KnitPattern& k, bool sliding) {
  const long courses = k.courses, wales = k.wales;
  const long nodes = 4 * wales * (courses + 1);
  return 3 * nodes + (sliding ? 8 * std::max(0L, courses - 1) * std::max(0L, wales - 2) : 0);
}

}  // namespace

bool takes_amg_route(const Scene& scene, const std::string& model_name, long dofs) {
  if (model_name != "yarn" || scene.knit) return false;  // measured on the woven cloth only
  if (scene.linear_solver == "amg") return true;
  // auto takes amg from kAmgMinFree free DoFs on (nearly symmetric A); at twice
  // as many DoFs no set of handles pins enough to keep it below.
  return scene.linear_solver == "auto" && amg_available() && dofs >= 2L * kAmgMinFree;
}

MemoryEstimate estimate_run_memory(const Scene& scene, const std::string& model_name) {
  // A knit's continuum lies on its contact grid: 2·wales columns, courses + 1 rows (docs/models.md §11.9).
  const long w = scene.knit ? 2L * scene.knit->wales : scene.warps,
             h = scene.knit ? scene.knit->courses + 1L : scene.wefts;
  MemoryEstimate e;
  if (model_name == "fem") {
    const long k = std::max(1, scene.fem.stride);
    e.dofs = 3 * ((w - 1) / k + 1) * ((h - 1) / k + 1);
  } else if (scene.knit) {
    e.dofs = knit_dofs(*scene.knit, scene.sliding);
  } else {
    // 3 DoFs per node, plus (u, v) on interior nodes when sliding (docs/models.md §2.1).
    e.dofs = 3 * w * h + (scene.sliding ? 2 * std::max(0L, w - 2) * std::max(0L, h - 2) : 0);
  }
  const double n = static_cast<double>(std::max(1L, e.dofs));
  e.bytes = kProcess + n * (takes_amg_route(scene, model_name, e.dofs) ? kAmgPerDof : kBase + kPerLog2 * std::log2(n));
  return e;
}

double available_memory_bytes() {
  std::ifstream in("/proc/meminfo");
  std::string line;
  while (std::getline(in, line)) {
    std::istringstream ls(line);
    std::string key;
    double kb = 0.0;
    if (ls >> key >> kb && key == "MemAvailable:") return kb * 1024.0;
  }
  return static_cast<double>(sysconf(_SC_PHYS_PAGES)) * static_cast<double>(sysconf(_SC_PAGE_SIZE));
}

double peak_resident_bytes() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return static_cast<double>(u.ru_maxrss) * 1024.0;  // Linux: kilobytes
}

}  // namespace wl
