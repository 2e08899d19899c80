// Segment–edge contact (docs/models.md §3.11.10): the segment's distance to a
// box edge and a disk rim against dense sampling, the term through the FD
// checker (interior and end closest points, box and rim), its continuous
// collision, and a strip dropped across a thin plate: no point of any segment
// ever inside the plate, at either level.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "integrators/integrator.h"
#include "models/common/obstacle_edge.h"
#include "models/core/term_model.h"
#include "models/model_factory.h"
#include "tests/support/fd_check.h"
#include "tests/support/obstacle_meshes.h"

namespace wl {
namespace {

constexpr double kDhat = 1e-3, kKappa = 10.0;

ObstacleSpec box_spec() {  // half extents (10, 8, 5) mm, turned and moved
  ObstacleSpec s;
  s.shape = ObstacleSpec::Shape::box;
  s.center_m = {0.01, -0.02, 0.005};
  s.rotation_deg = {20.0, -35.0, 50.0};
  s.half_extents_m = {0.01, 0.008, 0.005};
  return s;
}

ObstacleSpec disk_spec() {  // radius 16 mm, 2 mm thick, tilted
  ObstacleSpec s;
  s.shape = ObstacleSpec::Shape::disk;
  s.center_m = {0.03, 0.03, -0.001};
  s.rotation_deg = {10.0, 5.0, 0.0};
  s.radius_m = 0.016;
  s.height_m = 0.002;
  return s;
}

Vec3 world(const ObstacleSpec& s, const Vec3& p) { return test::world_point(s, p); }

std::shared_ptr<std::vector<Obstacle>> one(const ObstacleSpec& s) {
  return std::make_shared<std::vector<Obstacle>>(std::vector<Obstacle>{Obstacle(s)});
}

// Body-frame segments near an edge: across the box's edge (x = 10, z = 5 mm)
// with the closest point inside the segment, near its corner, and one whose
// closest point is its end; across the disk's top rim, square and at 45°.
struct Segment {
  ObstacleSpec spec;
  Vec3 a, b;
  bool interior;
};
std::vector<Segment> segments() {
  const double mm = 1e-3;
  const Vec3 edge(0.01, 0.0, 0.005), corner(0.01, 0.008, 0.005), rim(0.016, 0.0, 0.001);
  return {{box_spec(), edge + mm * Vec3(-0.6, 0.0, 0.3), edge + mm * Vec3(0.6, 0.1, 0.25), true},
          {box_spec(), corner + mm * Vec3(-0.4, -0.4, 0.3), corner + mm * Vec3(0.4, 0.4, 0.25), true},
          {box_spec(), edge + mm * Vec3(0.2, 0.0, 0.3), edge + mm * Vec3(1.0, 0.3, 0.8), false},
          {disk_spec(), rim + mm * Vec3(-0.5, 0.0, 0.3), rim + mm * Vec3(0.5, 0.2, 0.25), true},
          {disk_spec(), rim + mm * Vec3(-0.3, -0.4, 0.3), rim + mm * Vec3(0.4, 0.3, 0.2), true}};
}

// A point's distance to an edge: a segment's clamped projection, a circle's hypot(ρ − r, z).
double point_to_edge(const SharpEdge& e, const Vec3& p) {
  const Vec3 rel = p - e.a;
  if (e.circle) {
    const double z = rel.dot(e.k);
    return std::hypot((rel - z * e.k).norm() - e.r, z);
  }
  const double t = std::clamp(rel.dot(e.b - e.a) / (e.b - e.a).squaredNorm(), 0.0, 1.0);
  return (rel - t * (e.b - e.a)).norm();
}

TEST(SegmentEdgeDistance, EqualsTheMinimumOverDenseSamples) {
  int checked = 0;
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (const Segment& c : segments()) {
    const Obstacle o(c.spec);
    for (int k = 0; k < 20; ++k) {
      const Vec3 a = world(c.spec, c.a + 2e-4 * Vec3(u(rng), u(rng), u(rng))),
                 b = world(c.spec, c.b + 2e-4 * Vec3(u(rng), u(rng), u(rng)));
      double best = 1.0;
      for (const SharpEdge& e : sharp_edges(o, 0.0)) {
        const SegmentEdgeClosest cp = closest_to_edge(e, a, b);
        double sampled = 1.0;
        const int n = 20000;
        for (int i = 0; i <= n; ++i) sampled = std::min(sampled, point_to_edge(e, a + (double(i) / n) * (b - a)));
        // Sampling overestimates the minimum by at most half a sample step (D is 1-Lipschitz).
        EXPECT_LE(cp.distance, sampled + 1e-15);
        EXPECT_GE(cp.distance, sampled - 0.5 * (b - a).norm() / n);
        EXPECT_NEAR(point_to_edge(e, a + cp.s * (b - a)), cp.distance, 1e-15);
        best = std::min(best, cp.distance);
        ++checked;
      }
      EXPECT_LT(best, kDhat);
    }
  }
  EXPECT_EQ(checked, 3 * 20 * 12 + 2 * 20 * 2);
}

TEST(ObstacleEdgeTerm, MatchesFiniteDifferencesAtInteriorAndEndClosestPoints) {
  int checked = 0;
  for (const Segment& c : segments()) {
    ObstacleEdgeTerm term(one(c.spec), kDhat, kKappa);
    term.add({0, 1, 2, 3, 4, 5}, 0);
    term.prepare(EvalContext{0.0});
    const Vec3 a = world(c.spec, c.a), b = world(c.spec, c.b);
    double d = 1.0, s = 0.0;
    for (const SharpEdge& e : sharp_edges(Obstacle(c.spec), 0.0)) {
      const SegmentEdgeClosest cp = closest_to_edge(e, a, b);
      if (cp.distance < d) std::tie(d, s) = std::make_pair(cp.distance, cp.s);
    }
    ASSERT_GT(d, 0.1 * kDhat);
    ASSERT_LT(d, 0.7 * kDhat);
    EXPECT_EQ(c.interior, s > 0.0 && s < 1.0) << "segment " << checked << ": s* = " << s;
    const std::vector<double> q = {a.x(), a.y(), a.z(), b.x(), b.y(), b.z()};
    const double extent = *std::max_element(q.begin(), q.end()) - *std::min_element(q.begin(), q.end());
    test::FdOptions opt;
    opt.rel_step = 1e-6 * d / extent;
    opt.jitter = 0.05 * d / extent;
    auto r = test::check_element(term, 0, {{q, std::vector<double>(6, 0.0)}}, opt);
    EXPECT_TRUE(r.ok) << "segment " << checked << ": " << r.detail;
    ++checked;
  }
  EXPECT_EQ(checked, 5);
}

// A segment that falls onto the box's edge within one step: the admissible
// fraction stops it at η d₀ (d₀ its distance at the start), never past; a
// move that stays clear is admissible in full.
TEST(ObstacleEdgeTerm, ContinuousCollisionStopsASegmentFallingOntoAnEdge) {
  const ObstacleSpec box = box_spec();
  ObstacleEdgeTerm term(one(box), kDhat, kKappa);
  term.add({0, 1, 2, 3, 4, 5}, 0);
  const double mm = 1e-3;
  const Vec3 edge(0.01, 0.0, 0.005);
  // Both ends 0.5 mm off the box's faces at the end of the move: only the segment meets the edge.
  const Vec3 a0 = world(box, edge + mm * Vec3(-1.0, 0.0, 0.8)), b0 = world(box, edge + mm * Vec3(1.0, 0.0, 0.8));
  const Vec3 a1 = world(box, edge + mm * Vec3(-1.0, 0.0, -0.5)), b1 = world(box, edge + mm * Vec3(1.0, 0.0, -1.5));
  Vec q0(6), q1(6), q2(6);
  q0 << a0, b0;
  q1 << a1, b1;
  const EvalContext from{0.0, &q0}, to{1e-3, &q1};
  const double alpha = term.admissible_fraction(from, to);
  ASSERT_GT(alpha, 0.0);
  ASSERT_LT(alpha, 1.0);
  q2 = q0 + alpha * (q1 - q0);
  double closest = 1.0, d0 = 1.0;
  for (const SharpEdge& e : sharp_edges(Obstacle(box), 0.0)) {
    closest = std::min(closest, closest_to_edge(e, q2.head<3>(), q2.tail<3>()).distance);
    d0 = std::min(d0, closest_to_edge(e, a0, b0).distance);
  }
  const double tau = ObstacleEdgeTerm::kApproachFraction * std::min(d0, kDhat);
  EXPECT_GE(closest, tau * (1.0 - 1e-6));
  EXPECT_LT(closest, 1.5 * tau);  // not far short of it either
  Vec q3 = q0;
  q3[2] += 2 * mm;
  q3[5] += 2 * mm;
  EXPECT_EQ(term.admissible_fraction(from, EvalContext{1e-3, &q3}), 1.0);
}

// A 10×3 strip (1 mm spacing) dropped from 0.3 mm above a plate 0.1 mm thick
// whose top edge runs across it between two columns of nodes, d̂ = 0.2 mm: no
// node comes within d̂ of the plate's faces, so only the segments that straddle
// it can hold the strip. At every step no point of any segment is inside the
// plate (each segment sampled at 201 points against the plate's own distance),
// and the strip hangs on the edge.
TEST(ObstacleEdgeTerm, AStripDroppedAcrossAThinPlateNeverCutsIt) {
  for (const char* model_name : {"yarn", "fem"}) {
    Scene scene;
    scene.wefts = 10;  // nodes along x
    scene.warps = 3;
    scene.pose = Scene::Pose::flat;
    scene.height_m = 0.0003;
    scene.terms.wind = false;
    scene.obstacle_contact.activation_distance_m = 0.0002;
    scene.obstacle_contact.segment_edges = true;
    ObstacleSpec plate;
    plate.shape = ObstacleSpec::Shape::box;
    plate.center_m = {0.0045, 0.001, -0.005};
    plate.half_extents_m = {0.00005, 0.005, 0.005};
    scene.obstacles.push_back(plate);
    const Obstacle o(plate);
    auto model = make_model(scene, model_name);
    const auto& terms = dynamic_cast<TermModel&>(*model).terms();
    const auto it =
        std::find_if(terms.begin(), terms.end(), [](const auto& t) { return t->name() == "obstacle_edge_contact"; });
    ASSERT_NE(it, terms.end()) << model_name;
    const Term& edges = **it;
    auto integ = make_integrator("be-linear");
    IntegratorOptions opt;
    opt.dt = 1e-3;
    integ->initialize(*model, 0.0, model->initial_q(), model->initial_v(), opt);
    double deepest = 1.0;
    auto check = [&](double t) {
      const Vec& q = integ->q();
      for (int e = 0; e < edges.num_elements(); ++e) {
        const auto s = edges.stencil(e);
        const Vec3 a(q[s[0]], q[s[1]], q[s[2]]), b(q[s[3]], q[s[4]], q[s[5]]);
        for (int i = 0; i <= 200; ++i) deepest = std::min(deepest, o.signed_distance(a + (i / 200.0) * (b - a), t));
      }
    };
    integ->on_step = [&](const StepRecord& r) { check(r.t); };
    const StepResult r = integ->advance_to(0.05);
    ASSERT_EQ(r.outcome, Outcome::ok) << model_name << ": " << r.message;
    EXPECT_GT(deepest, 0.0) << model_name << ": a segment cut the plate";
    double lowest = 1.0;
    const Vec& q = integ->q();
    for (int e = 0; e < edges.num_elements(); ++e) lowest = std::min(lowest, q[edges.stencil(e)[2]]);
    EXPECT_GT(lowest, -0.006) << model_name << ": the strip fell past the plate";
  }
}

}  // namespace
}  // namespace wl
