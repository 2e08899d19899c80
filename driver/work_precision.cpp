#include "driver/work_precision.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>

#include "driver/experiment_meta.h"
#include "driver/interrupted_record.h"
#include "models/model_factory.h"
#include "output/atomic_file.h"
#include "output/csv_table.h"
#include "output/json_writer.h"

namespace wl {

const std::vector<std::string> kWorkPrecisionColumns = {"model",
                                                        "integrator",
                                                        "mode",
                                                        "rtol",
                                                        "atol",
                                                        "dt_s",
                                                        "outcome",
                                                        "sundials_flag",
                                                        "message",
                                                        "error_rms_m",
                                                        "error_max_m",
                                                        "cpu_s",
                                                        "wall_s",
                                                        "steps",
                                                        "rejected_steps",
                                                        "rhs_evals",
                                                        "jac_evals",
                                                        "linear_setups",
                                                        "linear_solves",
                                                        "nonlinear_iters",
                                                        "max_node_speed_m_per_s",
                                                        "end_time_s",
                                                        "dofs"};

namespace {

constexpr double kNotApplicable = std::numeric_limits<double>::quiet_NaN();

void validate_names(const WorkPrecisionConfig& c) {
  for (const auto& m : c.models) check_model_for_scene(c.scene, m);  // unknown, or not the scene's cloth
  for (const auto& i : c.integrators) (void)make_integrator(i);      // throws for an unknown name
  if (c.rtols.empty()) throw std::invalid_argument("work-precision: no tolerances given");
  if (!(c.dt_max > 0) || !(c.dt_min > 0) || c.dt_min > c.dt_max)
    throw std::invalid_argument("work-precision: need 0 < dt_min <= dt_max");
}

std::vector<std::string> csv_row(const WorkPrecisionRow& r) {
  const IntegratorStats& s = r.run.stats;
  return {r.model,
          r.integrator,
          r.mode,
          csv_number(r.rtol),
          csv_number(r.atol),
          csv_number(r.dt),
          r.outcome(),
          r.run.result.library_flag_name,
          r.run.result.message,
          csv_number(r.error.rms),
          csv_number(r.error.max),
          csv_number(r.run.cpu_s),
          csv_number(r.run.wall_s),
          std::to_string(s.steps),
          std::to_string(s.rejected_steps),
          std::to_string(s.rhs_evals),
          std::to_string(s.jac_evals),
          std::to_string(s.linear_setups),
          std::to_string(s.linear_solves),
          std::to_string(s.nonlinear_iters),
          csv_number(r.run.max_node_speed),
          csv_number(r.run.end_time),
          std::to_string(r.run.dofs)};
}

Json reference_json(const Reference& r) {
  Json j = Json::object();
  j.set("hash", r.hash);
  j.set("file", r.file.string());
  j.set("from_cache", r.from_cache);
  j.set("rtol", r.rtol);
  j.set("atol", r.atol);
  j.set("meets_rtol_requirement", r.meets_requirement());
  j.set("required_rtol", r.required_rtol);
  j.set("cpu_s", r.cpu_s);
  Json a = Json::array();
  for (const auto& s : r.attempts) a.push(s);
  j.set("attempts_this_run", a);
  return j;
}

// Ladders: rtol for error-controlled methods, dt for fixed-step ones, and
// both for the in-house error-controlled method (sdirk2). (integrator, adaptive) pairs.
std::vector<std::pair<std::string, bool>> ladders_of(const WorkPrecisionConfig& cfg) {
  std::vector<std::pair<std::string, bool>> ladders;
  for (const std::string& integ : cfg.integrators) {
    const IntegratorCapabilities cap = make_integrator(integ)->capabilities();
    if (cap.controls_error) ladders.emplace_back(integ, true);
    if (!cap.controls_error || (cap.replays_steps && cap.fixed_step_order > 0)) ladders.emplace_back(integ, false);
  }
  return ladders;
}

std::vector<double> rungs_of(const WorkPrecisionConfig& cfg, bool adaptive) {
  if (adaptive) return cfg.rtols;
  std::vector<double> rungs;
  for (double dt = cfg.dt_max; dt >= cfg.dt_min * (1 - 1e-12); dt *= 0.5) rungs.push_back(dt);
  return rungs;
}

// One rung's run into row.run: pilots with growing step limits from `step_cap` (see
// WorkPrecisionConfig::run_budget_cpu_s), then the full run when it is predicted within budget.
void run_with_pilots(const WorkPrecisionConfig& cfg, const std::string& model, const std::string& integ,
                     IntegratorOptions opt, long step_cap, WorkPrecisionRow& row) {
  RecordOptions rec;
  rec.progress = cfg.progress;
  rec.speed_bound = cfg.speed_bound;
  rec.label = model + " " + integ;
  rec.stop_at_signal = true;
  long cap = step_cap;
  for (;;) {
    opt.max_steps = cap;
    row.run = run_recorded(cfg.scene, model, integ, opt, rec);
    if (row.run.result.outcome != Outcome::max_steps) break;
    const double frac = row.run.end_time / cfg.scene.duration_s;
    const double predicted = frac > 0 ? row.run.cpu_s / frac : std::numeric_limits<double>::infinity();
    if (predicted <= cfg.run_budget_cpu_s) {
      if (cfg.progress)
        std::fprintf(stderr, "    (%ld-step pilot reached t = %g s; rerunning without the limit)\n", cap,
                     row.run.end_time);
      opt.max_steps = IntegratorOptions{}.max_steps;
      row.run = run_recorded(cfg.scene, model, integ, opt, rec);
      break;
    }
    const double per_step = row.run.cpu_s / std::max(1L, row.run.stats.steps);
    if (per_step * 10.0 * cap > cfg.run_budget_cpu_s) {
      row.over_budget = true;
      row.predicted_cpu_s = predicted;
      row.run.result.message = "stopped at a pilot limit of " + std::to_string(cap) +
                               " steps at t = " + csv_number(row.run.end_time) + " s after " +
                               csv_number(row.run.cpu_s) + " s CPU; the full run extrapolates to " +
                               csv_number(predicted) + " s CPU > budget " + csv_number(cfg.run_budget_cpu_s) + " s";
      break;
    }
    cap *= 10;
  }
}

// One rung of a ladder: its run and its error against the reference.
WorkPrecisionRow run_rung(const WorkPrecisionConfig& cfg, const std::string& model, const std::string& integ,
                          bool adaptive, double rung, long step_cap, const Reference& ref) {
  WorkPrecisionRow row;
  row.model = model;
  row.integrator = integ;
  row.mode = adaptive ? "adaptive" : "fixed";
  IntegratorOptions opt;
  if (adaptive) {
    opt.adaptive = true;
    opt.rtol = row.rtol = rung;
    opt.atol = row.atol = rung * cfg.atol_per_rtol;
    opt.dt = cfg.adaptive_initial_dt;
    row.dt = kNotApplicable;
  } else {
    opt.adaptive = false;
    opt.dt = row.dt = rung;
    row.rtol = row.atol = kNotApplicable;
  }
  run_with_pilots(cfg, model, integ, opt, step_cap, row);
  row.error = {kNotApplicable, kNotApplicable};
  if (row.run.result.outcome == Outcome::ok) row.error = trajectory_error(row.run.trajectory, ref.trajectory);
  if (cfg.progress)
    std::fprintf(stderr, "  %-4s %-12s %s %-8s %-14s err rms %.3g m, max %.3g m, %.2f s CPU, %ld steps\n",
                 model.c_str(), integ.c_str(), adaptive ? "rtol" : "dt  ", csv_number(rung).c_str(),
                 row.outcome().c_str(), row.error.rms, row.error.max, row.run.cpu_s, row.run.stats.steps);
  return row;
}

// One ladder of a model and integrator, rung by rung until a rung is predicted over
// the CPU budget, not offered, or over budget; its rows into `csv` and `res`.
void run_ladder(const WorkPrecisionConfig& cfg, const std::string& model, const std::string& integ, bool adaptive,
                const Reference& ref, CsvTable& csv, WorkPrecisionResult& res) {
  const std::vector<double> rungs = rungs_of(cfg, adaptive);
  double prev_cpu = kNotApplicable, last_cpu = kNotApplicable;
  long step_cap = cfg.pilot_steps;
  for (size_t k = 0; k < rungs.size(); ++k) {
    if (std::isfinite(last_cpu)) {
      const double growth = std::isfinite(prev_cpu) && prev_cpu > 0 ? std::max(1.5, last_cpu / prev_cpu) : 2.0;
      if (last_cpu * growth > cfg.run_budget_cpu_s) {
        const std::string note = model + " " + integ + ": ladder stopped before " + (adaptive ? "rtol " : "dt ") +
                                 csv_number(rungs[k]) + " (predicted " + csv_number(last_cpu * growth) +
                                 " s CPU > budget " + csv_number(cfg.run_budget_cpu_s) + " s)";
        res.notes.push_back(note);
        if (cfg.progress) std::fprintf(stderr, "  %s\n", note.c_str());
        break;
      }
    }
    WorkPrecisionRow row = run_rung(cfg, model, integ, adaptive, rungs[k], step_cap, ref);
    csv.row(csv_row(row));
    const Outcome o = row.run.result.outcome;
    const bool over = row.over_budget;
    step_cap = std::max(cfg.pilot_steps, 4 * row.run.stats.steps);
    res.rows.push_back(std::move(row));
    if (o == Outcome::not_offered) {
      res.notes.push_back(model + " " + integ + ": not offered: " + res.rows.back().run.result.message);
      break;
    }
    if (over) {
      res.notes.push_back(model + " " + integ + ": ladder stopped: " + res.rows.back().run.result.message);
      break;
    }
    if (o != Outcome::ok) continue;  // a failed rung's CPU time predicts nothing of the next
    prev_cpu = last_cpu;
    last_cpu = res.rows.back().run.cpu_s;
  }
}

Json parameters_json(const WorkPrecisionConfig& cfg) {
  Json p = Json::object();
  p.set("models", Json(cfg.models));
  p.set("integrators", Json(cfg.integrators));
  p.set("rtols", Json(cfg.rtols));
  p.set("atol_per_rtol", cfg.atol_per_rtol);
  p.set("adaptive_initial_dt_s", cfg.adaptive_initial_dt);
  p.set("dt_max_s", cfg.dt_max);
  p.set("dt_min_s", cfg.dt_min);
  p.set("run_budget_cpu_s", cfg.run_budget_cpu_s);
  p.set("pilot_steps", cfg.pilot_steps);
  p.set("speed_bound_m_per_s", cfg.speed_bound);
  p.set("error",
        "RMS and max over nodes and output times t_k = k*output_interval_s (k >= 1) of the node position "
        "difference to the reference [m]");
  p.set("cpu_time", "process CPU time (all threads) of initialize + advance_to, frame extraction excluded");
  Json rp = Json::object();
  rp.set("integrator", cfg.reference.integrator);
  rp.set("rtols_tried_in_order", Json(cfg.reference.rtols));
  rp.set("required_rtol", cfg.reference.required_rtol);
  rp.set("atol_per_rtol", cfg.reference.atol_per_rtol);
  rp.set("cache_dir", cfg.reference.cache_dir.string());
  p.set("reference", rp);
  return p;
}

// work_precision.json; with `interrupted_in`, of the runs a signal left (driver/interrupted_record.h).
void write_work_precision_json(const WorkPrecisionConfig& cfg, const WorkPrecisionResult& res,
                               const std::string& started, const std::string& interrupted_in = "") {
  Json j = Json::object();
  j.set("experiment", "work-precision");
  if (!interrupted_in.empty()) mark_interrupted(j, interrupted_in);
  j.set("scene", scene_json(cfg.scene_path, cfg.scene_text, cfg.scene, cfg.overrides));
  j.set("published_dt_s", cfg.scene.dt_s);  // the scene's own step, marked on the chart
  j.set("parameters", parameters_json(cfg));
  Json refs = Json::object();
  for (const auto& [m, r] : res.references) refs.set(m, reference_json(r));
  j.set("references", refs);
  Json notes = Json::array();
  for (const auto& n : res.notes) notes.push(n);
  j.set("notes", notes);
  j.set("runs", static_cast<long>(res.rows.size()));
  j.set("started_utc", started);
  j.set("finished_utc", utc_now());
  j.set("wall_s", res.wall_s);
  add_provenance(j);
  write_file_atomically(cfg.out_dir / "work_precision.json", j.dump());
}

}  // namespace

WorkPrecisionResult run_work_precision(const WorkPrecisionConfig& cfg_in) {
  WorkPrecisionConfig cfg = cfg_in;
  if (cfg.integrators.empty()) cfg.integrators = integrator_names();
  validate_names(cfg);
  const auto t0 = std::chrono::steady_clock::now();
  const std::string started = utc_now();
  WorkPrecisionResult res;

  std::filesystem::create_directories(cfg.out_dir);
  CsvTable csv(cfg.out_dir / "work_precision.csv", kWorkPrecisionColumns);
  std::string stage, interrupted_in;
  try {
    for (const std::string& model : cfg.models) {
      if (cfg.progress) std::fprintf(stderr, "work-precision: %s model\n", model.c_str());
      stage = "the " + model + " reference";
      Reference ref = load_or_compute_reference(cfg.scene, cfg.scene_text, model, cfg.overrides, cfg.reference);
      if (!ref.meets_requirement()) {
        const std::string note = "reference for " + model + " is at rtol " + std::to_string(ref.rtol) +
                                 ", looser than the required " + std::to_string(ref.required_rtol);
        res.notes.push_back(note);
        std::fprintf(stderr, "work-precision: WARNING: %s\n", note.c_str());
      }
      for (const auto& [integ, adaptive] : ladders_of(cfg)) {
        stage = "the " + model + " " + integ + (adaptive ? " rtol" : " dt") + " ladder";
        run_ladder(cfg, model, integ, adaptive, ref, csv, res);
      }
      res.references.emplace(model, std::move(ref));
    }
  } catch (const Interrupted&) {  // the record of the runs complete so far
    interrupted_in = stage;
  }
  csv.commit();
  res.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  write_work_precision_json(cfg, res, started, interrupted_in);
  if (!interrupted_in.empty()) throw Interrupted{interrupted_in};
  return res;
}

}  // namespace wl
