#include "models/yarn/terms/friction_cirio.h"

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace wl {

// Return mapping on the accepted state: slip when k_f|u − ū| > μF_n, then
// ū = u − sign(u − ū) μF_n / k_f so that k_f|u − ū| = μF_n.
void CirioFrictionTerm::accept_step(const EvalContext& ctx, double) {
  mode_.resize(num_elements(), 0);
  for (int e = 0; e < num_elements(); ++e) {
    const int dof = stencils_[e][0];
    if (!is_dof(dof) || !ctx.q) continue;
    const double u = (*ctx.q)[dof];
    const double limit = mu_ * Fn_[e];
    const double delta = u - anchor_[e];
    if (kf_ * std::abs(delta) > limit) {
      mode_[e] = delta > 0.0 ? 1 : -1;
      anchor_[e] = u - mode_[e] * limit / kf_;
    } else {
      mode_[e] = 0;
    }
  }
}

void CirioFrictionTerm::evaluate(int e, const double* q, const double* v, const ElementOutput& out) const {
  if (slip_direction(e) == 0) {  // stick: F = −k_f(u − ū) − d_f u̇
    out.force[0] = -kf_ * (q[0] - anchor_[e]) - df_ * v[0];
    if (out.dfdq) out.dfdq[0] = -kf_;
  } else {  // slip: F = −sign(u − ū) μF_n − d_f u̇, direction held for the step
    out.force[0] = -slip_direction(e) * mu_ * Fn_[e] - df_ * v[0];
    if (out.dfdq) out.dfdq[0] = 0.0;
  }
  if (out.dfdv) out.dfdv[0] = -df_;
}

void CirioFrictionTerm::frozen_input_derivatives(int e, const double*, const double*, double* dfdFn, double*) const {
  dfdFn[0] += -slip_direction(e) * mu_;
}

// ∂F/∂μ = −sign(u − ū) F_n while slipping, 0 while sticking.
void CirioFrictionTerm::parameter_derivative(int e, int, const double*, const double*, double* dfdp) const {
  dfdp[0] += -slip_direction(e) * Fn_[e];
}

std::vector<double> CirioFrictionTerm::sliding_state() const {
  std::vector<double> s(num_elements());
  for (int e = 0; e < num_elements(); ++e) s[e] = slip_direction(e) != 0 ? 1.0 : 0.0;
  return s;
}

}  // namespace wl
