#include "models/yarn/terms/shear_cirio.h"

#include <numbers>
#include <stdexcept>
#include <string>

#include "models/yarn/terms/crossing_angle.h"

namespace wl {

void CirioShearTerm::add(const std::array<int, 9>& stencil, double kx_L) {
  if (!(kx_L >= 0.0))
    throw std::invalid_argument("CirioShearTerm: k_x L = " + std::to_string(kx_L) + ", expected >= 0");
  stencils_.push_back(stencil);
  kx_L_.push_back(kx_L);
}

// V = ½ k_x L (φ − π/2)², docs/models.md §3.4.2, Cirio et al. 2016 eq. (42).
double CirioShearTerm::energy(int e, const double* q) const {
  const CrossingAngle a(q);
  const double s = a.phi - std::numbers::pi / 2;
  return 0.5 * kx_L_[e] * s * s;
}

// F = −V′∇φ, ∂F/∂x = −(V″∇φ∇φᵀ + V′H) with V′ = k_x L (φ − π/2), V″ = k_x L;
// equal to Cirio et al. 2016 eqs. (43)–(51). A degenerate crossing (φ → 0, π or a zero-length
// segment) gets zero force: the direction of ∇φ is undefined there.
void CirioShearTerm::evaluate(int e, const double* q, const double*, const ElementOutput& out) const {
  const CrossingAngle a(q);
  const double k = kx_L_[e];
  a.write(k * (a.phi - std::numbers::pi / 2), k, out);
}

}  // namespace wl
