#include "driver/experiment_meta.h"

#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <ctime>

#include "driver/determinism.h"

namespace wl {

std::string utc_now() {
  const std::time_t now = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  char stamp[32];
  std::strftime(stamp, sizeof stamp, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&now));
  return stamp;
}

Json statistics_json(const IntegratorStats& st) {
  Json s = Json::object();
  s.set("steps", st.steps);
  s.set("rejected_steps", st.rejected_steps);
  s.set("rhs_evals", st.rhs_evals);
  s.set("jac_evals", st.jac_evals);
  s.set("linear_setups", st.linear_setups);
  s.set("linear_solves", st.linear_solves);
  s.set("nonlinear_iters", st.nonlinear_iters);
  s.set("factorizations", st.factorizations);
  s.set("krylov_iters", st.krylov_iters);
  s.set("linear_solver", st.linear_solver);
  s.set("step_matrix_asymmetry", st.step_matrix_asymmetry);
  s.set("wall_s", st.wall_s);
  s.set("cpu_s", st.cpu_s);
  return s;
}

Json scene_json(const std::filesystem::path& path, const std::string& text, const Scene& scene,
                const std::map<std::string, std::string>& overrides) {
  Json s = Json::object();
  s.set("file", path.string());
  s.set("name", path.stem().string());
  s.set("overrides", Json(overrides));
  s.set("warps", scene.warps);
  s.set("wefts", scene.wefts);
  s.set("duration_s", scene.duration_s);
  s.set("output_interval_s", scene.output_interval_s);
  s.set("text", text);
  return s;
}

void add_provenance(Json& j) {
  j.set("git_revision", git_revision());
  j.set("machine", Json(machine_info()));
  j.set("threads", thread_counts());
  Json env = Json::object();
  for (const char* name : {"OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS"}) {
    const char* value = std::getenv(name);
    env.set(name, value ? Json(std::string(value)) : Json());
  }
  j.set("environment", env);
}

std::string text_hash(const std::string& text) {
  std::uint64_t h = 14695981039346656037ull;  // FNV-1a 64
  for (unsigned char c : text) {
    h ^= c;
    h *= 1099511628211ull;
  }
  char buf[17];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(h));
  return buf;
}

}  // namespace wl
