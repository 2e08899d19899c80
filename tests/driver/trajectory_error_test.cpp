// The error metric of a run against a reference (driver/trajectory_error.h).
#include <gtest/gtest.h>

#include <cmath>

#include "driver/trajectory_error.h"
#include "tests/driver/driver_test_data.h"

namespace wl {
namespace {

using test::random_trajectory;

TEST(TrajectoryError, RunAgainstItselfIsZero) {
  const Trajectory t = random_trajectory(25, 4, 1);
  const ErrorNorms e = trajectory_error(t, t);
  EXPECT_EQ(e.rms, 0.0);
  EXPECT_EQ(e.max, 0.0);
}

TEST(TrajectoryError, UniformOffsetGivesThatOffset) {
  const Trajectory ref = random_trajectory(25, 4, 2);
  Trajectory run = ref;
  const Eigen::Vector3d d(3e-4, -4e-4, 0.0);  // ‖d‖ = 5e-4 m
  for (Eigen::Index k = 0; k < run.positions.cols(); ++k)
    for (int n = 0; n < run.nodes(); ++n) run.positions.col(k).segment<3>(3 * n) += d;
  const ErrorNorms e = trajectory_error(run, ref);
  EXPECT_NEAR(e.rms, 5e-4, 1e-15);
  EXPECT_NEAR(e.max, 5e-4, 1e-15);
}

TEST(TrajectoryError, SingleNodeOffsetIsAveragedOverNodesAndTimes) {
  const int nodes = 16, times = 4;
  const Trajectory ref = random_trajectory(nodes, times, 3);
  Trajectory run = ref;
  run.positions(3 * 5 + 2, 1) += 2e-3;  // node 5, z, second output time
  const ErrorNorms e = trajectory_error(run, ref);
  EXPECT_NEAR(e.max, 2e-3, 1e-15);
  EXPECT_NEAR(e.rms, 2e-3 / std::sqrt(double(nodes * times)), 1e-15);
}

TEST(TrajectoryError, MismatchedShapesAreRejected) {
  const Trajectory a = random_trajectory(9, 3, 4);
  EXPECT_THROW(trajectory_error(a, random_trajectory(16, 3, 4)), std::invalid_argument);
  EXPECT_THROW(trajectory_error(a, random_trajectory(9, 2, 4)), std::invalid_argument);
  Trajectory shifted = a;
  shifted.times[1] += 1e-4;
  EXPECT_THROW(trajectory_error(a, shifted), std::invalid_argument);
}

}  // namespace
}  // namespace wl
