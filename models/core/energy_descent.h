// Static equilibrium by energy descent (docs/models.md §11.3): Newton steps
// A dq = f_f with A = −K_ff + μ·max diag(−K_ff) on the free DoFs, the
// Levenberg–Marquardt shift μ raised until the potential energy descends (a
// state the model calls invalid counts as infinite energy). Unlike the
// residual line search of calibration/equilibrium.h it walks through
// indefinite stiffness (a free knit edge) to a minimum.
#pragma once
#include <functional>
#include <vector>

#include "models/core/model.h"

namespace wl {

struct DescentResult {
  double residual_N = 0.0;  // ‖f_f‖∞ at the returned state
  double energy_J = 0.0;
  int steps = 0;  // accepted steps
};

// Descends from q (in place) until ‖f_f‖∞ ≤ tol or no shift lowers the
// energy or max_steps or `stop` (asked before each step) returns true; `held`
// DoFs keep their values in q, as do the model's fixed DoFs. Velocities are zero.
DescentResult descend_energy(Model& model, Vec& q, const std::vector<int>& held, double tol, int max_steps = 400,
                             const std::function<bool()>& stop = {});

}  // namespace wl
