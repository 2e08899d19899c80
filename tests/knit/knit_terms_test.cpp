// The knit terms (docs/models.md §11.4–§11.5) and the periodic image wrapper
// (§11.3): analytic forces and Jacobians against finite differences, the roll
// angle's sign and rest, the roll through a degenerate triangle (§11.4.1; one
// be-newton run across it), the wrapper's shift.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>

#include "integrators/integrator.h"
#include "models/knit/image_term.h"
#include "models/knit/terms/stitch_compression.h"
#include "models/knit/terms/stitch_length.h"
#include "models/knit/terms/stitch_roll.h"
#include "models/knit/terms/yarn_compression.h"
#include "models/yarn/terms/segment_inertia.h"
#include "models/yarn/terms/stretch.h"
#include "tests/support/fd_check.h"
#include "tests/support/node_mass.h"

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
  t.add(identity12(), 0.02, 1e-3, 0.3, 0.5);
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
  // A nearly degenerate triangle a: x5 0.5 % of its distance off the segment's line.
  std::vector<double> thin = stitch_state(0.0);
  for (int k = 0; k < 3; ++k) thin[9 + k] = thin[3 + k] + 1.5 * (thin[3 + k] - thin[k]) + (k == 0 ? 5e-6 : 0.0);
  states.push_back({thin, zero});
  EXPECT_LT(StitchRollTerm::opening(thin.data()), 1e-4) << "the thin state should nearly degenerate";
  test::FdOptions opt;
  opt.floor = 1e-14;
  const auto r = test::check_element(t, 0, states, opt);
  EXPECT_TRUE(r.ok) << r.detail;
  EXPECT_LT(StitchRollTerm::angle(flipped.data()) * StitchRollTerm::angle(stitch_state(0.0).data()), 0.0)
      << "the test states should put ψ on both sides of 0";
}

// ∂f/∂k_t of the roll (a force proportional to k_t, docs/models.md §11.4) against differences in k_t.
TEST(StitchRollTerm, ParameterDerivativeMatchesFiniteDifferences) {
  auto make = [](double kt) {
    auto term = std::make_unique<StitchRollTerm>();
    term->add(identity12(), kt, 1e-3, 0.3, 0.5);
    term->tag_last("knit.roll_stiffness_N", kt);
    return std::unique_ptr<Term>(std::move(term));
  };
  const std::vector<double> zero(12, 0.0);
  test::FdOptions opt;
  opt.floor = 1e-14;
  const auto r = test::check_parameter_derivative(make, 0.02, 0, 0,
                                                  {{stitch_state(0.0), zero}, {stitch_state(-0.7e-3), zero}}, opt);
  EXPECT_TRUE(r.ok) << r.detail;
}

