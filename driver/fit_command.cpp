#include "driver/fit_command.h"

#include <algorithm>
#include <cmath>

#include "calibration/fit_continuation.h"
#include "calibration/scene_parameters.h"
#include "driver/experiment_meta.h"
#include "driver/interrupt.h"
#include "driver/interrupted_record.h"
#include "driver/run_settings.h"
#include "driver/time_error.h"
#include "driver/time_steps.h"
#include "models/common/self_contact.h"
#include "models/fem/fem_material.h"
#include "models/fem/knit_contact_mesh.h"
#include "models/model_factory.h"
#include "output/atomic_file.h"
#include "output/csv_table.h"
#include "output/json_writer.h"
#include "output/run_reader.h"

namespace wl {
namespace {

std::string num(double x) {
  char b[32];
  std::snprintf(b, sizeof b, "%.10g", x);
  return b;
}

// The fitted distance beside each side's time error (docs/models.md §7.8): the
// fitted model rerun to the last fitted frame at the fit's integrator and step,
// its estimate formed by a second run; the target's read from its summary.json.
Json fit_error_budget(const FitCommandConfig& c, const FitCommandPlan& p, const TrajectoryFitResult& r) {
  Scene fitted = p.scene;
  for (const TrajectoryFitParameter& fp : r.parameters) set_scene_parameter(fitted, fp.key, fp.value);
  fitted.integrator = c.fit.integrator.empty() ? p.scene.integrator : c.fit.integrator;
  fitted.duration_s = p.target.back().time;
  RecordOptions rec;
  rec.step_ends = true;
  rec.progress = c.fit.progress;
  rec.label = "fitted run";
  const IntegratorOptions opt = scene_integrator_options(fitted);
  const RecordedRun run = run_recorded(fitted, c.fit.model, fitted.integrator, opt, rec);
  Json b = Json::object();
  double distance = 0;
  for (double x : r.final_rms) distance += x / double(r.final_rms.size());
  b.set("distance_mean_rms_m", distance);
  TimeErrorEstimate fitted_error;  // not_offered: no estimate
  fitted_error.second_run.outcome = Outcome::not_offered;
  if (run.result.outcome == Outcome::ok) {
    fitted_error = estimate_time_error(fitted, c.fit.model, fitted.integrator, opt, run, c.fit.progress);
    b.set("fitted_time_error", fitted_error.to_json());
  } else {
    b.set("fitted_time_error", "the fitted rerun ended " + std::string(to_string(run.result.outcome)));
  }
  // The target's estimate, as the verdict reads it.
  TimeErrorEstimate target_error;
  target_error.second_run.outcome = Outcome::not_offered;
  if (const std::optional<double> t = read_run_time_error(c.target_dir)) {
    target_error.second_run.outcome = Outcome::ok;
    target_error.mean_rms = *t;
    b.set("target_time_error_mean_rms_m", *t);
  } else {
    b.set("target_time_error_mean_rms_m", "not estimated: run the target with --error-estimate");
  }
  const std::string verdict = error_budget_verdict(distance, fitted_error, target_error);
  b.set("verdict", verdict);
  if (c.fit.progress)
    std::fprintf(stderr, "fit: distance %.3g mm mean RMS; time error (mean RMS) fitted %.3g mm, target %.3g mm: %s\n",
                 1e3 * distance, 1e3 * fitted_error.mean_rms, 1e3 * target_error.mean_rms, verdict.c_str());
  return b;
}

// The stage of the fit a signal ended: "stage K of the fit (N frames)".
std::string fit_stage(const TrajectoryFitResult& r) {
  if (r.stages.empty()) return "the fit";
  return "stage " + std::to_string(r.stages.size()) + " of the fit (" + std::to_string(r.stages.back().frames) +
         " frames)";
}

// The configuration with the model and the growing window the plan chose (the
// scene's yarn level for an empty model, the default window of a long fit), and
// the stop hook that ends the fit on SIGINT or SIGTERM.
FitCommandConfig with_model(FitCommandConfig c, const FitCommandPlan& p) {
  c.fit.model = p.model;
  c.fit.window = p.window;
  c.fit.stop_requested = [] { return interrupt_signal() != 0; };
  return c;
}

// The growing window of a fit over `frames` frames and where it comes from.
void choose_window(const FitCommandConfig& c, int frames, FitCommandPlan& p) {
  if (!c.fit.window.empty()) {
    check_window(c.fit.window, frames);
    p.window = c.fit.window;
    p.window_rule = "given";
  } else if (!c.default_window) {
    p.window_rule = "off";
  } else {
    p.window = default_growing_window(frames);
    p.window_rule = p.window.empty() ? "short" : "default";
  }
}

}  // namespace

FitCommandPlan plan_fit(const FitCommandConfig& c) {
  FitCommandPlan p;
  p.scene = load_scene(c.scene_path.string());
  refuse_self_contact(p.scene, "fit (its forward sensitivities)");
  p.model = c.fit.model.empty() ? yarn_level_model(p.scene) : c.fit.model;
  try {
    check_model_for_scene(p.scene, p.model);
  } catch (const std::invalid_argument& e) {
    throw TrajectoryFitError(std::string("--model: ") + e.what());
  }
  if (!c.time_steps.scene) {
    if (!c.fit.integrator.empty() && c.fit.integrator != "sdirk2")
      throw TrajectoryFitError("--integrator: got '" + c.fit.integrator +
                               "', --time-steps controlled runs sdirk2 (use --time-steps scene for another)");
    p.scene = at_time_steps(p.scene, c.time_steps);
  }
  {  // the fitted simulations' steps, as `run` checks them (adaptive steps need error control)
    Scene stepped = p.scene;
    std::map<std::string, std::string> record;
    if (!c.fit.integrator.empty()) stepped.integrator = record["integrator"] = c.fit.integrator;
    check_run_settings(stepped, record);
  }
  if (!c.fem_params.empty()) {
    p.scene.fem.parameter_file = c.fem_params;
    (void)fem_material(p.scene);  // a bad file is exit 2 before anything runs
  }
  if (c.frames < 0) throw TrajectoryFitError("--frames: got " + std::to_string(c.frames) + ", expected a count >= 1");
  for (const RecordedFrame& f : read_run_frames(c.target_dir)) {
    if (!(f.time > 0.0)) continue;
    if (c.frames > 0 && static_cast<int>(p.target.size()) == c.frames) break;
    TargetFrame t;
    t.time = f.time;
    t.points = f.points;
    for (size_t i = 0; i < f.u.size(); ++i) t.uv.emplace_back(f.u[i], f.v[i]);
    p.target.push_back(std::move(t));
  }
  // A yarn-level knit run observed by the knit's continuum: its stitch contacts, each the midpoint
  // of its two nodes at the contact's material point (docs/models.md §11.9).
  if (p.scene.knit && p.model == "fem" && !p.target.empty()) {
    const std::vector<KnitGridContact> contacts = knit_grid_contacts(p.scene);
    if (p.target.front().points.rows() == 2 * static_cast<Eigen::Index>(contacts.size()))
      for (TargetFrame& t : p.target) {
        t.points = knit_contact_midpoints(contacts, t.points);
        t.uv.clear();
        for (const KnitGridContact& k : contacts) t.uv.push_back(k.uv);
      }
  }
  if (c.frames > static_cast<int>(p.target.size()))
    throw TrajectoryFitError("--frames: got " + std::to_string(c.frames) + ", the target " + c.target_dir.string() +
                             " has " + std::to_string(p.target.size()) + " frames after t = 0");
  for (const auto& [key, value] : c.fit.start) scene_parameter(p.scene, key);  // an unknown key: exit 2
  choose_window(c, static_cast<int>(p.target.size()), p);
  return p;
}

TrajectoryFitResult run_fit(const FitCommandConfig& config, const FitCommandPlan& p) {
  const FitCommandConfig c = with_model(config, p);
  const TrajectoryFitResult r = fit_trajectory(p.scene, p.target, c.fit);
  write_fit(c, p, r);
  return r;
}

std::vector<TrajectoryFitResult> run_fits(const std::vector<FitCommandConfig>& configs, const FitCommandPlan& p,
                                          int jobs) {
  std::vector<FitCommandConfig> starts;
  std::vector<TrajectoryFitOptions> fits;
  for (const FitCommandConfig& c : configs) {
    starts.push_back(with_model(c, p));
    fits.push_back(starts.back().fit);
  }
  const std::vector<TrajectoryFitResult> r = fit_trajectories(p.scene, p.target, fits, jobs);
  for (size_t k = 0; k < starts.size(); ++k) write_fit(starts[k], p, r[k]);
  return r;
}

void write_fit(const FitCommandConfig& c, const FitCommandPlan& p, const TrajectoryFitResult& r) {
  std::filesystem::create_directories(c.out_dir);

  Json j = Json::object();
  j.set("scene", scene_json(c.scene_path, p.scene.text, p.scene, {}));
  j.set("target", c.target_dir.string());
  j.set("model", c.fit.model);
  j.set("integrator", c.fit.integrator.empty() ? p.scene.integrator : c.fit.integrator);
  j.set("resolution", c.time_steps.describe());
  j.set("frames", static_cast<int>(p.target.size()));
  j.set("observed_points", r.observed_points);
  Json params = Json::array();
  for (const TrajectoryFitParameter& fp : r.parameters) {
    Json e = Json::object();
    e.set("key", fp.key);
    e.set("start", fp.start);
    e.set("value", fp.value);
    e.set("std_error", std::isfinite(fp.std_error) ? Json(fp.std_error) : Json(nullptr));
    e.set("lower", fp.lower);
    e.set("upper", fp.upper);
    e.set("at_bound", fp.at_bound);
    e.set("identifiable", fp.identifiable);
    e.set("frozen", fp.frozen);
    params.push(std::move(e));
  }
  j.set("parameters", std::move(params));
  Json corr = Json::array();
  for (const auto& row : r.correlation) corr.push(Json(row));
  j.set("correlation", std::move(corr));
  j.set("covariance_note", r.covariance_message.empty()
                               ? "ceres::Covariance (DENSE_SVD) of log-parameters times the residual variance"
                               : r.covariance_message);
  j.set("outcome", r.interrupted         ? "interrupted"
                   : r.final_rms.empty() ? "failed"
                   : r.converged         ? "converged"
                                         : "not_converged");
  j.set("converged", r.converged);
  j.set("stopped_at_iteration_cap", r.at_cap);
  j.set("message", r.message);
  if (r.interrupted) mark_interrupted(j, fit_stage(r));  // the message then names the signal
  Json window = Json::array();
  for (int stage_frames : p.window) window.push(stage_frames);
  j.set("growing_window", std::move(window));
  j.set("growing_window_rule", p.window_rule);
  j.set("iterations", r.iterations);
  j.set("simulations", r.simulations);
  j.set("wall_s", r.wall_s);
  j.set("cpu_s", r.cpu_s);
  Json stages = Json::array();                   // the growing window's stages (one without --growing-window)
  for (const TrajectoryFitStage& st : r.stages)  // a RMS of a stage that did not simulate is NaN: null
    stages.push(Json::object()
                    .set("frames", st.frames)
                    .set("start", Json(st.start))
                    .set("value", Json(st.value))
                    .set("converged", st.converged)
                    .set("stopped_at_iteration_cap", st.at_cap)
                    .set("message", st.message)
                    .set("frozen", Json(st.frozen))
                    .set("residual_noise_m", st.residual_noise)
                    .set("iterations", st.iterations)
                    .set("simulations", st.simulations)
                    .set("wall_s", st.wall_s)
                    .set("cpu_s", st.cpu_s)
                    .set("start_rms_m", st.start_rms)
                    .set("final_rms_m", st.final_rms));
  j.set("stages", std::move(stages));
  if (!r.start_rms.empty()) j.set("start_rms_m", *std::max_element(r.start_rms.begin(), r.start_rms.end()));
  if (!r.final_rms.empty()) j.set("final_rms_m", *std::max_element(r.final_rms.begin(), r.final_rms.end()));
  if (!r.final_rms.empty()) j.set("error_budget", fit_error_budget(c, p, r));
  j.set("created", utc_now());
  add_provenance(j);
  write_file_atomically(c.out_dir / "fit.json", j.dump());

  if (c.fit.model == "fem" && !r.final_rms.empty() && !r.interrupted) {  // usable as `weavelab run --fem-params`
    Scene fitted = p.scene;
    for (const TrajectoryFitParameter& fp : r.parameters) set_scene_parameter(fitted, fp.key, fp.value);
    write_fem_parameter_file((c.out_dir / "params.toml").string(), fem_material(fitted),
                             {{"method", "weavelab fit: trajectory of " + c.target_dir.string()},
                              {"source_scene", c.scene_path.string()},
                              {"source_scene_hash", text_hash(p.scene.text)},
                              {"frames", std::to_string(p.target.size())},
                              {"created", utc_now()}});
  }

  CsvTable conv(c.out_dir / "convergence.csv", {"stage", "frames", "iteration", "cost", "rms_m"});
  for (size_t s = 0; s < r.stages.size(); ++s) {
    const TrajectoryFitStage& st = r.stages[s];
    const double per_point = 2.0 / (r.observed_points * std::max(1, st.frames));
    for (size_t i = 0; i < st.cost_history.size(); ++i)
      conv.row({std::to_string(s + 1), std::to_string(st.frames), std::to_string(i), num(st.cost_history[i]),
                num(std::sqrt(per_point * st.cost_history[i]))});
  }
  conv.commit();

  // The point that moves most in the target, for the trajectory chart.
  int tracked = 0;
  double most = -1;
  const Eigen::MatrixXd& first = p.target.front().points;
  for (Eigen::Index i = 0; i < first.rows(); ++i) {
    const double d = (p.target.back().points.row(i) - first.row(i)).norm();
    if (d > most) most = d, tracked = static_cast<int>(i);
  }
  CsvTable frames(c.out_dir / "frames.csv",
                  {"time_s", "start_rms_m", "final_rms_m", "point", "target_x", "target_y", "target_z", "start_x",
                   "start_y", "start_z", "fitted_x", "fitted_y", "fitted_z"});
  // A simulation that failed (a numerical outcome, in the message) holds fewer
  // frames than the target: the frames it did not reach are NaN.
  auto value_at = [](const std::vector<double>& v, size_t k) { return k < v.size() ? num(v[k]) : std::string("nan"); };
  auto coordinate_at = [](const std::vector<Vec>& v, size_t k, Eigen::Index i) {
    return k < v.size() && i < v[k].size() ? num(v[k][i]) : std::string("nan");
  };
  for (size_t k = 0; k < r.times.size(); ++k) {
    std::vector<std::string> row{num(r.times[k]), value_at(r.start_rms, k), value_at(r.final_rms, k),
                                 std::to_string(tracked)};
    for (int c3 = 0; c3 < 3; ++c3) row.push_back(num(p.target[k].points(tracked, c3)));
    for (int c3 = 0; c3 < 3; ++c3) row.push_back(coordinate_at(r.start_positions, k, 3 * tracked + c3));
    for (int c3 = 0; c3 < 3; ++c3) row.push_back(coordinate_at(r.final_positions, k, 3 * tracked + c3));
    frames.row(row);
  }
  frames.commit();
}

}  // namespace wl
