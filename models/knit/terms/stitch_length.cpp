#include "models/knit/terms/stitch_length.h"

#include <cmath>
#include <stdexcept>

namespace wl {

void StitchLengthTerm::add(const std::array<int, 2>& stencil, double kl, double rest) {
  if (!(std::isfinite(kl) && kl >= 0.0 && std::isfinite(rest) && rest > 0.0))
    throw std::invalid_argument("StitchLengthTerm::add: expected k_l ≥ 0 and a rest length > 0");
  stencils_.push_back(stencil);
  kl_.push_back(kl);
  rest_.push_back(rest);
}

double StitchLengthTerm::energy(int e, const double* q) const {
  const double s = (q[1] - q[0]) / rest_[e] - 1.0;
  return 0.5 * kl_[e] * rest_[e] * s * s;  // V = ½ k_l L (Δu/L − 1)²
}

void StitchLengthTerm::evaluate(int e, const double* q, const double*, const ElementOutput& out) const {
  const double L = rest_[e], s = (q[1] - q[0]) / L - 1.0;
  out.force[0] = kl_[e] * s;  // F_u0 = −F_u1 = k_l (Δu/L − 1)
  out.force[1] = -kl_[e] * s;
  if (!out.dfdq) return;
  const double k = kl_[e] / L;  // ∂F_u1/∂u1 = −k_l/L
  out.dfdq[0] = -k;
  out.dfdq[1] = k;
  out.dfdq[2] = k;
  out.dfdq[3] = -k;
}

}  // namespace wl
