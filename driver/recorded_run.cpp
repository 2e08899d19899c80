#include "driver/recorded_run.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <stdexcept>
#include <utility>

#include "driver/interrupt.h"
#include "models/model_factory.h"

namespace wl {

std::vector<double> output_times(const Scene& scene) {
  const int outputs = std::max(1, static_cast<int>(std::llround(scene.duration_s / scene.output_interval_s)));
  std::vector<double> t;
  for (int k = 1; k <= outputs; ++k) t.push_back(std::min(scene.duration_s, k * scene.output_interval_s));
  if (t.back() < scene.duration_s - 1e-12) t.push_back(scene.duration_s);
  return t;
}

RecordedRun run_recorded(const Scene& scene, const std::string& model_name, const std::string& integrator_name,
                         const IntegratorOptions& options, const RecordOptions& record) {
  auto model = make_model(scene, model_name);
  auto integrator = make_integrator(integrator_name);
  IntegratorOptions opt = options;
  opt.runaway_speed = std::min(opt.runaway_speed, record.speed_bound);
  std::vector<double> points;  // the times advance_to is called with
  const std::vector<double> times = output_times(scene);
  if (record.schedule.empty()) {
    points = times;
  } else {
    if (!integrator->capabilities().replays_steps)
      throw std::invalid_argument("integrator '" + integrator_name + "' cannot replay a step sequence");
    points = record.schedule;
    double widest = 0.0, t_prev = 0.0;
    for (double t : points) widest = std::max(widest, t - std::exchange(t_prev, t));
    opt.adaptive = false;
    opt.dt = widest * (1.0 + 1e-9);
  }

  RecordedRun run;
  run.dofs = model->num_dofs();
  const int nodes = static_cast<int>(model->frame(0.0, model->initial_q(), model->initial_v()).points.rows());
  run.trajectory.positions.resize(3 * nodes, static_cast<Eigen::Index>(times.size()));

  using clock = std::chrono::steady_clock;
  const auto start = clock::now();
  auto last_report = start;
  double cpu = 0.0, wall = 0.0;
  auto timed = [&](auto&& body) {
    const std::clock_t c0 = std::clock();
    const auto w0 = clock::now();
    body();
    cpu += double(std::clock() - c0) / CLOCKS_PER_SEC;
    wall += std::chrono::duration<double>(clock::now() - w0).count();
  };

  integrator->on_step = [&](const StepRecord& r) {
    if (record.step_ends) run.step_ends.push_back(r.t);
    if (record.on_step) record.on_step(*model, r.t, integrator->q(), integrator->v());
    const double s = max_node_speed(*model, integrator->v());
    run.max_node_speed = std::max(run.max_node_speed, std::isfinite(s) ? s : std::numeric_limits<double>::infinity());
    if (record.progress) {
      const auto now = clock::now();
      if (std::chrono::duration<double>(now - last_report).count() >= 5.0) {
        last_report = now;
        std::fprintf(stderr, "    %s t = %.4g / %.4g s, %ld steps, %.0f s\n", record.label.c_str(), r.t,
                     scene.duration_s, integrator->stats().steps, std::chrono::duration<double>(now - start).count());
      }
    }
    if (record.stop_at_signal) throw_if_interrupted();
  };

  timed([&] { integrator->initialize(*model, 0.0, model->initial_q(), model->initial_v(), opt); });
  int reached = 0;
  Evaluation scratch;
  if (record.energies)
    run.initial_energy_J = model->kinetic_energy(0.0, model->initial_q(), model->initial_v(), scratch) +
                           model->potential_energy(model->initial_q());
  size_t next_output = 0;
  for (double t_out : points) {
    timed([&] { run.result = integrator->advance_to(t_out); });
    if (run.result.outcome == Outcome::ok && run.max_node_speed > record.speed_bound)
      run.result = {Outcome::diverged,
                    "max node speed " + std::to_string(run.max_node_speed) + " m/s exceeds the bound " +
                        std::to_string(record.speed_bound) + " m/s",
                    FailureCause::runaway_speed};
    if (run.result.outcome != Outcome::ok) break;
    if (next_output == times.size() || std::abs(t_out - times[next_output]) > 1e-9 * std::max(opt.dt, 1e-12))
      continue;  // a replayed step end between two output times
    t_out = times[next_output++];
    const Frame f = model->frame(integrator->t(), integrator->q(), integrator->v());
    run.trajectory.times.push_back(t_out);
    run.trajectory.positions.col(reached) = Eigen::Map<const Eigen::VectorXd>(f.points.data(), 3 * nodes);
    ++reached;
    if (record.energies) {
      run.kinetic_J.push_back(model->kinetic_energy(integrator->t(), integrator->q(), integrator->v(), scratch));
      run.potential_J.push_back(model->potential_energy(integrator->q()));
    }
    if (record.on_frame) record.on_frame(f);
  }
  run.trajectory.positions.conservativeResize(Eigen::NoChange, reached);
  run.cpu_s = cpu;
  run.wall_s = wall;
  run.end_time = integrator->t();
  run.stats = integrator->stats();
  return run;
}

}  // namespace wl
