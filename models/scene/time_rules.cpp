// The rules of a run's time settings (scene.h), in one place for the scene
// reader and the command line.
#include <cmath>

#include "models/scene/scene.h"
#include "models/scene/scene_limits.h"
#include "models/scene/toml_reader.h"

namespace wl {

std::optional<SettingViolation> time_settings_violation(const Scene& s,
                                                        const std::function<int(const std::string&)>& rank) {
  using scene_detail::format_number;
  const std::string T = "time.duration_s", H = "time.dt_s", O = "time.output_interval_s";
  auto eq = [](double x) { return " (= " + format_number(x) + ")"; };
  auto violation = [](const std::string& key, double value, std::string expected) {
    return SettingViolation{key, format_number(value), std::move(expected)};
  };
  auto finite_positive = [](double x) { return std::isfinite(x) && x > 0.0; };

  // Each value on its own.
  for (const auto& [key, value, unit] :
       {std::tuple{T, s.duration_s, " (s)"}, std::tuple{H, s.dt_s, " (s)"}, std::tuple{O, s.output_interval_s, " (s)"}})
    if (!finite_positive(value)) return violation(key, value, std::string("a finite number > 0") + unit);
  if (!(s.rtol >= kMinRtol && s.rtol < 1.0))  // scene_limits.h
    return violation("time.rtol", s.rtol,
                     "a number ≥ " + format_number(kMinRtol) + " and < 1 (smaller tolerances are below round-off)");
  if (!finite_positive(s.atol)) return violation("time.atol", s.atol, "a finite number > 0");

  // Between two values: blame the one stated with more authority.
  auto between = [&](const std::string& a, double va, const std::string& expected_a, const std::string& b, double vb,
                     const std::string& expected_b) {
    return rank(b) > rank(a) ? violation(b, vb, expected_b) : violation(a, va, expected_a);
  };
  if (s.dt_s > s.duration_s)
    return between(H, s.dt_s, "a number ≤ " + T + eq(s.duration_s), T, s.duration_s, "a number ≥ " + H + eq(s.dt_s));
  if (s.dt_s > s.output_interval_s)
    return between(O, s.output_interval_s, "a number ≥ " + H + eq(s.dt_s), H, s.dt_s,
                   "a number ≤ " + O + eq(s.output_interval_s));
  if (s.output_interval_s > s.duration_s)
    return between(O, s.output_interval_s, "a number ≤ " + T + eq(s.duration_s), T, s.duration_s,
                   "a number ≥ " + O + eq(s.output_interval_s));
  if (!s.adaptive && s.duration_s / s.dt_s > kMaxSteps)
    return between(H, s.dt_s,
                   "a step ≥ " + T + " / " + format_number(kMaxSteps) + eq(s.duration_s / kMaxSteps) + " (at most " +
                       format_number(kMaxSteps) + " steps)",
                   T, s.duration_s,
                   "a duration ≤ " + format_number(kMaxSteps) + " × " + H + eq(kMaxSteps * s.dt_s) + " (at most " +
                       format_number(kMaxSteps) + " steps)");
  if (s.duration_s / s.output_interval_s > kMaxFrames)
    return between(O, s.output_interval_s,
                   "an interval ≥ " + T + " / " + format_number(kMaxFrames) + eq(s.duration_s / kMaxFrames) +
                       " (at most " + format_number(kMaxFrames) + " frames)",
                   T, s.duration_s,
                   "a duration ≤ " + format_number(kMaxFrames) + " × " + O + eq(kMaxFrames * s.output_interval_s) +
                       " (at most " + format_number(kMaxFrames) + " frames)");
  if (s.settle_dt_s != 0.0) {  // the settling phase (docs/models.md §3.11.6)
    const std::string SD = "time.settle_dt_s", SA = "time.settle_after_s";
    if (s.adaptive || s.error_estimate || s.accuracy_m > 0.0)
      return violation(SD, s.settle_dt_s,
                       "no settling phase with adaptive steps, error_estimate or accuracy_m (fixed steps only)");
    if (s.settle_dt_s > s.output_interval_s)
      return between(SD, s.settle_dt_s, "a number ≤ " + O + eq(s.output_interval_s), O, s.output_interval_s,
                     "a number ≥ " + SD + eq(s.settle_dt_s));
    if (s.settle_after_s >= s.duration_s)
      return between(SA, s.settle_after_s, "a number < " + T + eq(s.duration_s), T, s.duration_s,
                     "a number > " + SA + eq(s.settle_after_s));
  }
  return std::nullopt;
}

}  // namespace wl
