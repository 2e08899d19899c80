#include "driver/time_error.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "driver/interrupt.h"

namespace wl {

void frame_distances(const Trajectory& a, const Trajectory& b, double factor, std::vector<double>& rms,
                     std::vector<double>& max) {
  if (a.positions.rows() != b.positions.rows() || a.positions.cols() != b.positions.cols())
    throw std::invalid_argument("frame_distances: trajectories of different shapes");
  const int nodes = a.nodes();
  rms.assign(a.positions.cols(), 0.0);
  max.assign(a.positions.cols(), 0.0);
  for (Eigen::Index k = 0; k < a.positions.cols(); ++k) {
    double sum = 0.0;
    for (int n = 0; n < nodes; ++n) {
      const double d = factor * (a.positions.col(k).segment<3>(3 * n) - b.positions.col(k).segment<3>(3 * n)).norm();
      sum += d * d;
      max[k] = std::max(max[k], d);
    }
    rms[k] = nodes > 0 ? std::sqrt(sum / nodes) : 0.0;
  }
}

TimeErrorEstimate estimate_time_error(const Scene& scene, const std::string& model_name,
                                      const std::string& integrator_name, const IntegratorOptions& options,
                                      const RecordedRun& run, bool progress,
                                      const std::function<void(double t)>& on_step) {
  const IntegratorCapabilities cap = make_integrator(integrator_name)->capabilities();
  TimeErrorEstimate e;
  IntegratorOptions second = options;
  RecordOptions record;
  record.progress = progress;
  record.label = "time error:";
  double factor = 1.0;
  if (cap.replays_steps && cap.fixed_step_order > 0) {
    if (run.step_ends.empty())
      throw std::invalid_argument("estimate_time_error: the run's step ends were not recorded");
    e.method = "richardson";
    e.order = cap.fixed_step_order;
    double t_prev = 0.0;
    for (double t : run.step_ends) {
      record.schedule.push_back(0.5 * (t_prev + t));
      record.schedule.push_back(t);
      t_prev = t;
    }
  } else if (options.adaptive) {
    e.method = "tolerance";
    second.rtol = options.rtol / 100;
    second.atol = options.atol / 100;
  } else {
    e.method = "halved_step";
    e.order = cap.fixed_step_order;
    second.dt = options.dt / 2;
  }
  if (e.order > 0) factor = std::ldexp(1.0, e.order) / (std::ldexp(1.0, e.order) - 1.0);
  second.max_steps = std::max(second.max_steps, 2 * run.stats.steps + 16);
  record.on_step = [&](Model&, double t, const Vec&, const Vec&) {
    if (on_step) on_step(t);
    throw_if_interrupted();
  };
  RecordedRun refined;
  try {
    refined = run_recorded(scene, model_name, integrator_name, second, record);
  } catch (const Interrupted&) {
    e.second_run = {Outcome::interrupted, interrupted_message(interrupt_signal())};
    return e;
  }
  e.second_run = refined.result;
  e.second_run_cpu_s = refined.cpu_s;
  e.second_run_steps = refined.stats.steps;
  if (!e.ok()) return e;
  if (refined.trajectory.positions.cols() != run.trajectory.positions.cols()) {
    e.second_run = {Outcome::diverged, "the second run recorded a different number of frames"};
    return e;
  }
  e.times = run.trajectory.times;
  frame_distances(run.trajectory, refined.trajectory, factor, e.rms, e.max);
  for (size_t k = 0; k < e.rms.size(); ++k) {
    e.mean_rms += e.rms[k] / double(e.rms.size());
    e.max_max = std::max(e.max_max, e.max[k]);
  }
  return e;
}

std::string error_budget_verdict(double distance_m, const TimeErrorEstimate& a, const TimeErrorEstimate& b) {
  if (!a.ok() || !b.ok()) return "time error unknown";
  const double worst = std::max(a.mean_rms, b.mean_rms);
  if (worst > distance_m) return "time error exceeds the distance";
  if (worst > 0.1 * distance_m) return "time error above a tenth of the distance";
  return "resolved";
}

Json TimeErrorEstimate::to_json() const {
  Json j = Json::object();
  j.set("method", method);
  if (order > 0) j.set("order", order);
  j.set("second_run_outcome", to_string(second_run.outcome));
  if (!ok()) {
    j.set("second_run_message", second_run.message);
    return j;
  }
  j.set("mean_rms_m", mean_rms);
  j.set("max_m", max_max);
  j.set("second_run_cpu_s", second_run_cpu_s);
  j.set("second_run_steps", second_run_steps);
  j.set("times_s", times);
  j.set("rms_m", rms);
  j.set("max_per_frame_m", max);
  return j;
}

}  // namespace wl
