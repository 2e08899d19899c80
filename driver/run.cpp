#include "driver/run.h"

#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <iostream>
#include <memory>
#include <optional>
#include <sstream>

#include "driver/interrupt.h"
#include "driver/run_settings.h"
#include "driver/run_summary.h"
#include "models/common/intersection_count.h"
#include "models/model_factory.h"
#include "output/atomic_file.h"
#include "output/metrics_csv.h"
#include "output/pvd_series.h"
#include "output/run_folder.h"
#include "output/self_intersection.h"

namespace wl {
namespace {

class Progress {
 public:
  Progress(bool enabled, double t_end) : enabled_(enabled), t_end_(t_end), start_(clock::now()), last_(start_) {}
  void update(double t, long steps, bool force = false) {
    if (!enabled_) return;
    const auto now = clock::now();
    if (!force && std::chrono::duration<double>(now - last_).count() < 2.0) return;
    last_ = now;
    const double elapsed = std::chrono::duration<double>(now - start_).count();
    const double frac = t_end_ > 0 ? t / t_end_ : 1.0;
    const double eta = frac > 0 ? elapsed * (1.0 - frac) / frac : 0.0;
    std::fprintf(stderr, "  t = %.4g / %.4g s (%3.0f%%), %ld steps, %.1f s elapsed, ETA %.1f s\n", t, t_end_,
                 100.0 * frac, steps, elapsed, eta);
  }

 private:
  using clock = std::chrono::steady_clock;
  bool enabled_;
  double t_end_;
  clock::time_point start_, last_;
};

// The files a run writes (and a rerun into the same folder replaces), with
// their temporary names: run.pvd, frames/run_NNNNN.vtu, with obstacles
// obstacles.pvd, frames/obstacles_NNNNN.vtu and self_intersections.csv(.part),
// metrics.csv(.part), summary.json.
bool written_by_a_run(const std::filesystem::path& rel) {
  const std::string name = rel.filename().string();
  const std::string base = name.substr(0, name.find(".tmp-"));
  if (rel.parent_path() == "frames")
    return (base.starts_with("run_") || base.starts_with("obstacles_")) && base.ends_with(".vtu");
  if (!rel.parent_path().empty()) return false;
  return base == "run.pvd" || base == "obstacles.pvd" || base == "metrics.csv" || base == "metrics.csv.part" ||
         base == "self_intersections.csv" || base == "self_intersections.csv.part" || base == "summary.json";
}

StepResult interrupted_result() { return {Outcome::interrupted, interrupted_message(interrupt_signal())}; }

// The force at (q, 0): an equilibrium has none on a free DoF (the velocity
// terms, friction's damping among them, are left out; its anchors are not).
SettledBalance settled_balance(const Scene& scene, Model& model, double t, const Vec& q, const Vec& v) {
  Evaluation ev;
  allocate_evaluation(model, ev);
  model.evaluate(t, q, Vec::Zero(v.size()), kForce | kMass, ev);
  Vec free_force = ev.force;
  for (int i : model.fixed_dofs()) free_force[i] = 0.0;
  const auto& g = scene.gravity_m_per_s2;
  SettledBalance b;
  b.max_force_N = free_force.lpNorm<Eigen::Infinity>();
  b.heaviest_weight_N = Vec(ev.mass.diagonal()).maxCoeff() * std::sqrt(g[0] * g[0] + g[1] * g[1] + g[2] * g[2]);
  b.kinetic_J = 0.5 * v.dot(ev.mass * v);
  return b;
}

IntegratorOptions run_integrator_options(const Scene& scene) {
  IntegratorOptions iopt;
  iopt.linear_solver = parse_linear_solver(scene.linear_solver);
  iopt.dt = scene.dt_s;
  iopt.adaptive = scene.adaptive;
  iopt.rtol = scene.rtol;
  iopt.atol = scene.atol;
  return iopt;
}

// The files of a run folder, open while the run writes them (none for a run in memory).
struct RunFiles {
  std::optional<RunFolder> folder;
  std::optional<PvdSeries> series;
  std::optional<MetricsCsv> metrics;
  // The rigid obstacles, a second series beside the cloth's (docs/models.md §3.11.5).
  // With them, the cloth's self-intersecting triangle pairs per frame (CGAL, docs/models.md §3.11.7);
  // a model that counts its own (IntersectionCount: the knit's overlapping yarn capsules, §11.7) writes its count.
  std::optional<PvdSeries> obstacle_series;
  std::optional<MetricsCsv> intersections;

