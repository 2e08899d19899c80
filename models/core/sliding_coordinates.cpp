#include "models/core/sliding_coordinates.h"

#include <algorithm>

namespace wl {

double max_node_speed(const Model& model, const Vec& v) {
  if (const SlidingCoordinates* sliding = sliding_coordinates(model)) return sliding->max_node_speed(v);
  double m = 0.0;
  for (Eigen::Index i = 0; i + 2 < v.size(); i += 3) m = std::max(m, v.segment<3>(i).norm());
  return m;
}

}  // namespace wl
