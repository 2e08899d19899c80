#include "models/common/handle_spring.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace wl {

// a(t) − a₀ = w·(clamp(t, t_start, t_stop) − t_start)  (docs/models.md §3.10)
Vec3 HandleMotion::displacement(double t) const {
  if (t <= start_s) return Vec3::Zero();
  return velocity * (std::min(t, stop_s) - start_s);
}

void HandleSpringTerm::add(const std::array<int, 3>& stencil, const Vec3& anchor, double k,
                           const HandleMotion& motion) {
  std::ostringstream msg;
  msg << "HandleSpringTerm::add: ";
  if (!(k >= 0.0) || !std::isfinite(k)) msg << "stiffness k = " << k << " N/m; expected a finite value >= 0";
  else if (!anchor.allFinite()) msg << "anchor = (" << anchor.transpose() << ") m; expected finite components";
  else if (!motion.velocity.allFinite())
    msg << "velocity = (" << motion.velocity.transpose() << ") m/s; expected finite components";
  else if (!std::isfinite(motion.start_s) || !(motion.stop_s > motion.start_s))
    msg << "motion from " << motion.start_s << " s to " << motion.stop_s
        << " s; expected a finite start before the stop";
  else {
    stencils_.push_back(stencil);
    anchor_.push_back(anchor);
    k_.push_back(k);
    motion_.push_back(motion);
    return;
  }
  throw std::invalid_argument(msg.str());
}

void HandleSpringTerm::add(const std::array<int, 3>& stencil, const Vec3& anchor, const Handle& handle) {
  const auto& w = handle.velocity_m_per_s;
  add(stencil, anchor, handle.stiffness_N_per_m, HandleMotion{Vec3(w[0], w[1], w[2]), handle.start_s, handle.stop_s});
}

// V = ½ k ‖x − a(t)‖²
double HandleSpringTerm::energy(int e, const double* q) const {
  return 0.5 * k_[e] * (Eigen::Map<const Vec3>(q) - target(e, t_)).squaredNorm();
}

// F = −k (x − a(t)),  ∂F/∂x = −k I
void HandleSpringTerm::evaluate(int e, const double* q, const double*, const ElementOutput& out) const {
  VecMap(out.force) = -k_[e] * (Eigen::Map<const Vec3>(q) - target(e, t_));
  if (out.dfdq) MatMap(out.dfdq) = -k_[e] * Mat3::Identity();
}

}  // namespace wl
