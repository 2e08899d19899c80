#include "driver/memory_estimate.h"

#include <sys/resource.h>
#include <unistd.h>

#include <cmath>
#include <fstream>
#include <sstream>

namespace wl {
namespace {

// Peak ≈ kProcess + DoFs · (kBase + kPerLog2 · log₂ DoFs): the factor's fill
// grows like n log n. An upper fit to the peak resident sizes of `weavelab run`
// on the hanging cloth at 257×257 (328 197 DoFs): 11.8 kB per DoF with gmres
// (the default), 15.7 kB with umfpack; the estimate gives 16.8 kB.
constexpr double kProcess = 64e6;
constexpr double kBase = 4000.0;
constexpr double kPerLog2 = 700.0;

}  // namespace

MemoryEstimate estimate_run_memory(const Scene& scene, const std::string& model_name) {
  const long w = scene.warps, h = scene.wefts;
  MemoryEstimate e;
  if (model_name == "fem") {
    const long k = std::max(1, scene.fem.stride);
    e.dofs = 3 * ((w - 1) / k + 1) * ((h - 1) / k + 1);
  } else {
    // 3 DoFs per node, plus (u, v) on interior nodes when sliding (docs/models.md §2.1).
    e.dofs = 3 * w * h + (scene.sliding ? 2 * std::max(0L, w - 2) * std::max(0L, h - 2) : 0);
  }
  const double n = static_cast<double>(std::max(1L, e.dofs));
  e.bytes = kProcess + n * (kBase + kPerLog2 * std::log2(n));
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