TEST(StitchRollTerm, NoForceAtTheRestAngleAndRotationInvariant) {
  const std::vector<double> q = stitch_state(0.0);
  StitchRollTerm t;
  t.add(identity12(), 0.02, 1e-3, StitchRollTerm::angle(q.data()), StitchRollTerm::opening(q.data()));
  std::vector<double> f(12, 1.0), v(12, 0.0);
  t.evaluate(0, q.data(), v.data(), ElementOutput{f.data()});
  for (double x : f) EXPECT_NEAR(x, 0.0, 1e-15);
  // The energy is periodic in the roll: a rest angle one turn away is the same rest.
  StitchRollTerm turn;
  turn.add(identity12(), 0.02, 1e-3, StitchRollTerm::angle(q.data()) + 2.0 * M_PI, StitchRollTerm::opening(q.data()));
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

// The leg yarn's node x5 turned by δ about the segment (the triangles keep their opening).
std::vector<double> rolled(std::vector<double> q, double delta) {
  const Eigen::Vector3d x0(q[0], q[1], q[2]), x1(q[3], q[4], q[5]), x5(q[9], q[10], q[11]);
  const Eigen::Vector3d turned = x0 + Eigen::AngleAxisd(delta, (x1 - x0).normalized()) * (x5 - x0);
  for (int k = 0; k < 3; ++k) q[9 + k] = turned[k];
  return q;
}

std::vector<double> roll_force(const StitchRollTerm& t, const std::vector<double>& q) {
  std::vector<double> f(12, 0.0), v(12, 0.0);
  t.evaluate(0, q.data(), v.data(), ElementOutput{f.data()});
  return f;
}

double norm(const std::vector<double>& f) {
  double s = 0.0;
  for (double x : f) s += x * x;
  return std::sqrt(s);
}

// Small rolls: the source's ½ k_t L (ψ − ψ̄)² (docs/models.md §11.4.1); a half
// turn: the energy's maximum 2 k_t L, its force continuous there (the quadratic
// in the wrapped angle jumped from −k_t L π ∇ψ to +k_t L π ∇ψ).
TEST(StitchRollTerm, SmallRollsAreTheSourcesQuadraticAndAHalfTurnIsSmooth) {
  const std::vector<double> q = stitch_state(0.0);
  const double kt = 0.02, L = 1e-3;
  StitchRollTerm t;
  t.add(identity12(), kt, L, StitchRollTerm::angle(q.data()), StitchRollTerm::opening(q.data()));
  for (double delta : {1e-3, -2e-3}) {
    const double expected = 0.5 * kt * L * delta * delta;
    EXPECT_NEAR(t.energy(0, rolled(q, delta).data()), expected, 1e-6 * expected) << delta;
  }
  EXPECT_NEAR(t.energy(0, rolled(q, M_PI).data()), 2.0 * kt * L, 1e-12 * kt * L);
  const std::vector<double> below = roll_force(t, rolled(q, M_PI - 1e-6)),
                            above = roll_force(t, rolled(q, M_PI + 1e-6));
  const double scale = norm(roll_force(t, rolled(q, 0.5 * M_PI)));
  ASSERT_GT(scale, 0.0);
  for (int a = 0; a < 12; ++a) EXPECT_NEAR(below[a], above[a], 1e-5 * scale) << a;
}

// x5 carried through the segment's line: ψ is undefined there and its
// gradient grows as 1/‖v_a‖, but the weighted energy and its force go to 0 on
// both sides (docs/models.md §11.4.1; the unweighted roll's force there grew
// without bound and flipped with the triangle's normal).
TEST(StitchRollTerm, ForceVanishesThroughADegenerateTriangle) {
  const std::vector<double> q = stitch_state(0.0);
  StitchRollTerm t;
  t.add(identity12(), 0.02, 1e-3, StitchRollTerm::angle(q.data()) + 1.0, StitchRollTerm::opening(q.data()));
  const double scale = norm(roll_force(t, q));
  ASSERT_GT(scale, 0.0);
  auto through = [&](double offset) {  // x5 on the segment's line beyond x1, moved off it along x by `offset`
    std::vector<double> p = q;
    for (int k = 0; k < 3; ++k) p[9 + k] = p[3 + k] + 1.5 * (p[3 + k] - p[k]) + (k == 0 ? offset : 0.0);
    return p;
  };
  for (double offset : {1e-7, -1e-7, 1e-9, -1e-9}) {
    const std::vector<double> p = through(offset);
    EXPECT_LT(norm(roll_force(t, p)), 2e-3 * scale) << offset;
    EXPECT_LT(t.energy(0, p.data()), 1e-6 * t.energy(0, q.data())) << offset;
  }
  // On the line (to rounding): no NaN, and still no force.
  const std::vector<double> on = through(0.0);
  const std::vector<double> f = roll_force(t, on);
  for (double x : f) EXPECT_TRUE(std::isfinite(x));
  EXPECT_LT(norm(f), 1e-6 * scale);
}

// One stitch whose leg node x5 (mass m) flies across the segment's line at
// speed w, x0, x1 and x3 held, the roll 1 rad from its rest: the free 12 × 12
// stockinette's failure at 292 ms in miniature (docs/models.md §11.4.1). With
// the source's roll energy this run gains energy from its second step on (4 %
// by the crossing): its force grows as 1/distance to the line and flips there.
class RollingLeg : public test::HandBuiltModel<RollingLeg> {
 public:
  RollingLeg(double m, double w) : HandBuiltModel("rolling-leg") {
    num_dofs_ = 12;
    std::vector<double> q = stitch_state(0.0);
    const Vec3 x0(q[0], q[1], q[2]), x1(q[3], q[4], q[5]);
    const Vec3 on_line = x1 + 1.5 * (x1 - x0), off = Vec3(1, 0, 0);
    const std::vector<double> rest = q;
    for (int k = 0; k < 3; ++k) q[9 + k] = on_line[k] + 0.2e-3 * off[k];
    q0_ = Eigen::Map<const Vec>(q.data(), 12);
    v0_ = Vec::Zero(12);
    v0_.segment<3>(9) = -w * off;
    terms_.push_back(std::make_unique<test::NodeMassTerm>(4, m));
    auto roll = std::make_unique<StitchRollTerm>();
    roll->add(identity12(), 1e-5, 1e-3, StitchRollTerm::angle(rest.data()) + 1.0, StitchRollTerm::opening(rest.data()));
    terms_.push_back(std::move(roll));
    for (int i = 0; i < 9; ++i) fixed_.push_back(i);
    finalize();
  }
};

TEST(StitchRollDynamics, BeNewtonCarriesALegNodeThroughTheSegmentsLine) {
  const double m = 1e-6, w = 0.37, h = 1e-4;
  RollingLeg model(m, w);
  auto integ = make_integrator("be-newton");
  IntegratorOptions opt;
  opt.dt = h;
  integ->initialize(model, 0.0, model.initial_q(), model.initial_v(), opt);
  auto energy = [&](const Vec& q, const Vec& v) { return model.potential_energy(q) + 0.5 * m * v.squaredNorm(); };
  double e_prev = energy(model.initial_q(), model.initial_v());
  const double x_line = model.initial_q()[9] - 0.2e-3;
  for (int k = 1; k <= 10; ++k) {
    const StepResult r = integ->advance_to(k * h);
    ASSERT_EQ(r.outcome, Outcome::ok) << "step " << k << ": " << r.message;
    const double e = energy(integ->q(), integ->v());
    EXPECT_LE(e, e_prev * (1.0 + 1e-9)) << "step " << k << ": backward Euler gained energy";
    e_prev = e;
  }
  EXPECT_LT(integ->q()[9], x_line - 0.1e-3) << "the leg node should have crossed the segment's line";
  EXPECT_EQ(integ->stats().rejected_steps, 0) << "no step should need halving";
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

// Two pieces of yarn crossing 0.3 mm apart (contact distance 0.4 mm): the
// closest points inside both (s, t ∈ (0, 1)), at an end of one (t clamped) and
// nearly parallel.
std::vector<test::LocalState> compression_states() {
  const std::vector<double> zero(12, 0.0);
  return {{{0.0, 0.0, 0.0, 1e-3, 0.1e-3, 0.0, 0.3e-3, -0.5e-3, 0.3e-3, 0.5e-3, 0.6e-3, 0.25e-3}, zero},
          {{0.0, 0.0, 0.0, 1e-3, 0.1e-3, 0.0, 0.3e-3, 0.2e-3, 0.3e-3, 0.5e-3, 1.2e-3, 0.25e-3}, zero},
          {{0.0, 0.0, 0.0, 1e-3, 0.0, 0.0, 0.2e-3, 0.01e-3, 0.25e-3, 1.3e-3, 0.03e-3, 0.3e-3}, zero}};
}

TEST(YarnCompressionTerm, ForcesJacobiansAndParameterDerivativeMatchFiniteDifferences) {
  const std::array<int, 12> s = identity12();
  YarnCompressionTerm t;
  t.add(s, 150.0, 0.4e-3);
  test::FdOptions opt;
  opt.rel_step = 1e-7;
  opt.floor = 1e-14;
  auto r = test::check_element(t, 0, compression_states(), opt);
  EXPECT_TRUE(r.ok) << r.detail;
  auto make = [&](double k) {
    auto term = std::make_unique<YarnCompressionTerm>();
    term->add(s, k, 0.4e-3);
    term->tag_last("knit.compression_stiffness_N_per_m", k);
    return std::unique_ptr<Term>(std::move(term));
  };
  r = test::check_parameter_derivative(make, 150.0, 0, 0, compression_states(), opt);
  EXPECT_TRUE(r.ok) << r.detail;
}

TEST(YarnCompressionTerm, DistanceAndPenaltyOfCrossingPieces) {
  // Perpendicular pieces crossing above each other at a gap of 0.3 mm, then
  // moved apart beyond the contact distance 0.4 mm (no force), then one piece
  // slid off the other's end (the distance to the end point).
  std::vector<double> q{-1e-3, 0.0, 0.0, 1e-3, 0.0, 0.0, 0.0, -1e-3, 0.3e-3, 0.0, 1e-3, 0.3e-3};
  EXPECT_NEAR(YarnCompressionTerm::distance(q.data()), 0.3e-3, 1e-15);
  YarnCompressionTerm t;
  t.add(identity12(), 200.0, 0.4e-3);
  EXPECT_NEAR(t.energy(0, q.data()), 0.5 * 200.0 * 1e-4 * 1e-4, 1e-18);
  std::vector<double> f(12, 0.0), v(12, 0.0);
  t.evaluate(0, q.data(), v.data(), ElementOutput{f.data()});
  // F = κ (D − d) = 0.02 N, half on each end, pushing the pieces apart along z.
  EXPECT_NEAR(f[2], -0.01, 1e-12);
  EXPECT_NEAR(f[8] + f[11], 0.02, 1e-12);
  q[8] = q[11] = 0.5e-3;
  std::fill(f.begin(), f.end(), 0.0);
  t.evaluate(0, q.data(), v.data(), ElementOutput{f.data()});
  EXPECT_EQ(t.energy(0, q.data()), 0.0);
  for (double x : f) EXPECT_EQ(x, 0.0);
  q[6] = q[9] = 1.3e-3;  // the second piece beside the first one's end (1 mm, 0, 0)
  q[8] = q[11] = 0.4e-3;
  EXPECT_NEAR(YarnCompressionTerm::distance(q.data()), 0.5e-3, 1e-15);
}

// A stitch contact (a, b) squeezed to a stack height below 2R = 0.4 mm, with
// the contact on the other side of its loop and those below and above it, the
// loop tilted out of the xy plane. `sign` mirrors it through the cloth (purl).
std::vector<double> stitch_contact_state(double sign) {
  std::vector<double> q{0.0,   0.0,  -0.12, 0.05, 0.55,  0.15, 1.0,  0.02, -0.25, 1.04, 0.5,  0.1,
                        -0.03, -1.6, -0.2,  0.02, -1.05, 0.22, 0.01, 1.6,  -0.18, 0.06, 2.15, 0.21};
  for (size_t k = 0; k < q.size(); ++k) q[k] *= 1e-3 * (k % 3 == 2 ? sign : 1.0);
  return q;
}

std::array<int, 24> identity24() {
  std::array<int, 24> s{};
  for (int a = 0; a < 24; ++a) s[a] = a;
  return s;
}

TEST(StitchCompressionTerm, ForcesJacobiansAndParameterDerivativeMatchFiniteDifferences) {
  // Knit and purl, from the left and from the right contact of the loop.
  for (const auto& [side, stitch] : {std::pair{1, 1}, std::pair{-1, -1}, std::pair{-1, 1}}) {
    std::vector<double> q = stitch_contact_state(stitch);
    if (side < 0)  // the other contact on the left: mirror in x
      for (size_t k = 0; k < q.size(); k += 3) q[k] = -q[k];
    const std::vector<test::LocalState> states{{q, std::vector<double>(24, 0.0)}};
    StitchCompressionTerm t;
    t.add(identity24(), 150.0, 0.4e-3, side, stitch);
    EXPECT_GT(t.energy(0, q.data()), 0.0) << "the test state should be squeezed";
    test::FdOptions opt;
    opt.rel_step = 1e-7;
    opt.floor = 1e-14;
    auto r = test::check_element(t, 0, states, opt);
    EXPECT_TRUE(r.ok) << r.detail;
    auto make = [&](double k) {
      auto term = std::make_unique<StitchCompressionTerm>();
      term->add(identity24(), k, 0.4e-3, side, stitch);
      term->tag_last("knit.compression_stiffness_N_per_m", k);
      return std::unique_ptr<Term>(std::move(term));
    };
    r = test::check_parameter_derivative(make, 150.0, 0, 0, states, opt);
    EXPECT_TRUE(r.ok) << r.detail;
  }
}

TEST(StitchCompressionTerm, StackHeightIsTheStitchExtentThroughTheCloth) {
  // A flat loop in the xy plane: h = z_b − z_a, the stitch slanting along the wale.
  std::vector<double> q(24, 0.0);
  const double nodes[8][3] = {{0, 0, -0.125}, {0, 0.5, 0.125}, {1, 0, 0},   {1, 0.5, 0},
                              {0, -1.6, 0},   {0, -1.1, 0},    {0, 1.6, 0}, {0, 2.1, 0}};
  for (int k = 0; k < 8; ++k)
    for (int d = 0; d < 3; ++d) q[3 * k + d] = 1e-3 * nodes[k][d];
  StitchCompressionTerm t;
  t.add(identity24(), 200.0, 0.4e-3, 1, 1);
  t.add(identity24(), 200.0, 0.4e-3, 1, -1);
  EXPECT_NEAR(t.stack_height(0, q.data()), 0.25e-3, 1e-15);
  EXPECT_NEAR(t.stack_height(1, q.data()), -0.25e-3, 1e-15);
  // V = ½ κ (2R − h)² for the knit; the purl stitch, crossing the wrong way, is deeper in.
  EXPECT_NEAR(t.energy(0, q.data()), 0.5 * 200.0 * 0.15e-3 * 0.15e-3, 1e-15);
  EXPECT_NEAR(t.energy(1, q.data()), 0.5 * 200.0 * 0.65e-3 * 0.65e-3, 1e-15);
  // The stack pushed open: F_b = κ (2R − h) n = 0.03 N along +z, F_a the opposite.
  std::vector<double> f(24, 0.0), v(24, 0.0);
  t.evaluate(0, q.data(), v.data(), ElementOutput{f.data()});
  EXPECT_NEAR(f[5], 0.03, 1e-12);
  EXPECT_NEAR(f[2], -0.03, 1e-12);
  q[5] = 0.35e-3;  // h = 0.45 mm ≥ 2R: no force
  std::fill(f.begin(), f.end(), 0.0);
  t.evaluate(0, q.data(), v.data(), ElementOutput{f.data()});
  for (double x : f) EXPECT_EQ(x, 0.0);
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

// A wrapped mass term's kinetic energy is that of the shifted state: the
// segment's rest coordinate span D = u₁ − u₀ includes the period's arc length.
TEST(ImageTerm, KineticEnergyOfTheShiftedState) {
  auto inertia = std::make_unique<SegmentInertiaTerm>();
  inertia->add({0, 1, 2, 3, 4, 5, 6, 7}, 2e-4);
  const std::vector<double> shift{0, 0, 0, 3e-3, 0, 0, 0, 3.1e-3};
  ImageTerm image(std::move(inertia), shift);
  const std::vector<double> q{0.0, 0.0, 0.0, -2.0e-3, 0.1e-3, 0.0, 0.0, -2.0e-3};
  const std::vector<double> v{0.1, -0.2, 0.05, 0.3, 0.1, -0.1, 0.02, -0.01};
  std::vector<double> shifted(8);
  for (int a = 0; a < 8; ++a) shifted[a] = q[a] + shift[a];
  const double expected = SegmentInertiaTerm::kinetic_energy(shifted.data(), v.data(), 2e-4);
  EXPECT_GT(expected, 0.0);
  EXPECT_DOUBLE_EQ(image.kinetic_energy(0, q.data(), v.data()), expected);
  // Term's generic ½ vᵀ M v from the wrapped evaluate agrees to round-off.
  EXPECT_NEAR(image.Term::kinetic_energy(0, q.data(), v.data()), expected, 1e-13 * expected);
}

}  // namespace
}  // namespace wl
