#include "models/fem/terms/lumped_mass.h"

namespace wl {

void LumpedMassTerm::add(const std::array<int, 9>& stencil, const std::array<double, 3>& vertex_mass_kg) {
  stencils_.push_back(stencil);
  mass_.push_back(vertex_mass_kg);
}

void LumpedMassTerm::evaluate(int e, const double*, const double*, const ElementOutput& out) const {
  if (!out.mass) return;
  auto m = MatMap(out.mass);
  for (int k = 0; k < 3; ++k) m.diagonal().segment<3>(3 * k).setConstant(mass_[e][k]);
}

double LumpedMassTerm::kinetic_energy(int e, const double*, const double* v) const {
  double t = 0.0;
  for (int k = 0; k < 3; ++k)
    t += mass_[e][k] * (v[3 * k] * v[3 * k] + v[3 * k + 1] * v[3 * k + 1] + v[3 * k + 2] * v[3 * k + 2]);
  return 0.5 * t;
}

}  // namespace wl
