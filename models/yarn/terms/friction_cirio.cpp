#include "models/yarn/terms/friction_cirio.h"

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace wl {

CirioFrictionTerm::CirioFrictionTerm(const std::vector<double>* normal_force, double mu, double kf, double df,
                                     double p)
    : normal_force_(normal_force), mu_(mu), kf_(kf), df_(df) {
  std::ostringstream bad;
  if (!(mu >= 0.0)) bad << "mu = " << mu << " (expected >= 0)";
  else if (!(kf > 0.0)) bad << "kf = " << kf << " (expected > 0)";
  else if (!(df >= 0.0)) bad << "df = " << df << " (expected >= 0)";
  else if (!(p > 0.0)) bad << "p = " << p << " (expected > 0)";
  if (!bad.str().empty()) throw std::invalid_argument("CirioFrictionTerm: " + bad.str());
}

void CirioFrictionTerm::add(int dof, int node, double anchor0) {
  if (normal_force_ && (node < 0 || node >= static_cast<int>(normal_force_->size()))) {
    std::ostringstream msg;
    msg << "CirioFrictionTerm: node " << node << " outside the normal-force table of size "
        << normal_force_->size();
    throw std::invalid_argument(msg.str());
  }
  stencils_.push_back({dof});
  node_.push_back(node);
  mode_.push_back(0);
  anchor_.push_back(anchor0);
  Fn_.push_back(0.0);
}

void CirioFrictionTerm::prepare(const EvalContext&) {
  for (int e = 0; e < num_elements(); ++e) Fn_[e] = normal_force_ ? (*normal_force_)[node_[e]] : 0.0;
}

// Return mapping on the accepted state: slip when k_f|u − ū| > μF_n, then
// ū = u − sign(u − ū) μF_n / k_f so that k_f|u − ū| = μF_n.
void CirioFrictionTerm::accept_step(const EvalContext& ctx, double) {
  for (int e = 0; e < num_elements(); ++e) {
    const int dof = stencils_[e][0];
    if (!is_dof(dof) || !ctx.q) continue;
    const double u = (*ctx.q)[dof];
    const double limit = mu_ * (normal_force_ ? (*normal_force_)[node_[e]] : 0.0);
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
  if (mode_[e] == 0) {  // stick: F = −k_f(u − ū) − d_f u̇
    out.force[0] = -kf_ * (q[0] - anchor_[e]) - df_ * v[0];
    if (out.dfdq) out.dfdq[0] = -kf_;
  } else {  // slip: F = −sign(u − ū) μF_n − d_f u̇, direction held for the step
    out.force[0] = -mode_[e] * mu_ * Fn_[e] - df_ * v[0];
    if (out.dfdq) out.dfdq[0] = 0.0;
  }
  if (out.dfdv) out.dfdv[0] = -df_;
}

std::vector<double> CirioFrictionTerm::sliding_state() const {
  std::vector<double> s(num_elements());
  for (int e = 0; e < num_elements(); ++e) s[e] = mode_[e] != 0 ? 1.0 : 0.0;
  return s;
}

}  // namespace wl
