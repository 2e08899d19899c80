#include "models/mixed/interface_mass.h"

namespace wl {

void InterfaceMassTerm::add(const std::array<int, 3>& stencil, double mass_kg) {
  stencils_.push_back(stencil);
  mass_.push_back(mass_kg);
}

void InterfaceMassTerm::evaluate(int e, const double*, const double*, const ElementOutput& out) const {
  if (out.mass) MatMap(out.mass).diagonal().setConstant(mass_[e]);
}

}  // namespace wl
