// The knit terms (docs/models.md §11.4–§11.5) and the periodic image wrapper
// (§11.3): analytic forces and Jacobians against finite differences, the roll
// angle's sign and rest, the wrapper's shift.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>

#include "models/knit/image_term.h"
#include "models/knit/terms/stitch_length.h"
#include "models/knit/terms/stitch_roll.h"
#include "models/yarn/terms/stretch.h"
#include "tests/support/fd_check.h"

namespace wl {
namespace {

std::array<int, 12> identity12() {
  std::array<int, 12> s{};
  for (int a = 0; a < 12; ++a) s[a] = a;
  return s;
}

// A stitch at millimetre scale: segment x0→x1 through the cloth, the head yarn
// leaving along +x (x3), the leg yarn along +y (x5).
std::vector<double> stitch_state(double lift) {
  return {0.0, 0.0, -0.5e-3, 0.0, 0.3e-3, 0.5e-3, 1.0e-3, 0.4e-3, 0.6e-3, 0.1e-3, 1.2e-3, 0.2e-3 + lift};
}

TEST(StitchRollTerm, ForcesAndJacobiansMatchFiniteDifferences) {
  StitchRollTerm t;
  t.add(identity12(), 0.02, 1e-3, 0.3);
  const std::vector<double> zero(12, 0.0);
  std::vector<test::LocalState> states = {{stitch_state(0.0), zero}, {stitch_state(-0.7e-3), zero}};
  // ψ on both sides of 0 and far from the rest angle: the signed angle's branches.
  std::vector<double> flipped = stitch_state(0.0);
  {  // x5 turned about the segment to −ψ
    const Eigen::Vector3d x0(flipped[0], flipped[1], flipped[2]), x1(flipped[3], flipped[4], flipped[5]);
    const Eigen::Vector3d x5(flipped[9], flipped[10], flipped[11]);
    const Eigen::Vector3d turned =
        x0 + Eigen::AngleAxisd(-2.0 * StitchRollTerm::angle(flipped.data()), (x1 - x0).normalized()) * (x5 - x0);
    for (int k = 0; k < 3; ++k) flipped[9 + k] = turned[k];
  }
  states.push_back({flipped, zero});
  test::FdOptions opt;
  opt.floor = 1e-14;
  const auto r = test::check_element(t, 0, states, opt);
  EXPECT_TRUE(r.ok) << r.detail;
  EXPECT_LT(StitchRollTerm::angle(flipped.data()) * StitchRollTerm::angle(stitch_state(0.0).data()), 0.0)
      << "the test states should put ψ on both sides of 0";
}

TEST(StitchRollTerm, NoForceAtTheRestAngleAndRotationInvariant) {
  const std::vector<double> q = stitch_state(0.0);
  StitchRollTerm t;
  t.add(identity12(), 0.02, 1e-3, StitchRollTerm::angle(q.data()));
  std::vector<double> f(12, 1.0), v(12, 0.0);
  t.evaluate(0, q.data(), v.data(), ElementOutput{f.data()});
  for (double x : f) EXPECT_NEAR(x, 0.0, 1e-15);
  // The energy is periodic in the roll: a rest angle one turn away is the same rest.
  StitchRollTerm turn;
  turn.add(identity12(), 0.02, 1e-3, StitchRollTerm::angle(q.data()) + 2.0 * M_PI);
  EXPECT_NEAR(turn.energy(0, q.data()), 0.0, 1e-24);
  // A rigid rotation about z keeps ψ.
  std::vector<double> r = q;
  const double c = std::cos(0.7), s = std::sin(0.7);
  for (int i = 0; i < 4; ++i) {
    r[3 * i] = c * q[3 * i] - s * q[3 * i + 1];
    r[3 * i + 1] = s * q[3 * i] + c * q[3 * i + 1];
  }
  EXPECT_NEAR(StitchRollTerm::angle(r.data()), StitchRollTerm::angle(q.data()), 1e-12);
  // Turning the leg yarn's node about the segment changes ψ by the turn (x5 rotated about e).
  const Eigen::Vector3d x0(q[0], q[1], q[2]), x1(q[3], q[4], q[5]), x5(q[9], q[10], q[11]);
  const Eigen::Vector3d e = (x1 - x0).normalized();
  const Eigen::Vector3d turned = x0 + Eigen::AngleAxisd(0.2, e) * (x5 - x0);
  std::vector<double> p = q;
  for (int k = 0; k < 3; ++k) p[9 + k] = turned[k];
  EXPECT_NEAR(std::abs(StitchRollTerm::angle(p.data()) - StitchRollTerm::angle(q.data())), 0.2, 1e-12);
}

TEST(StitchLengthTerm, ForcesAndJacobiansMatchFiniteDifferences) {
  StitchLengthTerm t;
  t.add({0, 1}, 1.5, 0.8e-3);
  const std::vector<test::LocalState> states = {{{2.0e-3, 2.9e-3}, {0.0, 0.0}}, {{-1.0e-3, -0.4e-3}, {0.0, 0.0}}};
  test::FdOptions opt;
  opt.floor = 1e-14;
  const auto r = test::check_element(t, 0, states, opt);
  EXPECT_TRUE(r.ok) << r.detail;
  // V = ½ k_l L (Δu/L − 1)²: Δu = 0.9 mm against L = 0.8 mm.
  const double q[2] = {2.0e-3, 2.9e-3};
  EXPECT_NEAR(t.energy(0, q), 0.5 * 1.5 * 0.8e-3 * std::pow(0.9 / 0.8 - 1.0, 2), 1e-18);
}

TEST(ImageTerm, ShiftsTheStateAndKeepsTheDerivatives) {
  auto stretch = std::make_unique<StretchTerm>();
  stretch->add({0, 1, 2, 3, 4, 5, 6, 7}, 2.0);
  // The second node is an image one period (3 mm along x, 3.1 mm of yarn) away.
  const std::vector<double> shift{0, 0, 0, 3e-3, 0, 0, 0, 3.1e-3};
  ImageTerm image(std::move(stretch), shift);
  const std::vector<double> q{0.0, 0.0, 0.0, -2.0e-3, 0.1e-3, 0.0, 0.0, -2.0e-3};
  std::vector<double> shifted(8);
  for (int a = 0; a < 8; ++a) shifted[a] = q[a] + shift[a];
  EXPECT_DOUBLE_EQ(image.energy(0, q.data()), StretchTerm::local_energy(shifted.data(), 2.0));
  EXPECT_GT(image.energy(0, q.data()), 0.0);
  test::FdOptions opt;
  opt.floor = 1e-14;
  const auto r = test::check_element(image, 0, {{q, std::vector<double>(8, 0.0)}}, opt);
  EXPECT_TRUE(r.ok) << r.detail;
}

}  // namespace
}  // namespace wl
