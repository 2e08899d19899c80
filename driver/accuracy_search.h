// The tolerance search of `--accuracy` (docs/models.md §7.9) as a pure
// function of the trials so far. Each trial's time error is measured by the
// next trial, at least `companion_ratio` times tighter: their distance (mean
// over frames of the RMS over nodes). The same distance bounds the error of
// the tighter trial, so the search ends on a trial whose distance to the one
// before is at most the target: that trial is the run, its bound the verdict.
//
// The measured relation over ALL measured trials, a least-squares fit of
// log e = log c + α·log rtol, predicts the tolerance that meets the target
// with a safety factor. The search stops on the target, on evidence of a floor
// (the last few measured trials, spanning a stated tolerance factor, fitted
// with a slope below a stated one), at the tolerance floor, or when the trial
// budget is spent.
#pragma once
#include <string>
#include <vector>

namespace wl {

// The smallest relative tolerance a run accepts (scene key time.rtol, --rtol;
// models/scene/time_rules.cpp): below about 10⁴ ε a step's round-off
// (positions relative to ε, Newton's 64 ε floor in sdirk2) is a sizeable part
// of the tolerance, and error control asked for less cannot deliver it.
inline constexpr double kMinRtol = 1e-12;

struct ToleranceTrial {
  double rtol = 0.0;
  bool ran = false;      // its run ended ok
  double error_m = 0.0;  // its distance to the next trial that ran; NaN until then (or when it did not run)
};

// log e = log_c + slope · log rtol over the trials with a finite error > 0;
// slope NaN with fewer than two distinct tolerances among them.
struct PowerLaw {
  double log_c = 0.0, slope = 0.0;
  int points = 0;
};
PowerLaw fit_power_law(const std::vector<ToleranceTrial>& trials);

struct SearchLimits {
  double first_rtol = 1e-3;
  double companion_ratio = 10.0;     // a trial's error is measured by one at least this many times tighter
  double safety = 0.7;               // aims at safety × target
  double assumed_slope = 0.5;        // before two measured trials: error proportional to √rtol
  double min_slope = 0.1;            // below it the relation is too flat to predict from
  int floor_trials = 3;              // a floor: this many last measured trials ...
  double floor_span = 10.0;          // ... spanning at least this tolerance factor ...
  double floor_slope = 0.1;          // ... fitted with a slope below this
  double max_tighten = 1e3;          // one trial tightens the tolerance by at most this factor ...
  double max_tighten_assumed = 1e2;  // ... and by at most this one on an assumed slope
  double min_rtol = kMinRtol;
  int max_trials = 6;
};

enum class SearchVerdict { reached, next_trial, floor, tolerance_floor, budget };
const char* to_string(SearchVerdict v);

struct SearchStep {
  SearchVerdict verdict = SearchVerdict::next_trial;
  double next_rtol = 0.0;  // with next_trial
  double bound_m = 0.0;    // the last trial's error bound (NaN when none)
  double slope = 0.0;      // the slope used (NaN when none)
  std::string reason;      // why the search stopped short of the target, or how the next tolerance was chosen
};

// The last trial's error bound: the error measured for the trial that ran
// before it (their distance), when that one is at least `companion_ratio`
// times looser; NaN otherwise.
double last_trial_bound(const std::vector<ToleranceTrial>& trials, const SearchLimits& limits = {});

// What to do after `trials` (in the order run, non-empty) for `target_m`.
SearchStep next_tolerance(const std::vector<ToleranceTrial>& trials, double target_m, const SearchLimits& limits = {});

}  // namespace wl
