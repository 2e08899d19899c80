// The reference trajectory of the integrator experiments (IDA at the tightest
// tolerance that converges) and its cache under results/reference/.
#pragma once
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "driver/recorded_run.h"

namespace wl {

struct ReferenceOptions {
  std::filesystem::path cache_dir = "results/reference";
  std::string integrator = "ida";
  std::vector<double> rtols = {1e-10, 1e-9};       // tried in order; the first that converges is used
  double required_rtol = 1e-9;                     // a reference looser than this is reported (and flagged)
  double atol_per_rtol = 1e-3;                     // atol = rtol × this [m, m/s]
  double initial_dt = 1e-6;                        // initial step hint [s]
  long max_steps = IntegratorOptions{}.max_steps;  // per attempt; beyond it the attempt fails (max_steps)
  bool progress = true;
};

struct Reference {
  Trajectory trajectory;
  std::string hash;            // 16 hex digits
  std::filesystem::path file;  // <cache_dir>/<hash>.bin
  bool from_cache = false;
  double rtol = 0.0, atol = 0.0;      // the tolerances that converged
  double cpu_s = 0.0;                 // CPU time of the run that produced it (also when read from the cache)
  std::vector<std::string> attempts;  // "rtol=1e-10: ok" / "rtol=1e-10: step_too_small: …" (this call only)
  bool meets_requirement() const { return rtol > 0 && rtol <= 1.0000001 * required_rtol; }
  double required_rtol = 1e-9;
};

// The cache key: scene file text, model, overrides (sorted key=value lines)
// and the reference integrator; the file is named by text_hash(key)
// (experiment_meta.h).
std::string reference_key(const std::string& scene_text, const std::string& model_name,
                          const std::map<std::string, std::string>& overrides, const ReferenceOptions& options);

// Reads <cache_dir>/<hash>.bin when it exists and holds the same key, output
// times, 3 rows per point of the model's frame and finite values; otherwise runs `options.integrator` at each rtol in
// turn until one ends ok, and writes the file atomically. Throws std::runtime_error when no tolerance converges (naming
// every attempt). A SIGINT or SIGTERM ends a run at its step: Interrupted, nothing written.
// `scene` must be the scene the text and overrides describe.
Reference load_or_compute_reference(const Scene& scene, const std::string& scene_text, const std::string& model_name,
                                    const std::map<std::string, std::string>& overrides,
                                    const ReferenceOptions& options = {});

// Cache file format (little-endian, as written on this machine):
//   char[8] "WLREF01\0"; u64 key length; key bytes; f64 rtol, atol, cpu_s;
//   u64 times, u64 rows (3·nodes); f64 times[times]; f64 positions[rows × times] (column-major).
void write_reference_file(const std::filesystem::path& path, const std::string& key, const Reference& ref);
// Returns false when the file is absent, unreadable, malformed or holds another key.
bool read_reference_file(const std::filesystem::path& path, const std::string& key, Reference& ref);

}  // namespace wl
