// When a trajectory fit stops improving (docs/calibration.md §7.1): Ceres's own
// tolerances are relative to round-off (a cost change of 1e-12 of the cost), far
// below what a simulated cost can resolve, so a fit that has reached the noise of
// its simulations would run on to its iteration cap. The flat-cost rule stops it
// once the cost over the last `window` iterations fell by no more than the larger
// of a fraction of itself and its noise floor:
//   C_{i−w} − C_i ≤ max(ρ·C_i, N(C_i)),  N(C) = √(2C)·σ + ½σ²,
// σ the measured noise of the residual vector (‖δr‖). The cost ½‖r + δr‖²
// differs from ½‖r‖² by rᵀδr + ½‖δr‖², at most N(C) in magnitude.
#pragma once
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace wl {

struct FlatCostRule {
  int window = 5;               // iterations the decrease is measured over
  double fraction = 1e-4;       // ρ: a decrease below this fraction of the cost is no progress
  double residual_noise = 0.0;  // σ [m]; 0 when unmeasured (the fraction alone then decides)
};

// The largest change of the cost ½‖r‖² that residual noise σ can cause at cost C.
double cost_noise(double cost, double residual_noise);

// With `history` the cost at iterations 0, 1, …, i (non-increasing, as Levenberg–Marquardt
// accepts only decreases): why the fit should stop at iteration i, or nothing while it still
// improves (or has run fewer than rule.window iterations).
std::optional<std::string> flat_cost_reason(const std::vector<double>& history, const FlatCostRule& rule);

// The noise of a simulated residual vector from two simulations a small step h·d apart (in
// the fitted coordinates), each with its exact Jacobian: what the trapezoidal prediction
//   r₁ − r₀ ≈ ½ h (J₀ + J₁) d,
// exact to O(h³), does not explain, ‖r₁ − r₀ − ½ h (J₀ + J₁) d‖.
double residual_noise(const Eigen::VectorXd& r0, const Eigen::MatrixXd& j0, const Eigen::VectorXd& r1,
                      const Eigen::MatrixXd& j1, const Eigen::VectorXd& step);

}  // namespace wl
