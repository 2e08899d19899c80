#include "driver/trajectory_error.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace wl {

ErrorNorms trajectory_error(const Trajectory& run, const Trajectory& reference) {
  if (run.positions.rows() != reference.positions.rows())
    throw std::invalid_argument("trajectory_error: " + std::to_string(run.nodes()) + " nodes against " +
                                std::to_string(reference.nodes()) + " in the reference");
  if (run.times.size() != reference.times.size() || run.positions.cols() != reference.positions.cols())
    throw std::invalid_argument("trajectory_error: " + std::to_string(run.times.size()) + " output times against " +
                                std::to_string(reference.times.size()) + " in the reference");
  for (size_t k = 0; k < run.times.size(); ++k)
    if (std::abs(run.times[k] - reference.times[k]) > 1e-9 * std::max(1.0, std::abs(reference.times[k])))
      throw std::invalid_argument("trajectory_error: output time " + std::to_string(run.times[k]) + " against " +
                                  std::to_string(reference.times[k]) + " in the reference");
  ErrorNorms e;
  const int nodes = run.nodes();
  const Eigen::Index cols = run.positions.cols();
  if (nodes == 0 || cols == 0) return e;
  double sum = 0.0;
  for (Eigen::Index k = 0; k < cols; ++k)
    for (int n = 0; n < nodes; ++n) {
      const double d2 =
          (run.positions.col(k).segment<3>(3 * n) - reference.positions.col(k).segment<3>(3 * n)).squaredNorm();
      sum += d2;
      e.max = std::max(e.max, std::sqrt(d2));
    }
  e.rms = std::sqrt(sum / (double(nodes) * double(cols)));
  return e;
}

}  // namespace wl
