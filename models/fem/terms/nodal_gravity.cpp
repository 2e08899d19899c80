#include "models/fem/terms/nodal_gravity.h"

namespace wl {

void NodalGravityTerm::add(const std::array<int, 3>& stencil, double mass_kg) {
  stencils_.push_back(stencil);
  mass_.push_back(mass_kg);
}

double NodalGravityTerm::energy(int e, const double* q) const { return -mass_[e] * g_.dot(Eigen::Map<const Vec3>(q)); }

void NodalGravityTerm::evaluate(int e, const double*, const double*, const ElementOutput& out) const {
  VecMap(out.force) = mass_[e] * g_;
}

}  // namespace wl
