#include "experiments/driver/run_summary.h"

#include <chrono>
#include <ctime>
#include <fstream>
#include <sstream>

#include "experiments/output/atomic_file.h"
#include "experiments/output/json_writer.h"

namespace wl {

void write_run_summary(const std::filesystem::path& path, const Scene& scene, const RunOptions& options,
                       const Model& model, const Integrator& integrator, const RunReport& report) {
  Json j = Json::object();
  Json s = Json::object();
  s.set("name", std::filesystem::path(scene.source).stem().string());
  s.set("file", scene.source);
  std::ifstream in(scene.source);
  std::stringstream text;
  text << in.rdbuf();
  s.set("text", text.str());
  s.set("overrides", Json(options.overrides));
  s.set("dt_s", scene.dt_s);
  s.set("duration_s", scene.duration_s);
  s.set("output_interval_s", scene.output_interval_s);
  j.set("scene", s);
  Json m(model.describe());
  m.set("name", model.name());
  j.set("model", m);
  Json in_ = Json::object();
  in_.set("name", integrator.name());
  in_.set("adaptive", scene.adaptive);
  if (scene.adaptive) {
    in_.set("rtol", scene.rtol);
    in_.set("atol", scene.atol);
  }
  j.set("integrator", in_);
  const IntegratorStats& st = report.stats;
  Json stats = Json::object();
  stats.set("steps", st.steps);
  stats.set("rejected_steps", st.rejected_steps);
  stats.set("rhs_evals", st.rhs_evals);
  stats.set("jac_evals", st.jac_evals);
  stats.set("linear_setups", st.linear_setups);
  stats.set("linear_solves", st.linear_solves);
  stats.set("nonlinear_iters", st.nonlinear_iters);
  stats.set("wall_s", st.wall_s);
  stats.set("cpu_s", st.cpu_s);
  j.set("statistics", stats);
  Json out = Json::object();
  out.set("outcome", to_string(report.result.outcome));
  out.set("message", report.result.message);
  out.set("end_time_s", report.end_time);
  out.set("frames", report.frames);
  j.set("result", out);
  j.set("git_revision", git_revision());
  j.set("machine", Json(machine_info()));
  const std::time_t now = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  char stamp[32];
  std::strftime(stamp, sizeof stamp, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&now));
  j.set("finished_utc", std::string(stamp));
  write_file_atomically(path, j.dump());
}

}  // namespace wl
