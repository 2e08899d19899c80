#include "models/common/handle_spring.h"

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace wl {

void HandleSpringTerm::add(const std::array<int, 3>& stencil, const Vec3& anchor, double k) {
  if (!(k >= 0.0) || !std::isfinite(k)) {
    std::ostringstream msg;
    msg << "HandleSpringTerm::add: stiffness k = " << k << " N/m; expected a finite value >= 0";
    throw std::invalid_argument(msg.str());
  }
  if (!anchor.allFinite()) {
    std::ostringstream msg;
    msg << "HandleSpringTerm::add: anchor = (" << anchor.transpose() << ") m; expected finite components";
    throw std::invalid_argument(msg.str());
  }
  stencils_.push_back(stencil);
  anchor_.push_back(anchor);
  k_.push_back(k);
}

// V = ½ k ‖x − a‖²
double HandleSpringTerm::energy(int e, const double* q) const {
  return 0.5 * k_[e] * (Eigen::Map<const Vec3>(q) - anchor_[e]).squaredNorm();
}

// F = −k (x − a),  ∂F/∂x = −k I
void HandleSpringTerm::evaluate(int e, const double* q, const double*, const ElementOutput& out) const {
  VecMap(out.force) = -k_[e] * (Eigen::Map<const Vec3>(q) - anchor_[e]);
  if (out.dfdq) MatMap(out.dfdq) = -k_[e] * Mat3::Identity();
}

}  // namespace wl
