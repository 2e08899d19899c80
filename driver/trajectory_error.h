// The error of a recorded trajectory against a reference trajectory.
#pragma once
#include "driver/recorded_run.h"

namespace wl {

// Error of a run against a reference: over all nodes n and output times k,
//   rms = sqrt( mean_{n,k} ‖x_run(n,k) − x_ref(n,k)‖² ),  max = max_{n,k} ‖…‖  [m].
// Throws std::invalid_argument when the node counts or output times differ.
struct ErrorNorms {
  double rms = 0.0;
  double max = 0.0;
};
ErrorNorms trajectory_error(const Trajectory& run, const Trajectory& reference);

}  // namespace wl
