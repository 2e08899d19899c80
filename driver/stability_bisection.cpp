#include "driver/stability_bisection.h"

#include <cmath>
#include <stdexcept>

#include "output/csv_table.h"

namespace wl {

StabilityLimit find_stability_limit(const std::function<StabilityProbe(double dt)>& probe, double dt_min, double dt_max,
                                    int bisections) {
  if (!(dt_min > 0) || !(dt_max > dt_min))
    throw std::invalid_argument("find_stability_limit: need 0 < dt_min < dt_max, got " + csv_number(dt_min) + ", " +
                                csv_number(dt_max));
  StabilityLimit lim;
  auto run = [&](double dt) {
    StabilityProbe p = probe(dt);
    lim.probes.emplace_back(dt, p);
    return p;
  };
  StabilityProbe top = run(dt_max);
  if (top.bounded) {
    lim.largest_stable_dt = dt_max;
    return lim;
  }
  lim.smallest_unstable_dt = dt_max;
  lim.failure = top;
  double lo = std::log(dt_min), hi = std::log(dt_max);
  bool found_bounded = false;
  for (int i = 0; i < bisections; ++i) {
    const double mid = 0.5 * (lo + hi), dt = std::exp(mid);
    StabilityProbe p = run(dt);
    if (p.bounded) {
      lo = mid;
      found_bounded = true;
      lim.largest_stable_dt = dt;
    } else {
      hi = mid;
      lim.smallest_unstable_dt = dt;
      lim.failure = p;
    }
  }
  if (!found_bounded) {
    StabilityProbe p = run(dt_min);
    if (p.bounded) {
      lim.largest_stable_dt = dt_min;
    } else {
      lim.smallest_unstable_dt = dt_min;
      lim.failure = p;
    }
  }
  return lim;
}

}  // namespace wl
