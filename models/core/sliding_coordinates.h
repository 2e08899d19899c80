// A capability of the yarn-level models (yarn and knit, docs/design.md §3.1):
// their generalized coordinates hold, beside each node's position, sliding
// coordinates along the yarns (docs/models.md §2.1, §11.1), and the yarn
// model's friction keeps anchors on them whose parameter derivative forward
// sensitivities carry (docs/models.md §9.2). A model offers it by deriving
// from SlidingCoordinates besides Model; callers ask with
// sliding_coordinates(model), null for every other model, as an integrator's
// callers read IntegratorCapabilities.
#pragma once
#include <string>
#include <vector>

#include "models/core/model.h"

namespace wl {

class SlidingCoordinates {
 public:
  virtual ~SlidingCoordinates() = default;
  // Largest node speed ‖ẋ‖ over the nodes' positions in v [m/s] (the sliding
  // coordinates' rates left out).
  virtual double max_node_speed(const Vec& v) const = 0;
  // Carries the derivative of the model's history (friction anchors) over an
  // accepted step of size h ending at (q, v), called by the integrators before
  // Model::accept_step with the sensitivities there, S_q = ∂q/∂p and S_v = ∂v/∂p
  // (one column per key; docs/models.md §9.2). The default: the history does
  // not depend on p.
  virtual void accept_step_sensitivities(const std::vector<std::string>& /*keys*/, const Vec& /*q*/, const Vec& /*v*/,
                                         const Eigen::MatrixXd& /*dq_dp*/, const Eigen::MatrixXd& /*dv_dp*/,
                                         double /*h*/) {}
};

// The model's SlidingCoordinates capability; null for a model without sliding coordinates.
inline SlidingCoordinates* sliding_coordinates(Model& model) { return dynamic_cast<SlidingCoordinates*>(&model); }
inline const SlidingCoordinates* sliding_coordinates(const Model& model) {
  return dynamic_cast<const SlidingCoordinates*>(&model);
}

}  // namespace wl
