#include "driver/accuracy.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

namespace wl {

AccuracyChoice choose_for_accuracy(const Scene& scene, const std::string& model_name, double target_m, bool progress,
                                   int max_trials) {
  AccuracyChoice c;
  c.target_m = target_m;
  double rtol = 1e-4;  // first trial; later ones scale it by target / estimate
  for (int k = 0; k < max_trials; ++k) {
    IntegratorOptions opt;
    opt.linear_solver = parse_linear_solver(scene.linear_solver);
    opt.adaptive = true;
    opt.dt = scene.dt_s;
    opt.rtol = rtol;
    opt.atol = 1e-3 * rtol;
    RecordOptions record;
    record.step_ends = true;
    record.progress = progress;
    record.label = "accuracy trial:";
    const RecordedRun run = run_recorded(scene, model_name, c.integrator, opt, record);
    AccuracyTrial trial{rtol, std::numeric_limits<double>::quiet_NaN(), run.cpu_s, to_string(run.result.outcome)};
    c.rtol = opt.rtol;
    c.atol = opt.atol;
    if (run.result.outcome == Outcome::ok) {
      c.estimate = estimate_time_error(scene, model_name, c.integrator, opt, run, progress);
      trial.cpu_s += c.estimate.second_run_cpu_s;
      trial.outcome = to_string(c.estimate.second_run.outcome);
      if (c.estimate.ok()) trial.estimate_m = c.estimate.mean_rms;
    }
    c.trials.push_back(trial);
    if (progress)
      std::fprintf(
          stderr,
          "weavelab: accuracy trial %d: sdirk2 rtol %.3g -> estimated time error %.3g m (target %.3g m), %.1f s CPU\n",
          k + 1, rtol, trial.estimate_m, target_m, trial.cpu_s);
    if (!std::isfinite(trial.estimate_m)) {
      rtol /= 10;  // a failed run or estimate: a tighter tolerance takes smaller steps
      continue;
    }
    if (trial.estimate_m <= target_m) {
      c.reached = true;
      break;
    }
    // A tighter tolerance that no longer lowers the estimate: the error has a
    // floor that error control does not reach (docs/models.md §7.10).
    const size_t n = c.trials.size();
    if (n >= 2 && std::isfinite(c.trials[n - 2].estimate_m) && trial.estimate_m > 0.8 * c.trials[n - 2].estimate_m) {
      c.note = "the estimate stopped following the tolerance (" + std::to_string(c.trials[n - 2].estimate_m) +
               " m at rtol " + std::to_string(c.trials[n - 2].rtol) + ", " + std::to_string(trial.estimate_m) +
               " m at rtol " + std::to_string(rtol) + "): a floor above the target";
      break;
    }
    // The error of an error-controlled run follows its tolerance: aim 30 % below.
    rtol *= std::clamp(0.7 * target_m / trial.estimate_m, 1e-3, 0.5);
  }
  return c;
}

Json AccuracyChoice::to_json() const {
  Json j = Json::object();
  j.set("target_m", target_m);
  j.set("reached", reached);
  if (!note.empty()) j.set("note", note);
  j.set("integrator", integrator);
  j.set("rtol", rtol);
  j.set("atol", atol);
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
