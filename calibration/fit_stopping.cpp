#include "calibration/fit_stopping.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace wl {

double cost_noise(double cost, double residual_noise) {
  return std::sqrt(2.0 * std::max(cost, 0.0)) * residual_noise + 0.5 * residual_noise * residual_noise;
}

std::optional<std::string> flat_cost_reason(const std::vector<double>& history, const FlatCostRule& rule) {
  const int i = static_cast<int>(history.size()) - 1;
  if (rule.window < 1 || i < rule.window) return std::nullopt;
  const double now = history[i], before = history[i - rule.window];
  const double decrease = before - now, relative = rule.fraction * now, noise = cost_noise(now, rule.residual_noise);
  if (!(decrease <= std::max(relative, noise))) return std::nullopt;  // a NaN cost is not flat
  char b[240];
  std::snprintf(b, sizeof b,
                "the cost stopped improving: it fell by %.3g over the last %d iterations, below %s (%.3g) at cost %.3g",
                decrease, rule.window, noise > relative ? "its noise floor" : "the set fraction of itself",
                std::max(relative, noise), now);
  return std::string(b);
}

double residual_noise(const Eigen::VectorXd& r0, const Eigen::MatrixXd& j0, const Eigen::VectorXd& r1,
                      const Eigen::MatrixXd& j1, const Eigen::VectorXd& step) {
  return (r1 - r0 - 0.5 * (j0 + j1) * step).norm();
}

}  // namespace wl
