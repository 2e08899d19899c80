#include "driver/stability.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>

#include "driver/experiment_meta.h"
#include "driver/interrupted_record.h"
#include "driver/recorded_run.h"
#include "driver/scene_scaling.h"
#include "models/model_factory.h"
#include "output/atomic_file.h"
#include "output/csv_table.h"
#include "output/json_writer.h"

namespace wl {
namespace {

// A short name for why a probe was unbounded, from the structured result: the
// SUNDIALS flag when the library reported the failure, "runaway" for a speed
// beyond the bound, "newton" for a Newton failure of the in-house methods, else
// the outcome.
std::string failure_mode(const StabilityProbe& p) {
  if (p.result.outcome == Outcome::ok) return p.bounded ? "" : "runaway";
  if (!p.result.library_flag_name.empty()) return p.result.library_flag_name;
  switch (p.result.cause) {
    case FailureCause::runaway_speed: return "runaway";
    case FailureCause::newton: return "newton";
    case FailureCause::other: break;
  }
  return to_string(p.result.outcome);
}

void check_stability_config(const StabilityConfig& cfg) {
  for (const auto& m : cfg.models) check_model_for_scene(cfg.scene, m);  // unknown, or not the scene's cloth
  for (const auto& i : cfg.integrators) (void)make_integrator(i);
  for (double m : cfg.multipliers)
    if (!(m > 0)) throw std::invalid_argument("stability: multipliers must be > 0, got " + csv_number(m));
  if (!(cfg.dt_min > 0) || !(cfg.dt_max > cfg.dt_min))
    throw std::invalid_argument("stability: need 0 < dt_min < dt_max");
  if (cfg.bisections < 1) throw std::invalid_argument("stability: bisections must be >= 1");
}

// One fixed-step run of a cell at `dt`: bounded or not, its row in stability_probes.csv,
// its CPU time and a not-offered pair into `row`.
StabilityProbe probe_cell(const StabilityConfig& cfg, const Scene& scene, double dt, StabilityRow& row,
                          CsvTable& probes) {
  const std::string& model = row.model;
  const std::string& integ = row.integrator;
  const double mult = row.multiplier;
  IntegratorOptions opt;
  opt.adaptive = false;
  opt.dt = dt;
  opt.rtol = scene.rtol;  // used only by ida (step capped at dt)
  opt.atol = scene.atol;
  RecordOptions rec;
  rec.speed_bound = cfg.speed_bound;
  rec.progress = cfg.progress;
  rec.stop_at_signal = true;
  rec.label = model + " " + integ + " x" + csv_number(mult) + " dt " + csv_number(dt);
  RecordedRun run = run_recorded(scene, model, integ, opt, rec);
  StabilityProbe p;
  p.result = run.result;
  p.max_speed = run.max_node_speed;
  p.bounded = run.result.outcome == Outcome::ok && run.max_node_speed < cfg.speed_bound;
  row.cpu_s += run.cpu_s;
  if (run.result.outcome == Outcome::not_offered) {
    row.not_offered = true;
    row.not_offered_message = run.result.message;
  }
  probes.row({model, integ, csv_number(mult), csv_number(dt), p.bounded ? "1" : "0", to_string(run.result.outcome),
              failure_mode(p), run.result.message, csv_number(run.max_node_speed), csv_number(run.end_time),
              std::to_string(run.stats.steps), csv_number(run.cpu_s)});
  if (cfg.progress)
    std::fprintf(stderr, "    dt %-10s %s (%s) %.2f s CPU\n", csv_number(dt).c_str(),
                 p.bounded ? "bounded" : "unbounded", failure_mode(p).c_str(), run.cpu_s);
  return p;
}

// One cell (model, integrator, stretch multiplier): the largest bounded step by bisection on log dt,
// its row in stability.csv.
StabilityRow run_cell(const StabilityConfig& cfg, const std::string& model, const std::string& integ, double mult,
                      CsvTable& table, CsvTable& probes) {
  const Scene scene = scale_stretch(cfg.scene, mult);
  StabilityRow row;
  row.model = model;
  row.integrator = integ;
  row.multiplier = mult;
  auto probe = [&](double dt) { return probe_cell(cfg, scene, dt, row, probes); };
  // A pair that is not offered ends at its first probe.
  StabilityProbe first = probe(cfg.dt_max);
  if (row.not_offered) {
    row.limit.probes.emplace_back(cfg.dt_max, first);
    row.limit.failure = first;
  } else {
    bool reuse = true;  // the dt_max probe is already done
    row.limit = find_stability_limit(
        [&](double dt) {
          if (reuse && dt == cfg.dt_max) {
            reuse = false;
            return first;
          }
          return probe(dt);
        },
        cfg.dt_min, cfg.dt_max, cfg.bisections);
  }
  const StabilityLimit& L = row.limit;
  const std::string mode = row.not_offered ? "not_offered" : failure_mode(L.failure);
  const bool has_failure = row.not_offered || std::isfinite(L.smallest_unstable_dt);
  table.row({model, integ, csv_number(mult), csv_number(L.largest_stable_dt), csv_number(L.smallest_unstable_dt),
             has_failure ? mode : "", has_failure ? to_string(L.failure.result.outcome) : "",
             has_failure ? L.failure.result.message : "", std::to_string(L.probes.size()), csv_number(row.cpu_s)});
  if (cfg.progress)
    std::fprintf(stderr, "  -> largest bounded dt %s s, failure above: %s (%.1f s CPU)\n",
                 csv_number(L.largest_stable_dt).c_str(), has_failure ? mode.c_str() : "none up to dt_max", row.cpu_s);
  return row;
}

// stability.json; with `interrupted_in`, of the cells a signal left (driver/interrupted_record.h).
void write_stability_json(const StabilityConfig& cfg, const StabilityResult& res, const std::string& started,
                          const std::string& interrupted_in = "") {
  Json j = Json::object();
  j.set("experiment", "stability");
  if (!interrupted_in.empty()) mark_interrupted(j, interrupted_in);
  j.set("scene", scene_json(cfg.scene_path, cfg.scene_text, cfg.scene, cfg.overrides));
  Json p = Json::object();
  p.set("models", Json(cfg.models));
  p.set("integrators", Json(cfg.integrators));
  p.set("multipliers", Json(cfg.multipliers));
  p.set("multiplier_meaning",
        "every yarn type's stretch_modulus_Pa and the FEM warp/weft stretch stiffness (N/m) multiplied by it");
  p.set("dt_min_s", cfg.dt_min);
  p.set("dt_max_s", cfg.dt_max);
  p.set("bisections", cfg.bisections);
  p.set("speed_bound_m_per_s", cfg.speed_bound);
  p.set("bounded", "outcome ok and max node speed below speed_bound at every accepted step, over the scene duration");
  p.set("fixed_steps",
        "IntegratorOptions.adaptive = false; ida (if listed) then caps its step at dt with error "
        "control at the scene's rtol/atol");
  j.set("parameters", p);
  j.set("cells", static_cast<long>(res.rows.size()));
  j.set("started_utc", started);
  j.set("finished_utc", utc_now());
  j.set("wall_s", res.wall_s);
  add_provenance(j);
  write_file_atomically(cfg.out_dir / "stability.json", j.dump());
}

}  // namespace

std::vector<std::string> default_stability_integrators() {
  std::vector<std::string> names;
  for (const auto& n : integrator_names())
    if (make_integrator(n)->capabilities().fixed_step_order > 0) names.push_back(n);
  return names;
}

StabilityResult run_stability(const StabilityConfig& cfg_in) {
  StabilityConfig cfg = cfg_in;
  if (cfg.integrators.empty()) cfg.integrators = default_stability_integrators();
  check_stability_config(cfg);
  const auto t0 = std::chrono::steady_clock::now();
  const std::string started = utc_now();
  std::filesystem::create_directories(cfg.out_dir);
  CsvTable table(cfg.out_dir / "stability.csv",
                 {"model", "integrator", "multiplier", "largest_stable_dt_s", "smallest_unstable_dt_s", "failure_mode",
                  "failure_outcome", "failure_message", "probes", "cpu_s"});
  CsvTable probes(cfg.out_dir / "stability_probes.csv",
                  {"model", "integrator", "multiplier", "dt_s", "bounded", "outcome", "failure_mode", "message",
                   "max_node_speed_m_per_s", "end_time_s", "steps", "cpu_s"});
  StabilityResult res;
  const size_t cells = cfg.models.size() * cfg.integrators.size() * cfg.multipliers.size();
  size_t cell = 0;
  std::string stage, interrupted_in;
  try {
    for (const std::string& model : cfg.models)
      for (const std::string& integ : cfg.integrators)
        for (double mult : cfg.multipliers) {
          ++cell;
          if (cfg.progress)
            std::fprintf(stderr, "stability [%zu/%zu]: %s %s, stretch x%g\n", cell, cells, model.c_str(), integ.c_str(),
                         mult);
          stage = "the cell " + model + " " + integ + " x" + csv_number(mult);
          res.rows.push_back(run_cell(cfg, model, integ, mult, table, probes));
        }
  } catch (const Interrupted&) {  // the record of the cells and probes complete so far
    interrupted_in = stage;
  }
  table.commit();
  probes.commit();
  res.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  write_stability_json(cfg, res, started, interrupted_in);
  if (!interrupted_in.empty()) throw Interrupted{interrupted_in};
  return res;
}

}  // namespace wl
