// FemModel: patch tests, bending normalisation, equilibrium at rest, output
// frame and short backward-Euler runs.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include <Eigen/Geometry>

#include "integrators/backward_euler.h"
#include "models/fem/fem_model.h"
#include "models/model_factory.h"
#include "models/scene/scene.h"
#include "tests/fem/fem_test_scene.h"

namespace wl {
namespace {

Vec force(FemModel& m, const Vec& q, const Vec& v) {
  Evaluation ev;
  allocate_evaluation(m, ev);
  m.evaluate(0.0, q, v, kForce | kDfdq | kDfdv | kMass, ev);
  return ev.force;
}
Vec force(FemModel& m, const Vec& q) { return force(m, q, Vec::Zero(q.size())); }

// Elastic terms with distinct warp/weft values and a lock.
Scene elastic_scene(int nu, int nv) {
  Scene s = test::fem_scene(nu, nv);
  s.fem.warp_stretch_N_per_m = 400.0;
  s.fem.weft_stretch_N_per_m = 150.0;
  s.fem.shear_N_per_m = 3.0;
  s.fem.shear_lock_angle_rad = 0.4;
  s.fem.shear_lock_exponent = 2.0;
  s.fem.warp_bending_N_m = 2e-6;
  s.fem.weft_bending_N_m = 5e-7;
  return s;
}

double scale_of(const FemModel& m) { return m.material().warp_stretch_N_per_m * 1e-3; }  // k·L: force at unit strain

TEST(FemModelPatch, RigidMotionsGiveZeroForce) {
  for (auto pose : {Scene::Pose::flat, Scene::Pose::upright}) {
    Scene s = elastic_scene(5, 4);
    s.pose = pose;
    FemModel m(s);
    const Vec q0 = m.initial_q();
    EXPECT_LT(force(m, q0).norm(), 1e-12 * scale_of(m));  // rest without gravity/wind: equilibrium
    const Mat3 R = Eigen::AngleAxisd(1.1, Vec3(0.3, -1, 2).normalized()).toRotationMatrix();
    const Vec3 t(0.5, -0.2, 3.0);
    Vec q = q0;
    for (int i = 0; i < m.mesh().num_vertices(); ++i) q.segment<3>(3 * i) = R * q0.segment<3>(3 * i) + t;
    EXPECT_LT(force(m, q).norm(), 1e-10 * scale_of(m));
    EXPECT_NEAR(m.potential_energy(q), 0.0, 1e-14);
  }
}

TEST(FemModelPatch, UniformStretchGivesAnalyticEdgeReaction) {
  // Flat sheet W × H stretched by ε along u (x = ((1+ε)u, v, h)): the right
  // edge carries k_u·ε·H, the left edge the opposite, interior vertices none.
  for (int axis : {0, 1}) {
    Scene s = elastic_scene(6, 5);
    FemModel m(s);
    const double eps = 0.03, L = 1e-3;
    const double k = axis == 0 ? 400.0 : 150.0;
    const double width = axis == 0 ? 4 * L : 5 * L;  // length of the loaded edge
    Vec q = m.initial_q();
    const FemMesh& mesh = m.mesh();
    for (int i = 0; i < mesh.num_vertices(); ++i) q[3 * i + axis] = (1 + eps) * mesh.uv[i][axis];
    const Vec f = force(m, q);
    const double umax = axis == 0 ? 5 * L : 4 * L;
    Vec3 right = Vec3::Zero(), left = Vec3::Zero();
    double interior = 0.0;
    for (int i = 0; i < mesh.num_vertices(); ++i) {
      const double c = mesh.uv[i][axis];
      if (std::abs(c - umax) < 1e-12) right += f.segment<3>(3 * i);
      else if (std::abs(c) < 1e-12) left += f.segment<3>(3 * i);
      else interior = std::max(interior, f.segment<3>(3 * i).norm());
    }
    Vec3 expect = Vec3::Zero();
    expect[axis] = -k * eps * width;
    EXPECT_NEAR((right - expect).norm(), 0.0, 1e-12) << "axis " << axis << ": " << right.transpose();
    EXPECT_NEAR((left + expect).norm(), 0.0, 1e-12);
    EXPECT_LT(interior, 1e-12);
    // tension map: l = 1+ε along the axis, tension k·ε everywhere
    const Frame fr = m.frame(0.0, q, Vec::Zero(q.size()));
    ASSERT_EQ(fr.cell_data.size(), 3u);
    EXPECT_EQ(fr.cell_data[0].name, "tension");
    for (double x : fr.cell_data[0].values) EXPECT_NEAR(x, k * eps, 1e-9);
    for (double x : fr.cell_data[axis == 0 ? 1 : 2].values) EXPECT_NEAR(x, 1 + eps, 1e-12);
  }
}

TEST(FemModelPatch, FlatSheetHasZeroBendingForce) {
  Scene s = elastic_scene(5, 5);
  s.terms.stretch = s.terms.shear = false;  // bending alone
  FemModel m(s);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> d(-3e-4, 3e-4);
  Vec q = m.initial_q();
  for (int i = 0; i < m.mesh().num_vertices(); ++i) {  // in-plane distortion, z unchanged
    q[3 * i] += d(rng);
    q[3 * i + 1] += d(rng);
  }
  EXPECT_EQ(force(m, q).norm(), 0.0);
  q[3 * 12 + 2] += 1e-4;  // and the check can fail: lift one vertex
  EXPECT_GT(force(m, q).norm(), 1e-6);
}

TEST(FemModelPatch, CylinderBendingEnergyIsHalfStiffnessCurvatureSquared) {
  // Bent about the v axis with curvature κ (vertices on the cylinder), only the
  // edges along v fold, each by θ = κL, with V_e = ½k_warp(κL)²: the interior
  // region carries ½k_warp κ² per area. About the u axis likewise with k_weft.
  const int na = 7, nb = 6;
  const double L = 1e-3, kappa = 20.0;
  for (int axis : {0, 1}) {
    Scene s = elastic_scene(na, nb);
    s.terms.stretch = s.terms.shear = false;
    FemModel m(s);
    Vec q = m.initial_q();
    for (int i = 0; i < m.mesh().num_vertices(); ++i) {
      const double u = m.mesh().uv[i][axis];
      q[3 * i + axis] = std::sin(kappa * u) / kappa;
      q[3 * i + 2] = 0.1 + (1 - std::cos(kappa * u)) / kappa;
    }
    const double k = axis == 0 ? 2e-6 : 5e-7;
    const int folds = axis == 0 ? (na - 2) * (nb - 1) : (nb - 2) * (na - 1);  // interior edges along v (resp. u)
    const double expect = folds * 0.5 * k * (kappa * L) * (kappa * L);
    EXPECT_NEAR(m.potential_energy(q), expect, 1e-9 * expect) << "axis " << axis;
  }
}

TEST(FemModel, MassIsArealDensityTimesArea) {
  Scene s = test::fem_scene(5, 4);
  FemModel m(s);
  Evaluation ev;
  allocate_evaluation(m, ev);
  m.evaluate(0.0, m.initial_q(), m.initial_v(), kMass, ev);
  const double area = 4e-3 * 3e-3;
  const double rho_a = (0.002 + 0.002) / 1e-3;  // default yarn density 0.002 kg/m, L = 1 mm
  Vec ones = Vec::Zero(m.num_dofs());
  for (int i = 0; i < m.mesh().num_vertices(); ++i) ones[3 * i] = 1.0;
  EXPECT_NEAR(ones.dot(ev.mass * ones), rho_a * area, 1e-15);
  EXPECT_FALSE(m.mass_depends_on_q());
}

// [fem] yarn_node_mass: the total stays ρ_A·A, shared in the proportions of the
// yarn level's own lumped node masses (two yarn types, so warps and wefts differ;
// the border carries 3/4 and the corners 1/2 of an interior crossing's yarn, where
// a third of each triangle gives them 1/2 and 1/4). The yarn level's masses are read
// from its assembled mass matrix (sliding frozen: 3 DoFs per node), row by row.
TEST(FemModel, YarnNodeMassFollowsTheYarnLevelsNodeMasses) {
  Scene s = test::fem_scene(5, 4);
  s.yarn_types["heavy"] = YarnType{0.005, 5e5, 1.4e-4};
  s.warp_yarn_types = {"default", "heavy"};
  s.weft_yarn_types = {"heavy", "default", "default"};
  s.sliding = false;
  s.gravity_m_per_s2 = {0, 0, -9.81};
  const std::vector<double> expected = yarn_node_masses(s);
  {
    auto yarn = make_model(s, "yarn");
    Evaluation ev;
    allocate_evaluation(*yarn, ev);
    yarn->evaluate(0.0, yarn->initial_q(), yarn->initial_v(), kMass, ev);
    ASSERT_EQ(yarn->num_dofs(), 3 * static_cast<int>(expected.size()));
    const Vec rows = ev.mass * Vec::Ones(yarn->num_dofs());
    for (size_t n = 0; n < expected.size(); ++n) EXPECT_NEAR(rows[3 * n], expected[n], 1e-15) << "node " << n;
  }
  s.fem.yarn_node_mass = true;
  FemModel m(s);
  const double area = 4e-3 * 3e-3, total = m.material().areal_density_kg_per_m2 * area;
  double yarn_total = 0;
  for (double x : expected) yarn_total += x;
  const std::vector<double>& mass = m.vertex_mass();
  const Vec f = force(m, m.initial_q());
  double sum = 0;
  for (size_t n = 0; n < mass.size(); ++n) {
    EXPECT_NEAR(mass[n], total * expected[n] / yarn_total, 1e-15) << "vertex " << n;
    EXPECT_NEAR(f[3 * n + 2], -9.81 * mass[n], 1e-14) << "gravity at vertex " << n;
    sum += mass[n];
  }
  EXPECT_NEAR(sum, total, 1e-15);
  EXPECT_NEAR(mass[0] / mass[6], 0.5, 1e-12);  // corner (0, 0) against interior (1, 1): same yarns, half
}

TEST(FemModel, GravityPullsWithTotalMass) {
  Scene s = test::fem_scene(4, 4);
  s.gravity_m_per_s2 = {0, 0, -9.81};
  FemModel m(s);
  const Vec f = force(m, m.initial_q());
  double fz = 0;
  for (int i = 0; i < m.mesh().num_vertices(); ++i) fz += f[3 * i + 2];
  EXPECT_NEAR(fz, -9.81 * m.material().areal_density_kg_per_m2 * 9e-6, 1e-12);
}

TEST(FemModel, PinsAndHandlesMapToVerticesAtTheirMaterialPoints) {
  Scene s = test::fem_scene(5, 5, Scene::Pose::upright);
  s.fem.stride = 2;
  s.pins = {{0, 0}, {4, 0}};
  s.handles = {{{2, 4}, 100.0}};
  FemModel m(s);
  EXPECT_EQ(m.vertex_of_node({4, 0}), m.mesh().grid_vertex(2, 0));
  EXPECT_EQ(m.vertex_of_node({2, 4}), m.mesh().grid_vertex(1, 2));
  const auto fixed = m.fixed_dofs();
  EXPECT_EQ(fixed.size(), 6u);
  // the handle pulls its vertex back to its rest position
  Vec q = m.initial_q();
  const int hv = m.mesh().grid_vertex(1, 2);
  q[3 * hv + 1] += 1e-3;
  s.terms.stretch = s.terms.shear = s.terms.bending = false;
  FemModel handles_only(s);
  EXPECT_NEAR(force(handles_only, q)[3 * hv + 1], -100.0 * 1e-3, 1e-12);
  EXPECT_THROW(m.vertex_of_node({1, 1}), std::invalid_argument);  // not on the stride lattice
}

TEST(FemModel, WindPushesDownwind) {
  Scene s = test::fem_scene(4, 4, Scene::Pose::upright);  // cloth in xz, normal along y
  s.wind_velocity_m_per_s = {0, 5, 0};
  s.air_density_kg_per_m3 = 2.0;
  s.wind_drag_Ns_per_m3 = 0.5;
  s.terms.wind = true;
  FemModel m(s);
  const Vec f = force(m, m.initial_q());
  double fy = 0;
  for (int i = 0; i < m.mesh().num_vertices(); ++i) fy += f[3 * i + 1];
  EXPECT_NEAR(fy, 2.0 * 9e-6 * 25.0, 1e-12);  // ρ_w a v_n², a = total area
}

TEST(FemModel, FrameCarriesMeshAndData) {
  Scene s = test::fem_scene(4, 3, Scene::Pose::upright);
  FemModel m(s);
  Vec v = Vec::LinSpaced(m.num_dofs(), 0, 1);
  const Frame f = m.frame(0.25, m.initial_q(), v);
  EXPECT_EQ(f.time, 0.25);
  EXPECT_EQ(f.points.rows(), 12);
  ASSERT_EQ(f.cells.size(), 1u);
  EXPECT_EQ(f.cells[0].type, CellType::triangle);
  EXPECT_EQ(f.cells[0].size(), 12);
  ASSERT_EQ(f.point_data.size(), 2u);
  EXPECT_EQ(f.point_data[0].name, "velocity");
  EXPECT_EQ(f.point_data[0].values[5], v[5]);
  EXPECT_EQ(f.point_data[1].name, "uv");
  EXPECT_EQ(f.point_data[1].components, 2);
  EXPECT_DOUBLE_EQ(f.point_data[1].values[2 * 5], 1e-3);  // vertex 5 = (1, 1)
  for (const auto& c : f.cell_data) EXPECT_EQ(c.values.size(), 12u) << c.name;
  for (double x : f.cell_data[0].values) EXPECT_EQ(x, 0.0);  // rest: no tension
  const auto d = m.describe();
  EXPECT_EQ(d.at("vertices"), "12");
  EXPECT_EQ(d.at("triangles"), "12");
  EXPECT_EQ(d.at("dofs"), "36");
  EXPECT_NE(d.at("terms").find("fem-stretch"), std::string::npos);
  EXPECT_EQ(m.name(), "fem");
}

TEST(FemModel, SurfacePointInterpolatesTriangles) {
  Scene s = test::fem_scene(3, 3, Scene::Pose::upright);
  FemModel m(s);
  Vec3 x;
  ASSERT_TRUE(m.surface_point(m.initial_q(), Vec2(0.7e-3, 1.2e-3), &x));
  EXPECT_NEAR((x - pose_position(s, 0.7e-3, 1.2e-3)).norm(), 0.0, 1e-15);
  EXPECT_FALSE(m.surface_point(m.initial_q(), Vec2(3e-3, 0), &x));
}

void run_hanging(BackwardEuler::Variant variant) {
  Scene s = test::fem_scene(7, 7, Scene::Pose::upright);
  s.gravity_m_per_s2 = {0, 0, -9.81};
  s.wind_velocity_m_per_s = {0, 3, 0};
  s.air_density_kg_per_m3 = 1.2;
  s.wind_drag_Ns_per_m3 = 0.5;
  s.terms.wind = true;
  s.pins = {{0, 0}, {6, 0}};  // top corners (upright: j = 0 is the top row)
  FemModel m(s);
  BackwardEuler be(variant);
  IntegratorOptions opt;
  opt.dt = 1e-3;
  be.initialize(m, 0.0, m.initial_q(), m.initial_v(), opt);
  const StepResult r = be.advance_to(0.02);
  ASSERT_EQ(r.outcome, Outcome::ok) << r.message;
  EXPECT_TRUE(be.q().allFinite());
  const int bottom = m.mesh().grid_vertex(3, 6);
  EXPECT_LT(be.q()[3 * bottom + 2], m.initial_q()[3 * bottom + 2]);  // falls
  EXPECT_GT(be.q()[3 * bottom + 1], 0.0);                            // downwind
  for (int d : m.fixed_dofs()) EXPECT_EQ(be.q()[d], m.initial_q()[d]);
}

TEST(FemModelIntegration, BackwardEulerLinearRunsHangingSheet) { run_hanging(BackwardEuler::Variant::linear); }
TEST(FemModelIntegration, BackwardEulerNewtonRunsHangingSheet) { run_hanging(BackwardEuler::Variant::newton); }

}  // namespace
}  // namespace wl

