#include "driver/accuracy.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "driver/interrupt.h"

namespace wl {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

}  // namespace

TimeErrorEstimate estimate_from_looser_trial(const Trajectory& loose, const Trajectory& tight, double loose_cpu_s) {
  TimeErrorEstimate e;
  e.method = "looser_trial";
  e.second_run_cpu_s = loose_cpu_s;
  if (loose.positions.cols() != tight.positions.cols()) {
    e.second_run = {Outcome::diverged, "the looser trial recorded a different number of frames"};
    return e;
  }
  e.times = tight.times;
  frame_distances(loose, tight, 1.0, e.rms, e.max);
  for (size_t k = 0; k < e.rms.size(); ++k) {
    e.mean_rms += e.rms[k] / double(e.rms.size());
    e.max_max = std::max(e.max_max, e.max[k]);
  }
  return e;
}

double AccuracyChoice::trials_cpu_s() const {
  double sum = 0.0;
  for (const AccuracyTrial& t : trials) sum += t.cpu_s;
  return sum;
}

AccuracyChoice search_accuracy(double target_m, const std::function<TrialRun(double rtol, int trial)>& run_trial,
                               bool progress, const SearchLimits& limits) {
  AccuracyChoice c;
  c.target_m = target_m;
  std::vector<ToleranceTrial> tolerances;
  TrialRun looser;  // the last trial that ran
  int looser_index = -1;
  double rtol = limits.first_rtol;
  for (int k = 1;; ++k) {
    TrialRun run = run_trial(rtol, k);
    c.rtol = rtol;
    c.atol = 1e-3 * rtol;
    c.trials.push_back({rtol, kNaN, run.cpu_s, to_string(run.result.outcome)});
    c.estimate = TimeErrorEstimate{};
    c.estimate.second_run = {Outcome::not_offered, "no trial before this one ran"};
    if (run.result.outcome == Outcome::interrupted) {
      c.verdict = "interrupted";
      c.note = run.result.message;
      c.estimate.second_run = run.result;
      return c;
    }
    const bool ran = run.result.outcome == Outcome::ok;
    tolerances.push_back({rtol, ran, kNaN});
    if (ran && looser_index >= 0) {
      c.estimate = estimate_from_looser_trial(looser.trajectory, run.trajectory, looser.cpu_s);
      if (c.estimate.ok()) c.trials[looser_index].estimate_m = tolerances[looser_index].error_m = c.estimate.mean_rms;
    }
    if (ran) looser = std::move(run), looser_index = k - 1;
    const SearchStep step = next_tolerance(tolerances, target_m, limits);
    if (progress) {
      std::fprintf(stderr, "weavelab: accuracy trial %d: sdirk2 rtol %.3g %s, %.1f s CPU", k, rtol,
                   c.trials.back().outcome.c_str(), c.trials.back().cpu_s);
      if (k > 1 && std::isfinite(c.trials[k - 2].estimate_m))
        std::fprintf(stderr, "; trial %d's time error %.3g m, a bound of this one's (target %.3g m)", k - 1,
                     c.trials[k - 2].estimate_m, target_m);
      std::fprintf(stderr, "\n");
    }
    if (step.verdict != SearchVerdict::next_trial) {
      c.reached = step.verdict == SearchVerdict::reached;
      c.verdict = to_string(step.verdict);
      c.note = step.reason;
      if (progress && c.reached)
        std::fprintf(stderr,
                     "weavelab: time error target met: the run, sdirk2 at rtol %.3g, has its time error bounded "
                     "by %.3g m, its distance to the trial before (target %.3g m); the trials took %.1f s CPU\n",
                     rtol, step.bound_m, target_m, c.trials_cpu_s());
      return c;
    }
    if (progress) std::fprintf(stderr, "weavelab: next: rtol %.3g: %s\n", step.next_rtol, step.reason.c_str());
    rtol = step.next_rtol;
  }
}

AccuracyChoice choose_for_accuracy(const Scene& scene, const std::string& model_name, double target_m, bool progress,
                                   const SearchLimits& limits) {
  auto run_trial = [&](double rtol, int) {
    IntegratorOptions opt;
    opt.linear_solver = parse_linear_solver(scene.linear_solver);
    opt.adaptive = true;
    opt.dt = scene.dt_s;
    opt.rtol = rtol;
    opt.atol = 1e-3 * rtol;
    RecordOptions record;
    record.progress = progress;
    record.label = "accuracy trial:";
    record.on_step = [](Model&, double, const Vec&, const Vec&) { throw_if_interrupted(); };
    try {
      const RecordedRun run = run_recorded(scene, model_name, "sdirk2", opt, record);
      return TrialRun{run.result, run.trajectory, run.cpu_s};
    } catch (const Interrupted&) {
      return TrialRun{{Outcome::interrupted, interrupted_message(interrupt_signal())}, {}, 0.0};
    }
  };
  return search_accuracy(target_m, run_trial, progress, limits);
}

Json AccuracyChoice::to_json() const {
  Json j = Json::object();
  j.set("target_m", target_m);
  j.set("reached", reached);
  j.set("verdict", verdict);
  if (!note.empty()) j.set("note", note);
  j.set("integrator", integrator);
  j.set("rtol", rtol);
  j.set("atol", atol);
  j.set("trials_cpu_s", trials_cpu_s());
  Json trials_json = Json::array();
  for (const AccuracyTrial& t : trials) {
    Json tj = Json::object();
    tj.set("rtol", t.rtol);
    tj.set("estimate_mean_rms_m", t.estimate_m);
    tj.set("cpu_s", t.cpu_s);
    tj.set("outcome", t.outcome);
    trials_json.push(tj);
  }
  j.set("trials", trials_json);
  return j;
}

}  // namespace wl
