#include "driver/accuracy_search.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <optional>

namespace wl {
namespace {

constexpr double kNoFit = std::numeric_limits<double>::quiet_NaN();

bool measured(const ToleranceTrial& t) { return std::isfinite(t.error_m) && t.error_m > 0.0 && t.rtol > 0.0; }

std::string number(double x) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3g", x);
  return text;
}

std::string listed(const std::vector<ToleranceTrial>& trials) {
  std::string s;
  for (const ToleranceTrial& t : trials)
    s += (s.empty() ? "" : ", ") + number(t.error_m) + " m at rtol " + number(t.rtol);
  return s;
}

bool at_min_rtol(double rtol, const SearchLimits& limits) { return rtol <= limits.min_rtol * (1.0 + 1e-9); }

// The last `limits.floor_trials` measured trials, when they span the stated
// tolerance factor and their fitted slope is below the stated one.
std::optional<std::string> floor_evidence(const std::vector<ToleranceTrial>& trials, const SearchLimits& limits) {
  std::vector<ToleranceTrial> finite;
  for (const ToleranceTrial& t : trials)
    if (measured(t)) finite.push_back(t);
  if (static_cast<int>(finite.size()) < limits.floor_trials) return std::nullopt;
  const std::vector<ToleranceTrial> tail(finite.end() - limits.floor_trials, finite.end());
  const auto [loosest, tightest] = std::minmax_element(
      tail.begin(), tail.end(), [](const ToleranceTrial& a, const ToleranceTrial& b) { return a.rtol > b.rtol; });
  const PowerLaw fit = fit_power_law(tail);
  if (loosest->rtol < limits.floor_span * tightest->rtol || !(fit.slope < limits.floor_slope)) return std::nullopt;
  return "the estimate stopped falling with the tolerance (" + listed(tail) + "; fitted slope " + number(fit.slope) +
         "): a floor above the target";
}

}  // namespace

PowerLaw fit_power_law(const std::vector<ToleranceTrial>& trials) {
  double sx = 0.0, sy = 0.0;
  PowerLaw fit;
  for (const ToleranceTrial& t : trials)
    if (measured(t)) {
      sx += std::log(t.rtol);
      sy += std::log(t.error_m);
      ++fit.points;
    }
  if (fit.points == 0) return {kNoFit, kNoFit, 0};
  const double mx = sx / fit.points, my = sy / fit.points;
  double sxx = 0.0, sxy = 0.0;
  for (const ToleranceTrial& t : trials)
    if (measured(t)) {
      sxx += (std::log(t.rtol) - mx) * (std::log(t.rtol) - mx);
      sxy += (std::log(t.rtol) - mx) * (std::log(t.error_m) - my);
    }
  fit.slope = sxx > 1e-12 ? sxy / sxx : kNoFit;  // two distinct tolerances at least
  fit.log_c = std::isfinite(fit.slope) ? my - fit.slope * mx : kNoFit;
  return fit;
}

const char* to_string(SearchVerdict v) {
  switch (v) {
    case SearchVerdict::reached: return "reached";
    case SearchVerdict::next_trial: return "next_trial";
    case SearchVerdict::floor: return "floor";
    case SearchVerdict::tolerance_floor: return "tolerance_floor";
    case SearchVerdict::budget: return "budget";
  }
  return "?";
}

double last_trial_bound(const std::vector<ToleranceTrial>& trials, const SearchLimits& limits) {
  const ToleranceTrial& last = trials.back();
  if (!last.ran) return kNoFit;
  for (size_t i = trials.size() - 1; i-- > 0;)
    if (trials[i].ran)
      return trials[i].rtol >= limits.companion_ratio * last.rtol * (1.0 - 1e-9) ? trials[i].error_m : kNoFit;
  return kNoFit;
}

SearchStep next_tolerance(const std::vector<ToleranceTrial>& trials, double target_m, const SearchLimits& limits) {
  const ToleranceTrial& last = trials.back();
  const double bound = last_trial_bound(trials, limits);
  if (bound <= target_m) return {SearchVerdict::reached, 0.0, bound, kNoFit, ""};
  const std::string state =
      last.ran
          ? (std::isfinite(bound) ? "the last trial, rtol " + number(last.rtol) + ", within " + number(bound) + " m"
                                  : "the last trial, rtol " + number(last.rtol) + ", not yet measured")
          : "the last trial, rtol " + number(last.rtol) + ", failed";
  if (static_cast<int>(trials.size()) >= limits.max_trials)
    return {SearchVerdict::budget, 0.0, bound, kNoFit,
            "the trial budget of " + std::to_string(limits.max_trials) + " trials is spent (" + state + ")"};
  if (at_min_rtol(last.rtol, limits))
    return {SearchVerdict::tolerance_floor, 0.0, bound, kNoFit,
            "the tolerance floor rtol " + number(limits.min_rtol) + " is reached (" + state + ")"};
  if (!last.ran)  // a tighter tolerance takes smaller steps
    return {SearchVerdict::next_trial, std::max(last.rtol / 10.0, limits.min_rtol), bound, kNoFit,
            "the last trial failed: ten times tighter"};
  if (auto floor = floor_evidence(trials, limits)) return {SearchVerdict::floor, 0.0, bound, kNoFit, *floor};

  SearchStep step{SearchVerdict::next_trial, std::max(last.rtol / limits.companion_ratio, limits.min_rtol), bound,
                  kNoFit, "a trial " + number(limits.companion_ratio) + " times tighter measures the last one's error"};
  const PowerLaw fit = fit_power_law(trials);
  if (fit.points == 0) return step;
  step.slope = std::isfinite(fit.slope) ? fit.slope : limits.assumed_slope;
  std::string how = std::isfinite(fit.slope) ? "slope fitted over " + std::to_string(fit.points) + " trials"
                                             : "slope assumed (one trial measured)";
  if (step.slope < limits.min_slope) {
    how += ", " + number(step.slope) + " raised to " + number(limits.min_slope);
    step.slope = limits.min_slope;
  }
  // Anchored at the last measured trial: e(r) = e_a · (r / r_a)^slope = safety · target.
  const ToleranceTrial& anchor = *std::find_if(trials.rbegin(), trials.rend(), measured);
  const double predicted = anchor.rtol * std::pow(limits.safety * target_m / anchor.error_m, 1.0 / step.slope);
  if (predicted >= last.rtol) {
    step.reason = "the last trial is predicted to meet the target (" + how + "): " + step.reason;
    return step;
  }
  if (std::isfinite(fit.slope) && predicted < limits.min_rtol)
    return {SearchVerdict::tolerance_floor, 0.0, bound, step.slope,
            "the measured relation (" + how + ") puts the target at rtol " + number(predicted) +
                ", below the tolerance floor rtol " + number(limits.min_rtol) + " (" + state + ")"};
  const double tighten = std::isfinite(fit.slope) ? limits.max_tighten : limits.max_tighten_assumed;
  step.next_rtol = std::clamp(predicted, last.rtol / tighten, last.rtol / limits.companion_ratio);
  step.next_rtol = std::max(step.next_rtol, limits.min_rtol);
  step.reason = "rtol " + number(predicted) + " predicted for " + number(limits.safety) + " × the target (" + how + ")";
  return step;
}

}  // namespace wl