namespace wl {
namespace {

// The published scene as the default experiment runs it: 500 steps of be-linear,
// no NaN, swings downwind, carries tension.
TEST(FemModelIntegration, HangingWindSceneRunsItsSteps) {
  const Scene s = load_scene(std::string(WEAVELAB_SOURCE_DIR) + "/experiments/scenes/hanging_wind.toml");
  FemModel m(s);
  BackwardEuler be(BackwardEuler::Variant::linear);
  IntegratorOptions opt;
  opt.dt = s.dt_s;
  be.initialize(m, 0.0, m.initial_q(), m.initial_v(), opt);
  const StepResult r = be.advance_to(s.duration_s);
  ASSERT_EQ(r.outcome, Outcome::ok) << r.message;
  EXPECT_EQ(be.stats().steps, 500);
  EXPECT_TRUE(be.q().allFinite() && be.v().allFinite());
  double mean_y = 0.0;
  for (int i = 0; i < m.mesh().num_vertices(); ++i) mean_y += be.q()[3 * i + 1] / m.mesh().num_vertices();
  EXPECT_GT(mean_y, 1e-3);  // wind along +y
  const Frame f = m.frame(be.t(), be.q(), be.v());
  double max_tension = 0.0;
  for (double x : f.cell_data[0].values) max_tension = std::max(max_tension, x);
  EXPECT_GT(max_tension, 0.0);
}

}  // namespace
}  // namespace wl
