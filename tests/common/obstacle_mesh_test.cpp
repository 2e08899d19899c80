// Triangle-mesh obstacles (docs/models.md §3.11.9): the distance of a box mesh
// against the analytic box (value, sign, gradient, Hessian, inside and out),
// the icosphere against the sphere within its tessellation, the barrier
// through the FD checker in every feature region, near the switch between
// regions and near the barrier's limit, the force's continuity where the
// nearest feature changes, and the conservative continuous collision.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <random>

#include <Eigen/Geometry>

#include "models/common/obstacle.h"
#include "models/common/obstacle_barrier.h"
#include "models/scene/obstacle_mesh.h"
#include "tests/support/fd_check.h"
#include "tests/support/obstacle_meshes.h"

namespace wl {
namespace {

constexpr double kDhat = 0.01, kKappa = 10.0;
const Vec3 kHalf(0.1, 0.05, 0.08), kCenter(0.3, 0.0, 0.1), kRot(20.0, -35.0, 50.0);

ObstacleSpec analytic_box() {
  ObstacleSpec s;
  s.shape = ObstacleSpec::Shape::box;
  s.half_extents_m = {kHalf.x(), kHalf.y(), kHalf.z()};
  s.center_m = {kCenter.x(), kCenter.y(), kCenter.z()};
  s.rotation_deg = {kRot.x(), kRot.y(), kRot.z()};
  return s;
}

// The box as an OBJ in millimetres (quads), read with scale 10⁻³.
ObstacleSpec box_mesh_obstacle() {
  const auto dir = test::temp_folder();
  test::write_obj(dir / "box.obj", test::box_mesh(kHalf), 1e-3);
  return test::mesh_obstacle(dir / "box.obj", ObstacleSpec::Side::outside, 1e-3, kCenter, kRot);
}

TEST(MeshDistance, BoxMeshEqualsTheAnalyticBoxInsideAndOut) {
  const ObstacleSpec box_spec = analytic_box();
  const Obstacle box(box_spec), mesh(box_mesh_obstacle());
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1.6, 1.6);
  int inside = 0, outside = 0;
  for (int k = 0; k < 2000; ++k) {
    const Vec3 x = test::world_point(box_spec, kHalf.cwiseProduct(Vec3(u(rng), u(rng), u(rng))));
    Vec3 gb, gm;
    Mat3 hb, hm;
    const double db = box.signed_distance(x, 0.0, &gb, &hb), dm = mesh.signed_distance(x, 0.0, &gm, &hm);
    ASSERT_NEAR(dm, db, 1e-13) << "at " << x.transpose();
    ASSERT_LT((gm - gb).norm(), 1e-9) << "at " << x.transpose();
    if (db > 0.0) {
      ASSERT_LT((hm - hb).norm(), 1e-9 * std::max(1.0, hb.norm())) << "at " << x.transpose();
      ++outside;
    } else {
      ++inside;
    }
  }
  EXPECT_GT(inside, 200);
  EXPECT_GT(outside, 1000);
}

// The level-3 icosphere has its vertices on the sphere, so its solid lies in
// the ball and contains the ball of radius r·h_min, h_min the smallest
// distance of a face plane from the centre: d_sphere ≤ d_mesh ≤ d_sphere + r(1 − h_min).
TEST(MeshDistance, IcosphereIsTheSphereWithinItsTessellation) {
  const double r = 0.004;
  ObstacleSpec sphere;
  sphere.shape = ObstacleSpec::Shape::sphere;
  sphere.radius_m = r;
  const ObstacleSpec mesh_spec = test::mesh_obstacle(test::icosphere_file(), ObstacleSpec::Side::outside, r);
  const Obstacle s(sphere), m(mesh_spec);
  double h_min = 1.0;
  for (const auto& f : mesh_spec.mesh->faces) {
    const auto& V = mesh_spec.mesh->vertices;
    const Vec3 a(V[f[0]][0], V[f[0]][1], V[f[0]][2]), b(V[f[1]][0], V[f[1]][1], V[f[1]][2]),
        c(V[f[2]][0], V[f[2]][1], V[f[2]][2]);
    h_min = std::min(h_min, std::abs((b - a).cross(c - a).normalized().dot(a)) / r);
  }
  ASSERT_GT(h_min, 0.99);  // a fine tessellation: 0.45 % of r at most
  std::mt19937 rng(5);
  std::normal_distribution<double> n(0.0, 1.0);
  std::uniform_real_distribution<double> radius(0.3 * r, 2.0 * r);
  double widest = 0.0;
  for (int k = 0; k < 2000; ++k) {
    const Vec3 x = Vec3(n(rng), n(rng), n(rng)).normalized() * radius(rng);
    const double ds = s.signed_distance(x, 0.0), dm = m.signed_distance(x, 0.0);
    ASSERT_GE(dm, ds - 1e-15) << x.transpose();
    ASSERT_LE(dm, ds + r * (1.0 - h_min) + 1e-15) << x.transpose();
    widest = std::max(widest, dm - ds);
  }
  EXPECT_GT(widest, 0.5 * r * (1.0 - h_min));  // the bound is reached, not loose
}

struct Probe {
  Vec3 x;       // world point, 0 < d < d̂
  double room;  // how far it may move and stay in its feature region [m]
  const char* what;
};

void expect_fd(const Obstacle& o, const std::vector<Probe>& probes) {
  ObstacleBarrierTerm term(std::make_shared<std::vector<Obstacle>>(std::vector<Obstacle>{o}), kDhat, kKappa);
  term.add({0, 1, 2}, 0, 0);
  term.prepare(EvalContext{0.0});
  for (const Probe& p : probes) {
    const double d = o.signed_distance(p.x, 0.0);
    ASSERT_GT(d, 0.0) << p.what;
    ASSERT_LT(d, kDhat) << p.what;
    const double extent = std::max(p.x.maxCoeff() - p.x.minCoeff(), 1e-12);
    test::FdOptions opt;
    opt.rel_step = 1e-3 * std::min(d, p.room) / extent;
    opt.jitter = 0.3 * p.room / extent;
    auto r = test::check_element(term, 0, {{{p.x.x(), p.x.y(), p.x.z()}, {0, 0, 0}}}, opt);
    EXPECT_TRUE(r.ok) << p.what << " (d = " << d << " m): " << r.detail;
  }
}

// Body-frame points of the box mesh (faces x = ±a, y = ±b, z = ±c, each split
// along a diagonal) in each region, near the switch between two regions, and
// near the barrier's limit.
TEST(MeshBarrier, EveryFeatureRegionMatchesFiniteDifferences) {
  const ObstacleSpec spec = box_mesh_obstacle();
  const Obstacle o(spec);
  const double a = kHalf.x(), b = kHalf.y(), c = kHalf.z();
  auto at = [&](double x, double y, double z) { return test::world_point(spec, Vec3(x, y, z)); };
  expect_fd(o, {
                   {at(a + 0.004, 0.01, 0.02), 0.004, "face +x"},
                   {at(a + 0.003, b + 0.002, 0.0), 0.002, "edge x = a, y = b"},
                   {at(-a - 0.002, b + 0.002, -c - 0.003), 0.002, "vertex (−a, b, −c)"},
                   {at(0.03, -b - 0.0045, 0.01), 0.0045, "face −y"},
                   {at(a + 0.004, b - 1e-5, 0.0), 1e-5, "face +x, 10 µm from its edge"},
                   {at(a + 0.004, b + 1e-5, 0.0), 1e-5, "edge, 10 µm past the face's region"},
                   {at(a + 0.003, b + 0.002, c - 1e-5), 1e-5, "edge, 10 µm from the vertex region"},
                   {at(a + 0.003, b + 0.002, c + 1e-5), 1e-5, "vertex, 10 µm past the edge region"},
                   {at(a + 1e-3 * kDhat, 0.01, 0.02), 1e-3 * kDhat, "face at d = 10⁻³ d̂"},
                   {at(a + 1e-3 * kDhat, b + 1e-3 * kDhat, 0.0), 1e-3 * kDhat, "edge at d ≈ 1.4·10⁻³ d̂"},
                   {at(a + 1e-3 * kDhat, b + 1e-3 * kDhat, c + 1e-3 * kDhat), 1e-3 * kDhat, "vertex at d ≈ 1.7·10⁻³ d̂"},
               });
  // Closer to the limit the point's coordinates must be of the order of d, so
  // that rounding does not swamp the differences: a sheet through the origin.
  const auto dir = test::temp_folder();
  test::write_obj(dir / "sheet.obj", test::square_mesh(0.5));
  const ObstacleSpec sheet = test::mesh_obstacle(dir / "sheet.obj", ObstacleSpec::Side::both, 1.0, Vec3::Zero(), kRot);
  std::vector<Probe> near;
  for (double frac : {1e-5, 1e-7, 1e-10}) {
    const double d = frac * kDhat;
    near.push_back({test::world_point(sheet, Vec3(0.5 * d, -0.3 * d, d)), d, "sheet near the limit"});
  }
  expect_fd(Obstacle(sheet), near);
}

// An open V (two squares meeting at a 90° fold along y, concave from above),
// two-sided: above and below, and the fold's edge from below (convex there).
TEST(MeshBarrier, OpenTwoSidedMeshMatchesFiniteDifferencesOnBothSides) {
  const auto dir = test::temp_folder();
  test::PolyMesh v{{Vec3(-0.1, -0.1, 0.1), Vec3(0, -0.1, 0), Vec3(0, 0.1, 0), Vec3(-0.1, 0.1, 0.1),
                    Vec3(0.1, -0.1, 0.1), Vec3(0.1, 0.1, 0.1)},
                   {{0, 1, 2, 3}, {1, 4, 5, 2}}};
  test::write_obj(dir / "v.obj", v);
  const ObstacleSpec spec =
      test::mesh_obstacle(dir / "v.obj", ObstacleSpec::Side::both, 1.0, Vec3(0.1, 0.2, 0.0), kRot);
  const Obstacle o(spec);
  const Vec3 n_left = Vec3(1, 0, 1).normalized(), n_right = Vec3(-1, 0, 1).normalized();
  auto at = [&](const Vec3& p) { return test::world_point(spec, p); };
  expect_fd(o, {
                   {at(Vec3(-0.05, 0.02, 0.05) + 0.004 * n_left), 0.004, "left face, above"},
                   {at(Vec3(0.05, -0.03, 0.05) - 0.003 * n_right), 0.003, "right face, below"},
                   {at(Vec3(0.0, 0.01, -0.004)), 0.003, "the fold from below"},
                   {at(Vec3(0.1, 0.1, 0.1) + Vec3(0.002, 0.003, 0.001)), 0.001, "a corner"},
               });
  EXPECT_GT(o.signed_distance(at(Vec3(0.05, -0.03, 0.05) - 0.003 * n_right), 0.0), 0.0);  // two-sided: never < 0
}

// ‖F(+ε) − F(−ε)‖ across the switch from the +x face's region to the edge's
// shrinks with ε: the force is continuous there (∇d is; only ∇²d jumps).
TEST(MeshBarrier, ForceIsContinuousWhereTheNearestFeatureChanges) {
  const ObstacleSpec spec = box_mesh_obstacle();
  ObstacleBarrierTerm term(std::make_shared<std::vector<Obstacle>>(std::vector<Obstacle>{Obstacle(spec)}), kDhat,
                           kKappa);
  term.add({0, 1, 2}, 0, 0);
  auto jump = [&](double eps) {
    auto f = [&](double s) {
      return term.force(0, 0.0, test::world_point(spec, Vec3(kHalf.x() + 0.004, kHalf.y() + s, 0)));
    };
    return (f(eps) - f(-eps)).norm();
  };
  const double f0 = term.force(0, 0.0, test::world_point(spec, Vec3(kHalf.x() + 0.004, kHalf.y(), 0))).norm();
  ASSERT_GT(f0, 0.0);
  EXPECT_LT(jump(1e-6), 1e-3 * f0);
  EXPECT_LT(jump(1e-8), 0.02 * jump(1e-6));
}

// Conservative advancement: exact for a path straight at a face, caught before
// a thin sheet it would cross in one step, never past the analytic box's first
// approach and close to it, with a moving mesh too.
TEST(MeshCcd, FirstApproachIsConservativeAndCatchesTunnelling) {
  const auto dir = test::temp_folder();
  test::write_obj(dir / "sheet.obj", test::square_mesh(0.5));
  const ObstacleSpec sheet_spec = test::mesh_obstacle(dir / "sheet.obj", ObstacleSpec::Side::both);
  const Obstacle sheet(sheet_spec);
  const double tau = 1e-3;
  // Straight through the sheet in one step: stopped τ before it.
  EXPECT_NEAR(sheet.first_approach(Vec3(0.1, 0.1, 0.5), 0, Vec3(0.1, 0.1, -0.5), 1, tau), (0.5 - tau) / 1.0, 1e-12);
  // Obliquely through it (45°): the first α where d = τ is (0.5 − τ)/1 along z.
  const double oblique = sheet.first_approach(Vec3(-0.3, 0.0, 0.5), 0, Vec3(0.3, 0.0, -0.1), 1, tau);
  EXPECT_NEAR(oblique, (0.5 - tau) / 0.6, 1e-6);
  EXPECT_LE(oblique, (0.5 - tau) / 0.6);
  // A sheet rising at 0.02 m/s to a node at rest 10 mm above it.
  ObstacleSpec rising = sheet_spec;
  rising.velocity_m_per_s = {0, 0, 0.02};
  EXPECT_NEAR(Obstacle(rising).first_approach(Vec3(0, 0, 0.01), 0, Vec3(0, 0, 0.01), 1, tau), (0.01 - tau) / 0.02,
              1e-12);
  // Passing by: no approach.
  EXPECT_EQ(sheet.first_approach(Vec3(0, 0, 0.5), 0, Vec3(0.3, 0.2, 0.4), 1, tau), 1.0);

  const Obstacle box(analytic_box()), mesh(box_mesh_obstacle());
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-0.25, 0.25);
  int hits = 0, close = 0;
  for (int k = 0; k < 300; ++k) {
    const Vec3 x0 = kCenter + Vec3(u(rng), u(rng), 0.4), x1 = kCenter + Vec3(u(rng), u(rng), -0.4);
    const double am = mesh.first_approach(x0, 0, x1, 1, 0.01), ab = box.first_approach(x0, 0, x1, 1, 0.01);
    for (int j = 0; j < 200; ++j)  // above τ on [0, α)
      ASSERT_GT(mesh.signed_distance(x0 + am * j / 200.0 * (x1 - x0), 0), 0.01 * (1 - 1e-9));
    // never past the first approach to τ of the analytic box (exact to 10⁻⁶ τ)
    ASSERT_GT(box.signed_distance(x0 + am * (x1 - x0), 0), 0.01 * (1 - 1e-9));
    if (ab < 1.0) {
      ++hits;
      close += std::abs(ab - am) < 1e-4;
    }
  }
  EXPECT_GT(hits, 100);
  EXPECT_GE(close, hits * 9 / 10);
}

}  // namespace
}  // namespace wl
