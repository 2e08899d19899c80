#include "experiments/driver/run.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <sstream>

#include "experiments/driver/model_factory.h"
#include "experiments/driver/run_summary.h"
#include "experiments/output/metrics_csv.h"
#include "experiments/output/pvd_series.h"

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

}  // namespace

RunReport run_scene(const Scene& scene, const RunOptions& options) {
  auto model = make_model(scene, options.model);
  auto integrator = make_integrator(scene.integrator);
  IntegratorOptions iopt;
  iopt.dt = scene.dt_s;
  iopt.adaptive = scene.adaptive;
  iopt.rtol = scene.rtol;
  iopt.atol = scene.atol;

  std::filesystem::create_directories(options.out_dir);
  PvdSeries series(options.out_dir, "run");
  MetricsCsv metrics(options.out_dir / "metrics.csv",
                     {"time_s", "kinetic_J", "potential_J", "max_speed_m_per_s", "newton_iters", "step_wall_s"});
  if (options.progress)
    std::fprintf(stderr, "weavelab: %s model, %d DoFs, %s, dt = %g s, %g s simulated -> %s\n", model->name().c_str(),
                 model->num_dofs(), scene.integrator.c_str(), scene.dt_s, scene.duration_s,
                 options.out_dir.string().c_str());

  Progress progress(options.progress, scene.duration_s);
  integrator->initialize(*model, 0.0, model->initial_q(), model->initial_v(), iopt);
  Evaluation scratch;
  auto metrics_row = [&](double t, int iters, double wall) {
    const Vec& q = integrator->q();
    const Vec& v = integrator->v();
    metrics.row({t, kinetic_energy(*model, t, q, v, scratch), model->potential_energy(q), model->max_node_speed(v),
                 double(iters), wall});
  };
  integrator->on_step = [&](const StepRecord& r) {
    metrics_row(r.t, r.nonlinear_iters, r.wall_s);
    progress.update(r.t, integrator->stats().steps);
  };

  RunReport rep;
  metrics_row(0.0, 0, 0.0);
  series.add(model->frame(0.0, integrator->q(), integrator->v()));
  rep.frames = 1;
  const int outputs = static_cast<int>(std::llround(scene.duration_s / scene.output_interval_s));
  for (int k = 1; k <= outputs; ++k) {
    const double t_out = std::min(scene.duration_s, k * scene.output_interval_s);
    rep.result = integrator->advance_to(t_out);
    if (rep.result.outcome != Outcome::ok) break;
    series.add(model->frame(integrator->t(), integrator->q(), integrator->v()));
    ++rep.frames;
  }
  if (rep.result.outcome == Outcome::ok && integrator->t() < scene.duration_s - 1e-12) {
    rep.result = integrator->advance_to(scene.duration_s);
    if (rep.result.outcome == Outcome::ok) {
      series.add(model->frame(integrator->t(), integrator->q(), integrator->v()));
      ++rep.frames;
    }
  }
  progress.update(integrator->t(), integrator->stats().steps, true);
  metrics.commit();
  rep.stats = integrator->stats();
  rep.end_time = integrator->t();
  write_run_summary(options.out_dir / "summary.json", scene, options, *model, *integrator, rep);
  return rep;
}

}  // namespace wl