  RunFiles(const std::filesystem::path& out_dir, const Model& model) {
    if (out_dir.empty()) return;
    folder.emplace(out_dir, written_by_a_run);
    series.emplace(out_dir, "run");
    metrics.emplace(out_dir / "metrics.csv",
                    std::vector<std::string>{"time_s", "kinetic_J", "potential_J", "max_speed_m_per_s", "newton_iters",
                                             "step_wall_s"});
    const IntersectionCount* counter = intersection_count(model);
    if (model.obstacle_frame(0.0).points.rows() > 0) obstacle_series.emplace(out_dir, "obstacles");
    if (counter || obstacle_series)
      intersections.emplace(out_dir / "self_intersections.csv",
                            std::vector<std::string>{"time_s", counter ? counter->intersection_column()
                                                                       : std::string("intersecting_triangle_pairs")});
  }
};

// Steps to the scene's duration, a frame at each output time: the outcome and the frame count.
// The settling phase (time.settle_dt_s): steps of settle_dt_s from settle_after_s on.
void step_to_duration(const Scene& scene, Model& model, Integrator& integrator,
                      const std::function<void(Frame)>& add_frame, RunReport& rep) {
  bool settling = false;
  auto advance = [&](double t_out) {
    if (interrupt_signal()) return interrupted_result();
    try {
      if (scene.settle_dt_s > 0.0 && !settling && t_out > scene.settle_after_s) {
        if (integrator.t() < scene.settle_after_s) {
          const StepResult r = integrator.advance_to(scene.settle_after_s);
          if (r.outcome != Outcome::ok) return r;
        }
        integrator.set_fixed_step(scene.settle_dt_s);
        settling = true;
      }
      return integrator.advance_to(t_out);
    } catch (const Interrupted&) {
      return interrupted_result();
    }
  };
  const int outputs = static_cast<int>(std::llround(scene.duration_s / scene.output_interval_s));
  for (int k = 1; k <= outputs; ++k) {
    const double t_out = std::min(scene.duration_s, k * scene.output_interval_s);
    rep.result = advance(t_out);
    if (rep.result.outcome != Outcome::ok) break;
    add_frame(model.frame(integrator.t(), integrator.q(), integrator.v()));
    ++rep.frames;
  }
  if (rep.result.outcome == Outcome::ok && integrator.t() < scene.duration_s - 1e-12) {
    rep.result = advance(scene.duration_s);
    if (rep.result.outcome == Outcome::ok) {
      add_frame(model.frame(integrator.t(), integrator.q(), integrator.v()));
      ++rep.frames;
    }
  }
}

// Scene key time.error_estimate: the time error of a run that ended ok, from a
// second run. A signal during the second run ends it, and the run with it.
void estimate_run_time_error(const Scene& scene, const RunOptions& options, const IntegratorOptions& iopt,
                             RecordedRun& record, RunReport& rep) {
  if (!scene.error_estimate || rep.result.outcome != Outcome::ok) return;
  if (options.progress) std::fprintf(stderr, "weavelab: estimating the time error (a second run)\n");
  record.stats = rep.stats;
  std::function<void(double)> observe;
  if (options.on_step) observe = [&](double t) { options.on_step("time error", t); };
  rep.time_error = estimate_time_error(scene, options.model, scene.integrator, iopt, record, options.progress, observe);
  if (rep.time_error->second_run.outcome == Outcome::interrupted) {
    rep.result = rep.time_error->second_run;
    return;
  }
  if (!options.progress) return;
  if (rep.time_error->ok())
    std::fprintf(stderr, "weavelab: time error (%s): mean RMS %.3g m, max %.3g m\n", rep.time_error->method.c_str(),
                 rep.time_error->mean_rms, rep.time_error->max_max);
  else
    std::fprintf(stderr, "weavelab: no time error estimate: the second run ended %s: %s\n",
                 to_string(rep.time_error->second_run.outcome), rep.time_error->second_run.message.c_str());
}

void print_measures(const RunReport& rep) {
  if (!rep.drape) return;
  if (*rep.drape)
    std::fprintf(stderr, "weavelab: drape at t = %g s: coefficient %.4g, %d folds\n", (*rep.drape)->time_s,
                 (*rep.drape)->coefficient, (*rep.drape)->folds);
  else std::fprintf(stderr, "weavelab: drape not measured: the last frame's shadow is too large to rasterize\n");
}

// One run as written: its model and integrator (for the summary), its open
// files (the folder stays locked until the summary is written), its report,
// and what an estimate needs (step ends and node positions at the frames).
struct WrittenRun {
  std::unique_ptr<Model> model;
  std::unique_ptr<Integrator> integrator;
  std::unique_ptr<RunFiles> files;
  RunReport rep;
  RecordedRun record;
  std::vector<Frame> held_frames;  // the frames options.on_frame gets later (--accuracy trials)
};

// The intersecting pairs of a frame at state q: the model's own count, else the triangles' (CGAL).
long count_intersections(const Model& model, const Vec& q, const Frame& f) {
  if (const IntersectionCount* counter = intersection_count(model)) return counter->intersecting_pairs(q);
  return count_self_intersections(f);
}

// Runs `scene` into options.out_dir: frames and metrics.csv; the report, not the
// summary. `phase` names it for options.on_step. `keep` fills w.record;
// `hold_frames` keeps the frames in w.held_frames instead of calling options.on_frame.
void written_run(const Scene& scene, const RunOptions& options, const std::string& phase, bool keep, bool hold_frames,
                 WrittenRun& w) {
  const std::clock_t cpu_start = std::clock();
  w.model = make_model(scene, options.model);
  Model& model = *w.model;
  check_linear_solver(scene, model, options.overrides);
  w.integrator = make_integrator(scene.integrator);
  Integrator& integrator = *w.integrator;
  const IntegratorOptions iopt = run_integrator_options(scene);
  w.files = std::make_unique<RunFiles>(options.out_dir, model);
  RunFiles& files = *w.files;
  if (options.progress)
    std::fprintf(stderr, "weavelab: %s model, %d DoFs, %s, dt = %g s, %g s simulated -> %s\n", model.name().c_str(),
                 model.num_dofs(), scene.integrator.c_str(), scene.dt_s, scene.duration_s,
                 options.out_dir.string().c_str());

  Progress progress(options.progress, scene.duration_s);
  RecordedRun& record = w.record;
  auto keep_frame = [&](const Frame& f) {
    if (!keep || f.time == 0.0) return;
    const Eigen::Index rows = static_cast<Eigen::Index>(f.points.size());
    record.trajectory.positions.conservativeResize(rows, record.trajectory.positions.cols() + 1);
    record.trajectory.positions.col(record.trajectory.positions.cols() - 1) =
        Eigen::Map<const Eigen::VectorXd>(f.points.data(), rows);
    record.trajectory.times.push_back(f.time);
  };
  Frame last_frame;  // what the scene's [measures] are taken on
  auto add_frame = [&](Frame f) {
    keep_frame(f);
    if (files.series) files.series->add(f);
    if (hold_frames) w.held_frames.push_back(f);
    else if (options.on_frame) options.on_frame(f);
    if (files.obstacle_series) files.obstacle_series->add(model.obstacle_frame(f.time));
    if (files.intersections) files.intersections->row({f.time, double(count_intersections(model, integrator.q(), f))});
    last_frame = std::move(f);
  };
  integrator.initialize(model, 0.0, model.initial_q(), model.initial_v(), iopt);
  Evaluation scratch;
  auto metrics_row = [&](double t, int iters, double wall) {
    if (!files.metrics) return;
    const Vec& q = integrator.q();
    const Vec& v = integrator.v();
    files.metrics->row({t, model.kinetic_energy(t, q, v, scratch), model.potential_energy(q), max_node_speed(model, v),
                        double(iters), wall});
  };
  integrator.on_step = [&](const StepRecord& r) {
    metrics_row(r.t, r.nonlinear_iters, r.wall_s);
    if (keep) record.step_ends.push_back(r.t);
    progress.update(r.t, integrator.stats().steps);
    if (options.on_step) options.on_step(phase, r.t);
    throw_if_interrupted();
  };

  RunReport& rep = w.rep;
  metrics_row(0.0, 0, 0.0);
  add_frame(model.frame(0.0, integrator.q(), integrator.v()));
  rep.frames = 1;
  step_to_duration(scene, model, integrator, add_frame, rep);
  progress.update(integrator.t(), integrator.stats().steps, true);
  if (files.metrics) files.metrics->commit();
  if (files.intersections) files.intersections->commit();
  rep.stats = integrator.stats();
  rep.end_time = integrator.t();
  if (scene.settle_dt_s > 0.0 && rep.result.outcome == Outcome::ok)
    rep.settled = settled_balance(scene, model, integrator.t(), integrator.q(), integrator.v());
  if (scene.measures.drape) rep.drape = measure_drape(last_frame, drape_geometry(scene));
  if (options.progress) print_measures(rep);
  record.result = rep.result;
  record.stats = rep.stats;
  record.end_time = rep.end_time;
  record.cpu_s = double(std::clock() - cpu_start) / CLOCKS_PER_SEC;
}

void write_summary(const Scene& scene, const RunOptions& options, WrittenRun& w) {
  w.rep.summary_json = run_summary_json(scene, options, *w.model, *w.integrator, w.rep);
  if (!options.out_dir.empty()) write_file_atomically(options.out_dir / "summary.json", w.rep.summary_json);
}

// The scene of one --accuracy trial: sdirk2 under error control at `rtol` (atol = 1e-3 rtol m).
Scene trial_scene(const Scene& scene, double rtol) {
  Scene s = scene;
  s.integrator = "sdirk2";
  s.adaptive = true;
  s.rtol = rtol;
  s.atol = 1e-3 * rtol;
  s.error_estimate = false;  // the trials estimate each other's errors (driver/accuracy.h)
  return s;
}

// Scene key time.accuracy_m: every trial is a written run into the output
// folder (each replaces the one before), so the chosen run is the last trial
// and is not run again; the summary records the trials and the estimate.
RunReport run_for_accuracy(const Scene& scene, const RunOptions& options) {
  (void)make_model(scene, options.model);  // a model the scene cannot build fails before the trials
  if (options.progress)
    std::fprintf(stderr, "weavelab: choosing the integrator and tolerance for a time error of %g m\n",
                 scene.accuracy_m);
  WrittenRun w;
  Scene last_scene = scene;
  auto run_trial = [&](double rtol, int k) {
    w.files.reset();  // the folder of the trial before is closed before this one opens it
    w.integrator.reset();
    w = WrittenRun{};
    last_scene = trial_scene(scene, rtol);
    written_run(last_scene, options, "accuracy trial " + std::to_string(k), true, true, w);
    return TrialRun{w.record.result, w.record.trajectory, w.record.cpu_s};
  };
  AccuracyChoice choice = search_accuracy(scene.accuracy_m, run_trial, options.progress);
  if (options.on_frame)
    for (const Frame& f : w.held_frames) options.on_frame(f);
  w.rep.accuracy = std::move(choice);
  if (w.rep.accuracy->estimate.ok()) w.rep.time_error = w.rep.accuracy->estimate;
  write_summary(last_scene, options, w);
  return std::move(w.rep);
}

}  // namespace

RunReport run_scene(const Scene& scene, const RunOptions& options_in) {
  RunOptions options = options_in;
  if (options.model.empty()) options.model = yarn_level_model(scene);
  check_run_memory(scene, options.model);
  if (scene.accuracy_m > 0.0) return run_for_accuracy(scene, options);
  WrittenRun w;
  written_run(scene, options, "run", scene.error_estimate, false, w);
  estimate_run_time_error(scene, options, run_integrator_options(scene), w.record, w.rep);
  write_summary(scene, options, w);
  return std::move(w.rep);
}

}  // namespace wl
