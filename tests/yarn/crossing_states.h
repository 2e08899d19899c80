// Local states (x0, x1, x3) of a crossing with a chosen angle φ between the
// warp segment x0→x1 and the weft segment x0→x3, placed in a generic rotated
// frame, for the shear-term tests.
#pragma once
#include <cmath>
#include <vector>

#include <Eigen/Geometry>

#include "tests/support/fd_check.h"

namespace wl::test {

inline LocalState crossing_state(double phi, double l1, double l3, double tilt = 0.3) {
  const Eigen::Matrix3d R = (Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()) *
                             Eigen::AngleAxisd(tilt, Eigen::Vector3d::UnitX()))
                                .toRotationMatrix();
  const Eigen::Vector3d x0(0.1, -0.2, 0.3);
  const Eigen::Vector3d x1 = x0 + l1 * R * Eigen::Vector3d(1, 0, 0);
  const Eigen::Vector3d x3 = x0 + l3 * R * Eigen::Vector3d(std::cos(phi), std::sin(phi), 0);
  LocalState s;
  s.q = {x0[0], x0[1], x0[2], x1[0], x1[1], x1[2], x3[0], x3[1], x3[2]};
  s.v = {0.1, -0.2, 0.05, 0.3, 0.0, -0.1, 0.2, 0.1, 0.4};
  return s;
}

// The same crossing with every node nudged off the plane and along it.
inline LocalState nudged(LocalState s, double amount) {
  const double d[9] = {0.3, -0.7, 0.2, -0.4, 0.5, 0.9, 0.6, -0.1, -0.8};
  for (int i = 0; i < 9; ++i) s.q[i] += amount * d[i];
  return s;
}

inline double crossing_angle_of(const LocalState& s) {
  Eigen::Map<const Eigen::Vector3d> x0(s.q.data()), x1(s.q.data() + 3), x3(s.q.data() + 6);
  return std::acos((x1 - x0).normalized().dot((x3 - x0).normalized()));
}

}  // namespace wl::test
