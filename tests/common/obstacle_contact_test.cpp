// Node–obstacle contact (docs/models.md §3.11): the barrier and the friction
// through the FD checker (every shape and region, the barrier near its limit),
// the barrier's shape, and the continuous collision of first_approach.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>

#include "models/common/obstacle.h"
#include "models/common/obstacle_barrier.h"
#include "models/common/obstacle_friction.h"
#include "models/core/step_stiffness.h"
#include "tests/support/fd_check.h"
#include "tests/support/obstacle_meshes.h"

namespace wl {
namespace {

ObstacleSpec spec(ObstacleSpec::Shape shape, Vec3 c, Vec3 rot_deg = Vec3::Zero()) {
  ObstacleSpec s;
  s.shape = shape;
  s.center_m = {c.x(), c.y(), c.z()};
  s.rotation_deg = {rot_deg.x(), rot_deg.y(), rot_deg.z()};
  return s;
}

Vec3 world(const ObstacleSpec& s, const Vec3& p) { return test::world_point(s, p); }

struct Case {
  ObstacleSpec spec;
  std::vector<Vec3> local_points;  // body-frame points 0 < d < d̂
};

std::vector<Case> shape_cases() {
  const Vec3 rot(20.0, -35.0, 50.0);
  std::vector<Case> cases;
  cases.push_back({spec(ObstacleSpec::Shape::plane, Vec3(0.1, 0.2, 0.3), rot), {{0.01, 0.02, 0.004}, {0, 0, 0.0002}}});
  ObstacleSpec sphere = spec(ObstacleSpec::Shape::sphere, Vec3(0.0, 0.1, -0.2), rot);
  sphere.radius_m = 0.1;
  cases.push_back({sphere, {Vec3(0.3, -0.5, 0.8).normalized() * 0.104, Vec3(0, 0, 0.1005)}});
  ObstacleSpec box = spec(ObstacleSpec::Shape::box, Vec3(0.3, 0.0, 0.1), rot);
  box.half_extents_m = {0.1, 0.05, 0.08};
  cases.push_back({box, {{0.104, 0.01, 0.02}, {0.103, 0.053, 0.0}, {-0.102, 0.052, -0.083}, {0.03, -0.0545, 0.01}}});
  for (auto shape : {ObstacleSpec::Shape::cylinder, ObstacleSpec::Shape::disk}) {
    ObstacleSpec cyl = spec(shape, Vec3(-0.2, 0.1, 0.0), rot);
    cyl.radius_m = 0.05;
    cyl.height_m = shape == ObstacleSpec::Shape::disk ? 0.01 : 0.1;
    const double a = 0.5 * cyl.height_m;
    cases.push_back({cyl, {{0.054, 0.002, 0.0}, {0.01, 0.02, a + 0.004}, {0.052, 0.01, -(a + 0.003)}}});
  }
  return cases;
}

constexpr double kDhat = 0.01, kKappa = 10.0;

std::shared_ptr<std::vector<Obstacle>> one(const ObstacleSpec& s) {
  return std::make_shared<std::vector<Obstacle>>(std::vector<Obstacle>{Obstacle(s)});
}

TEST(ObstacleBarrier, EveryShapeAndRegionMatchesFiniteDifferences) {
  int checked = 0;
  for (const Case& c : shape_cases()) {
    ObstacleBarrierTerm term(one(c.spec), kDhat, kKappa);
    term.add({0, 1, 2}, 0, 0);
    term.prepare(EvalContext{0.0});
    for (const Vec3& p : c.local_points) {
      const Vec3 x = world(c.spec, p);
      const double d = term.obstacle(0).signed_distance(x, 0.0);
      ASSERT_GT(d, 0.0);
      ASSERT_LT(d, kDhat);
      // The state's extent is about the distance, so steps resolve the barrier's curvature.
      test::FdOptions opt;
      opt.rel_step = 1e-6 * d / std::max(x.maxCoeff() - x.minCoeff(), 1e-12);
      opt.jitter = 0.05 * d / std::max(x.maxCoeff() - x.minCoeff(), 1e-12);
      auto r = test::check_element(term, 0, {{{x.x(), x.y(), x.z()}, {0, 0, 0}}}, opt);
      EXPECT_TRUE(r.ok) << "shape " << static_cast<int>(c.spec.shape) << " at " << p.transpose() << ": " << r.detail;
      ++checked;
    }
  }
  EXPECT_EQ(checked, 14);
}

// Near the limit: d = 10⁻² d̂, 10⁻³ d̂, 10⁻⁵ d̂ (the log barrier) and 10⁻¹⁰ d̂ (its Taylor continuation).
TEST(ObstacleBarrier, NearItsLimitMatchesFiniteDifferences) {
  ObstacleSpec plane = spec(ObstacleSpec::Shape::plane, Vec3::Zero(), Vec3(10, 0, 0));
  ObstacleBarrierTerm term(one(plane), kDhat, kKappa);
  term.add({0, 1, 2}, 0, 0);
  term.prepare(EvalContext{0.0});
  for (double frac : {1e-2, 1e-3, 1e-5, 1e-10}) {
    const double d = frac * kDhat;
    const Vec3 x = world(plane, Vec3(0.5 * d, -0.3 * d, d));
    test::FdOptions opt;
    opt.rel_step = 1e-4;
    opt.jitter = 0.05;
    auto r = test::check_element(term, 0, {{{x.x(), x.y(), x.z()}, {0, 0, 0}}}, opt);
    EXPECT_TRUE(r.ok) << "d = " << d << ": " << r.detail;
  }
}

// The step stiffness (docs/models.md §3.11.2): with the projection on, the
// term's own ∂f/∂q is still the exact one (FD checker); the projected block
// −K̃ is positive semi-definite, equal to −K where that is, and otherwise
// keeps −K's positive eigenpairs and drops the rest. On a sphere
// −K = κ b'' g gᵀ + κ (b'/r)(I − g gᵀ) with b' < 0, so −K̃ = κ b'' g gᵀ.
TEST(ObstacleBarrier, StepStiffnessIsThePsdPartOfTheExactHessian) {
  int psd = 0, indefinite = 0;
  for (const Case& c : shape_cases()) {
    ObstacleBarrierTerm term(one(c.spec), kDhat, kKappa);
    term.set_projected_step_stiffness(true);
    term.add({0, 1, 2}, 0, 0);
    term.prepare(EvalContext{0.0});
    for (const Vec3& p : c.local_points) {
      const Vec3 x = world(c.spec, p);
      const double d = term.obstacle(0).signed_distance(x, 0.0);
      test::FdOptions opt;
      opt.rel_step = 1e-6 * d / std::max(x.maxCoeff() - x.minCoeff(), 1e-12);
      opt.jitter = 0.05 * d / std::max(x.maxCoeff() - x.minCoeff(), 1e-12);
      const auto r = test::check_element(term, 0, {{{x.x(), x.y(), x.z()}, {0, 0, 0}}}, opt);
      EXPECT_TRUE(r.ok) << r.detail;
      Vec3 f = Vec3::Zero();
      const Vec3 v = Vec3::Zero();
      Mat3 k = Mat3::Zero();
      term.evaluate(0, x.data(), v.data(), ElementOutput{f.data(), k.data()});
      Mat3 kp = k;
      project_step_stiffness(3, kp.data());
      const Eigen::SelfAdjointEigenSolver<Mat3> exact(-k);
      const double scale = exact.eigenvalues().cwiseAbs().maxCoeff();
      ASSERT_GT(scale, 0.0);
      const Vec3 lp = Eigen::SelfAdjointEigenSolver<Mat3>(-kp).eigenvalues();
      EXPECT_GE(lp.minCoeff(), -1e-12 * scale);
      if (exact.eigenvalues().minCoeff() >= 0.0) {
        EXPECT_EQ(kp, k);
        ++psd;
        continue;
      }
      ++indefinite;
      EXPECT_GE(Eigen::SelfAdjointEigenSolver<Mat3>(k - kp).eigenvalues().minCoeff(), -1e-12 * scale);  // −K̃ ⪰ −K
      for (int i = 0; i < 3; ++i) {
        const double l = exact.eigenvalues()[i];
        const Vec3 u = exact.eigenvectors().col(i);
        EXPECT_LT((-kp * u - std::max(l, 0.0) * u).norm(), 1e-10 * scale);
      }
      if (c.spec.shape != ObstacleSpec::Shape::sphere) continue;
      const Vec3 g = (x - Vec3(c.spec.center_m[0], c.spec.center_m[1], c.spec.center_m[2])).normalized();
      const Mat3 expected = -kKappa * contact_barrier(d, kDhat).d2b * g * g.transpose();
      EXPECT_LT((kp - expected).norm(), 1e-9 * expected.norm());
    }
  }
  EXPECT_GT(psd, 0);         // the plane, flat faces
  EXPECT_GT(indefinite, 0);  // the sphere, edges, rims
}

TEST(ObstacleBarrier, IsZeroBeyondDhatC2ThereAndUnboundedAtContact) {
  const BarrierValue at = contact_barrier(kDhat, kDhat), inside = contact_barrier(kDhat * (1 - 1e-6), kDhat);
  EXPECT_EQ(at.b, 0.0);
  EXPECT_EQ(contact_barrier(2 * kDhat, kDhat).db, 0.0);
  EXPECT_LT(std::abs(inside.db), 1e-10);  // b' → 0 and b'' → 0 at d̂ (C² join)
  EXPECT_LT(std::abs(inside.d2b), 1e-4);
  double last = 0.0;
  for (double frac : {0.5, 1e-1, 1e-2, 1e-3}) {  // repels ever harder towards contact
    const BarrierValue b = contact_barrier(frac * kDhat, kDhat);
    EXPECT_GT(b.b, last);
    EXPECT_LT(b.db, 0.0);
    last = b.b;
  }
  EXPECT_GT(-contact_barrier(1e-3 * kDhat, kDhat).db, 900 * kDhat);  // −b' ≈ d̂²/d
}

TEST(ObstacleFriction, MatchesFiniteDifferencesSlowAndFastAndOnAMovingObstacle) {
  ObstacleSpec plane = spec(ObstacleSpec::Shape::plane, Vec3::Zero(), Vec3(15, 0, 0));
  plane.friction_coefficient = 0.4;
  plane.velocity_m_per_s = {0.001, -0.002, 0.0};
  const double eps = 1e-3;
  test::FdOptions opt;
  opt.constant_force = true;  // λ and n are lagged: ∂F/∂x = 0
  const std::vector<test::LocalState> states = {{{0.01, 0.02, 0.003}, {0.0013, -0.0017, 0.0004}},  // ‖u‖ < ε
                                                {{0.01, 0.02, 0.003}, {0.03, 0.05, -0.01}}};       // ‖u‖ > ε
  for (double slip : {0.3 * eps, 20.0 * eps}) {  // lagged slip speed below and above ε
    ObstacleFrictionTerm term(one(plane), kDhat, kKappa, eps);
    term.add({0, 1, 2}, 0, 0);
    term.set_lagged(0, 2.0, Vec3(0.0, -std::sin(0.26), std::cos(0.26)), slip);
    auto r = test::check_element(term, 0, states, opt);
    EXPECT_TRUE(r.ok) << "y₀ = " << slip << ": " << r.detail;
  }
}

// F·(ẋ − v_o) ≤ 0 for every ẋ and lagged slip speed y₀; at the steady slip
// ‖u‖ = y₀ the force is μλ f₁(y₀), f₁(y) = 2y/ε − y²/ε² below ε, 1 above.
TEST(ObstacleFriction, DissipatesForEveryVelocityAndGivesSmoothedCoulombAtSteadySlip) {
  ObstacleSpec plane = spec(ObstacleSpec::Shape::plane, Vec3::Zero());
  plane.friction_coefficient = 0.5;
  plane.velocity_m_per_s = {0.2, 0.0, 0.0};
  const double eps = 1e-3, lambda = 3.0;
  ObstacleFrictionTerm term(one(plane), kDhat, kKappa, eps);
  term.add({0, 1, 2}, 0, 0);
  std::mt19937 rng(7);
  std::normal_distribution<double> n(0.0, 0.01);
  for (int k = 0; k < 50; ++k) {
    term.set_lagged(0, lambda, Vec3::UnitZ(), std::abs(n(rng)));
    const Vec3 v(n(rng), n(rng), n(rng));
    const Vec3 f = term.force(0, v);
    EXPECT_LE(f.dot(v - Vec3(0.2, 0, 0)), 1e-15);  // F·(ẋ − v_o) ≤ 0
    EXPECT_NEAR(f.z(), 0.0, 1e-15);                // tangential
  }
  for (double y : {0.25 * eps, 0.9 * eps, 1.0 * eps, 50.0 * eps}) {
    term.set_lagged(0, lambda, Vec3::UnitZ(), y);
    const double f1 = y < eps ? 2.0 * y / eps - y * y / (eps * eps) : 1.0;
    const Vec3 f = term.force(0, Vec3(0.2 + 0.6 * y, -0.8 * y, 7.0));  // slip (0.6, −0.8) y, any normal speed
    EXPECT_NEAR(f.norm(), 0.5 * lambda * f1, 1e-12 * lambda) << "y = " << y;
    EXPECT_NEAR(f.normalized().dot(Vec3(-0.6, 0.8, 0.0)), 1.0, 1e-12) << "y = " << y;  // against the slip
  }
}

// first_approach against the exact first time of the distance τ on a plane and a
// sphere, tunnelling through a thin disk, a moving obstacle, and conservativeness
// on random box and cylinder paths.
TEST(ObstacleCcd, FirstApproachIsExactOrConservative) {
  ObstacleSpec plane = spec(ObstacleSpec::Shape::plane, Vec3::Zero());
  Obstacle p(plane);
  EXPECT_NEAR(p.first_approach(Vec3(0, 0, 0.01), 0, Vec3(0.3, 0, -0.01), 1, 0.001), 0.45, 1e-12);
  EXPECT_EQ(p.first_approach(Vec3(0, 0, 0.01), 0, Vec3(0.3, 0, 0.02), 1, 0.001), 1.0);
  plane.velocity_m_per_s = {0, 0, 0.02};  // the floor rises to a resting node
  EXPECT_NEAR(Obstacle(plane).first_approach(Vec3(0, 0, 0.01), 0, Vec3(0, 0, 0.01), 1, 0.001), 0.45, 1e-12);

  ObstacleSpec sphere = spec(ObstacleSpec::Shape::sphere, Vec3::Zero());
  sphere.radius_m = 1.0;
  Obstacle s(sphere);
  // Along x at height y = 0.5: ‖p‖ = 1.1 at x = −√(1.21 − 0.25).
  const double x_hit = -std::sqrt(1.21 - 0.25), a = (x_hit + 2.0) / 4.0;
  EXPECT_NEAR(s.first_approach(Vec3(-2, 0.5, 0), 0, Vec3(2, 0.5, 0), 1, 0.1), a, 1e-6);
  EXPECT_EQ(s.first_approach(Vec3(-2, 1.2, 0), 0, Vec3(2, 1.2, 0), 1, 0.1), 1.0);  // passes by

  ObstacleSpec disk = spec(ObstacleSpec::Shape::disk, Vec3::Zero(), Vec3(0, 90, 0));
  disk.radius_m = 0.5;
  disk.height_m = 1e-4;
  const double thin = Obstacle(disk).first_approach(Vec3(-1, 0.1, 0), 0, Vec3(1, 0.1, 0), 1, 1e-3);
  EXPECT_LT(thin, 0.5);  // caught: one step would cross the thin disk
  EXPECT_NEAR(thin, (1.0 - 0.5e-4 - 1e-3) / 2.0, 1e-6);

  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-0.4, 0.4);
  ObstacleSpec box = spec(ObstacleSpec::Shape::box, Vec3::Zero(), Vec3(10, 20, 30));
  box.half_extents_m = {0.1, 0.2, 0.15};
  ObstacleSpec cyl = spec(ObstacleSpec::Shape::cylinder, Vec3::Zero(), Vec3(-20, 5, 40));
  cyl.radius_m = 0.15;
  cyl.height_m = 0.2;
  int hits = 0;
  for (const ObstacleSpec& sp : {box, cyl}) {
    const Obstacle o(sp);
    for (int k = 0; k < 200; ++k) {
      const Vec3 x0(u(rng), u(rng), 0.6), x1(u(rng), u(rng), -0.6);
      const double tau = 0.01, alpha = o.first_approach(x0, 0, x1, 1, tau);
      for (int j = 0; j < 400; ++j) {  // above τ on [0, α)
        const double at = alpha * j / 400.0;
        ASSERT_GT(o.signed_distance(x0 + at * (x1 - x0), 0), tau * (1 - 1e-9));
      }
      if (alpha < 1.0) {
        ++hits;
        EXPECT_NEAR(o.signed_distance(x0 + alpha * (x1 - x0), 0), tau, 1e-6 * tau);  // and it is the first approach
      }
    }
  }
  EXPECT_GT(hits, 100);
}

}  // namespace
}  // namespace wl
