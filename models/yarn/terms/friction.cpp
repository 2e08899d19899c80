#include "models/yarn/terms/friction.h"

#include "models/yarn/terms/frozen_normal_force.h"

#include <sstream>
#include <stdexcept>

namespace wl {

FrictionTerm::FrictionTerm(const char* who, double mu, double kf, double df, double p, bool kf_positive)
    : who_(who), mu_(mu), kf_(kf), df_(df), p_(p) {
  std::ostringstream bad;
  if (!(mu >= 0.0)) bad << "mu = " << mu << " (expected >= 0)";
  else if (kf_positive ? !(kf > 0.0) : !(kf >= 0.0))
    bad << "kf = " << kf << (kf_positive ? " (expected > 0)" : " (expected >= 0)");
  else if (!(df >= 0.0)) bad << "df = " << df << " (expected >= 0)";
  else if (!(p > 0.0)) bad << "p = " << p << " (expected > 0)";
  if (!bad.str().empty()) throw std::invalid_argument(std::string(who) + ": " + bad.str());
}

void FrictionTerm::add(int dof, int node, double anchor0) {
  stencils_.push_back({dof});
  node_.push_back(node);
  anchor_.push_back(anchor0);
  Fu_.push_back(0.0);
  Fn_.push_back(0.0);
}

void FrictionTerm::prepare(const EvalContext& ctx) {
  for (int e = 0; e < num_elements(); ++e) {
    const int dof = stencils_[e][0];
    Fu_[e] = ctx.force_so_far && is_dof(dof) ? (*ctx.force_so_far)[dof] : 0.0;
  }
  freeze_normal_force(ctx, node_, Fn_, who_);
}

}  // namespace wl
