#include "models/fem/terms/lumped_mass.h"

namespace wl {

void LumpedMassTerm::add(const std::array<int, 9>& stencil, double triangle_mass_kg) {
  stencils_.push_back(stencil);
  mass_.push_back(triangle_mass_kg);
}

void LumpedMassTerm::evaluate(int e, const double*, const double*, const ElementOutput& out) const {
  if (out.mass) MatMap(out.mass).diagonal().setConstant(mass_[e] / 3.0);
}

}  // namespace wl
