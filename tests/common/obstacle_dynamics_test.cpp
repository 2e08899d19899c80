// Obstacle contact in time (docs/models.md §3.11, docs/design.md §3.6): a node
// dropped on a floor rests at the barrier's equilibrium without bouncing out of
// the contact zone; a block on an incline sticks below tan θ = μ and slides with
// a = g (sin θ − μ cos θ) above it; a cloth dropped on a sphere keeps every
// node outside at every step (both models), on the sphere and on its mesh;
// a node rests on a mesh floor and never tunnels through it; integrators that cannot honour
// admissible states refuse the model.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <numbers>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>

#include "integrators/integrator.h"
#include "models/common/handle_spring.h"
#include "models/common/obstacle_barrier.h"
#include "models/common/obstacle_contact.h"
#include "models/core/term_model.h"
#include "models/fem/terms/nodal_gravity.h"
#include "models/model_factory.h"
#include "tests/support/node_mass.h"
#include "tests/support/obstacle_meshes.h"

namespace wl {
namespace {

constexpr double kMass = 1e-3, kG = 9.81, kDhat = 1e-3, kKappa = 50.0;

// One node of mass m under gravity among the scene's obstacles.
class NodeModel : public TermModel {
 public:
  // spring_k > 0: a spring of that stiffness [N/m] pulls the node to the origin.
  NodeModel(const Scene& scene, const Vec3& x0, const Vec3& v0, double spring_k = 0.0) {
    num_dofs_ = 3;
    q0_ = x0;
    v0_ = v0;
    terms_.push_back(std::make_unique<test::NodeMassTerm>(1, kMass));
    auto g = std::make_unique<NodalGravityTerm>(Vec3(0, 0, -kG));
    g->add({0, 1, 2}, kMass);
    terms_.push_back(std::move(g));
    if (spring_k > 0.0) {
      auto spring = std::make_unique<HandleSpringTerm>();
      spring->add({0, 1, 2}, Vec3::Zero(), spring_k);
      terms_.push_back(std::move(spring));
    }
    contact_ =
        ObstacleContact(scene, {kDhat, kKappa, scene.obstacle_contact.friction_speed_m_per_s}, {0}, {}, q0_, terms_);
    finalize();
  }
  std::unique_ptr<Model> clone() const override { return std::make_unique<NodeModel>(*this); }
  std::string name() const override { return "node"; }
  bool mass_depends_on_q() const override { return false; }
  Frame frame(double t, const Vec& q, const Vec&) const override {
    Frame f;
    f.time = t;
    f.points.resize(1, 3);
    f.points.row(0) = q.transpose();
    return f;
  }
  std::map<std::string, std::string> describe() const override { return {}; }

 private:
  ObstacleContact contact_;
};

Scene plane_scene(double tilt_deg, double mu) {
  Scene s;
  ObstacleSpec p;
  p.shape = ObstacleSpec::Shape::plane;
  p.rotation_deg = {tilt_deg, 0.0, 0.0};
  p.friction_coefficient = mu;
  s.obstacles.push_back(p);
  return s;
}

// −b'(d) κ = m g cos θ: the distance where the barrier holds the node.
double rest_distance(double load) {
  double lo = 1e-12, hi = kDhat;
  for (int k = 0; k < 200; ++k) {
    const double mid = 0.5 * (lo + hi);
    (-kKappa * contact_barrier(mid, kDhat).db > load ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

// The barrier is elastic (no restitution term): a node may rebound up to its drop
// height but never above it. Backward Euler's numerical damping settles it within
// the run at the barrier's equilibrium; second-order sdirk2 hardly damps the
// barrier's oscillation, so it is held to the energy bound only.
class DropOnPlane : public ::testing::TestWithParam<std::string> {};

TEST_P(DropOnPlane, RestsOnItWithoutPenetrationOrBounce) {
  const Scene scene = plane_scene(0.0, 0.0);
  const double z0 = 0.01;
  NodeModel model(scene, Vec3(0, 0, z0), Vec3::Zero());
  auto integ = make_integrator(GetParam());
  IntegratorOptions opt;
  opt.dt = 1e-3;
  integ->initialize(model, 0.0, model.initial_q(), model.initial_v(), opt);
  double lowest = 1.0, highest_after_contact = 0.0;
  bool touched = false;
  integ->on_step = [&](const StepRecord&) {
    const double z = integ->q().z();
    lowest = std::min(lowest, z);
    touched = touched || z < kDhat;
    if (touched) highest_after_contact = std::max(highest_after_contact, z);
  };
  const StepResult r = integ->advance_to(0.5);
  ASSERT_EQ(r.outcome, Outcome::ok) << r.message;
  EXPECT_TRUE(touched);
  EXPECT_GT(lowest, 0.0);                // never inside
  EXPECT_LT(highest_after_contact, z0);  // never above the drop height (no energy gained)
  EXPECT_GE(integ->stats().steps, 500);
  if (GetParam() == "sdirk2") return;
  EXPECT_LT(integ->v().norm(), 1e-4);  // at rest
  const double dstar = rest_distance(kMass * kG);
  EXPECT_NEAR(integ->q().z(), dstar, 1e-3 * dstar);  // where the barrier holds m g
}

INSTANTIATE_TEST_SUITE_P(Integrators, DropOnPlane, ::testing::Values("be-linear", "be-newton", "sdirk2"));

TEST(ObstacleSteps, FastFallIsCaughtByTheStepControl) {
  // 1 m/s down onto the floor from 1.2 mm: 1 ms steps would reach the floor in the second one.
  const Scene scene = plane_scene(0.0, 0.0);
  NodeModel model(scene, Vec3(0, 0, 0.0012), Vec3(0, 0, -1.0));
  for (const char* name : {"be-linear", "be-newton", "sdirk2"}) {
    auto integ = make_integrator(name);
    IntegratorOptions opt;
    opt.dt = 1e-3;
    auto m = model.clone();
    integ->initialize(*m, 0.0, m->initial_q(), m->initial_v(), opt);
    double lowest = 1.0;
    integ->on_step = [&](const StepRecord&) { lowest = std::min(lowest, integ->q().z()); };
    const StepResult r = integ->advance_to(0.05);
    ASSERT_EQ(r.outcome, Outcome::ok) << name << ": " << r.message << " t=" << integ->t();
    EXPECT_GT(lowest, 0.0) << name;
    EXPECT_GT(integ->stats().rejected_steps, 0) << name << ": the 1 ms step was never retaken";
  }
}

// A floor as a two-sided mesh: a square of two triangles (docs/models.md §3.11.9).
Scene mesh_floor_scene() {
  Scene s;
  const auto dir = test::temp_folder();
  test::write_obj(dir / "floor.obj", test::square_mesh(0.05));
  s.obstacles.push_back(test::mesh_obstacle(dir / "floor.obj", ObstacleSpec::Side::both));
  return s;
}

// Dropped from 10 mm on the mesh floor, the node rests where the barrier holds
// its weight, as on the analytic plane.
TEST(MeshObstacle, NodeDroppedOnAMeshFloorRestsOnIt) {
  const Scene scene = mesh_floor_scene();
  for (const char* name : {"be-linear", "be-newton"}) {
    NodeModel model(scene, Vec3(0.001, 0.002, 0.01), Vec3::Zero());
    auto integ = make_integrator(name);
    IntegratorOptions opt;
    opt.dt = 1e-3;
    integ->initialize(model, 0.0, model.initial_q(), model.initial_v(), opt);
    double lowest = 1.0;
    integ->on_step = [&](const StepRecord&) { lowest = std::min(lowest, integ->q().z()); };
    const StepResult r = integ->advance_to(0.5);
    ASSERT_EQ(r.outcome, Outcome::ok) << name << ": " << r.message;
    EXPECT_GT(lowest, 0.0) << name;
    EXPECT_LT(integ->v().norm(), 1e-4) << name;
    const double dstar = rest_distance(kMass * kG);
    EXPECT_NEAR(integ->q().z(), dstar, 1e-3 * dstar) << name;
  }
}

// At 1 m/s down onto a two-sided mesh floor from 1.2 mm: a 1 ms step would reach
// the sheet in the second step and a 5 ms step would carry the node 3.8 mm
// through it in the first, to a point as far from the sheet on its other side,
// which the node's distance alone cannot tell from an admissible state. The
// conservative step fraction retakes such steps; the node never ends one below
// the sheet.
TEST(MeshObstacle, AFastNodeNeverEndsAStepThroughAThinSheet) {
  const Scene scene = mesh_floor_scene();
  for (double dt : {1e-3, 5e-3})
    for (const char* name : {"be-linear", "be-newton", "sdirk2"}) {
      NodeModel model(scene, Vec3(0.001, 0.002, 0.0012), Vec3(0, 0, -1.0));
      auto integ = make_integrator(name);
      IntegratorOptions opt;
      opt.dt = dt;
      integ->initialize(model, 0.0, model.initial_q(), model.initial_v(), opt);
      double lowest = 1.0;
      integ->on_step = [&](const StepRecord&) { lowest = std::min(lowest, integ->q().z()); };
      const StepResult r = integ->advance_to(0.02);
      ASSERT_EQ(r.outcome, Outcome::ok) << name << " at dt = " << dt << ": " << r.message;
      EXPECT_GT(lowest, 0.0) << name << " at dt = " << dt;
      EXPECT_GT(integ->stats().rejected_steps, 0) << name << ": the step was never retaken";
    }
}

TEST(ObstacleSteps, AdaptiveSdirk2KeepsTheNodeOutside) {
  const Scene scene = plane_scene(0.0, 0.0);
  NodeModel model(scene, Vec3(0, 0, 0.0012), Vec3(0, 0, -1.0));
  auto integ = make_integrator("sdirk2");
  IntegratorOptions opt;
  opt.dt = 1e-3;
  opt.adaptive = true;
  opt.rtol = 1e-4;
  opt.atol = 1e-7;
  integ->initialize(model, 0.0, model.initial_q(), model.initial_v(), opt);
  double lowest = 1.0;
  integ->on_step = [&](const StepRecord&) { lowest = std::min(lowest, integ->q().z()); };
  const StepResult r = integ->advance_to(0.05);
  ASSERT_EQ(r.outcome, Outcome::ok) << r.message;
  EXPECT_GT(lowest, 0.0);
}

TEST(ObstacleSteps, MethodsWithoutAdmissibleStepsRefuseTheModel) {
  const Scene scene = plane_scene(0.0, 0.0);
  for (const std::string& name : integrator_names()) {
    auto integ = make_integrator(name);
    NodeModel model(scene, Vec3(0, 0, 0.01), Vec3::Zero());
    integ->initialize(model, 0.0, model.initial_q(), model.initial_v(), IntegratorOptions{});
    const StepResult r = integ->advance_to(0.002);
    if (integ->capabilities().admissible_steps) {
      EXPECT_EQ(r.outcome, Outcome::ok) << name << ": " << r.message;
    } else {
      EXPECT_EQ(r.outcome, Outcome::not_offered) << name;
      EXPECT_NE(r.message.find("not offered"), std::string::npos) << r.message;
    }
  }
}

// A node on a plane tilted by θ about x with μ = 0.5 (tan θ_c = 0.5), started
// at the barrier's rest distance: below θ_c it creeps at the speed where the
// smoothed law balances the weight, f₁(y) = tan θ/μ, y = ε (1 − √(1 − tan θ/μ)) < ε
// (§3.11.3); above it slides with a = g (sin θ − μ cos θ).
TEST(BlockOnIncline, SticksBelowTanThetaEqualsMuAndSlidesAbove) {
  const double mu = 0.5, theta_c = std::atan(mu);
  for (double factor : {0.8, 1.2}) {
    const double theta = factor * theta_c, deg = theta * 180.0 / std::numbers::pi;
    const Scene scene = plane_scene(deg, mu);
    const double eps = scene.obstacle_contact.friction_speed_m_per_s;
    const Vec3 n(0, -std::sin(theta), std::cos(theta)), down(0, -std::cos(theta), -std::sin(theta));
    NodeModel model(scene, rest_distance(kMass * kG * std::cos(theta)) * n, Vec3::Zero());
    auto integ = make_integrator("be-newton");
    IntegratorOptions opt;
    opt.dt = 1e-3;
    integ->initialize(model, 0.0, model.initial_q(), model.initial_v(), opt);
    ASSERT_EQ(integ->advance_to(0.2).outcome, Outcome::ok);
    const double s1 = integ->q().dot(down), v1 = integ->v().dot(down);
    ASSERT_EQ(integ->advance_to(0.4).outcome, Outcome::ok);
    const double s2 = integ->q().dot(down), v2 = integ->v().dot(down);
    EXPECT_GT(integ->q().dot(n), 0.0);
    if (factor < 1.0) {
      const double creep = eps * (1.0 - std::sqrt(1.0 - std::tan(theta) / mu));
      EXPECT_LT((s2 - s1) / 0.2, 1.05 * creep) << "θ = " << deg << "°: slid";
      EXPECT_LT(std::abs(v2), 1.05 * creep);
    } else {
      const double a = kG * (std::sin(theta) - mu * std::cos(theta));
      EXPECT_NEAR((v2 - v1) / 0.2, a, 0.02 * a) << "θ = " << deg << "°";
      EXPECT_GT(s2 - s1, 0.5 * a * 0.2 * 0.2);
    }
  }
}

// A node on a floor with friction, pulled sideways by a spring 4× stronger than
// μ m g: it slides, turns back, and comes to rest where friction holds the
// spring. Every term but friction is conservative and convex here (spring,
// gravity, the barrier of a plane), so backward Euler's step dissipates them;
// friction must dissipate too: the total energy may not rise in any step, in
// the slide, at the turns or at rest (docs/models.md §3.11.3). With 5 ms steps
// (the drapes' settling steps) a friction linearized at the start of a step
// pushes on past a turn.
TEST(FrictionOnAFloor, NoStepGainsEnergyInSlidingTurningOrAtRest) {
  const double mu = 0.5, k = 1.0, x0 = 4.0 * mu * kMass * kG / k;
  const Scene scene = plane_scene(0.0, mu);
  const double z0 = rest_distance(kMass * kG);
  for (const char* name : {"be-linear", "be-newton"}) {
    NodeModel model(scene, Vec3(x0, 0.3 * x0, z0), Vec3::Zero(), k);
    auto integ = make_integrator(name);
    IntegratorOptions opt;
    opt.dt = 5e-3;
    integ->initialize(model, 0.0, model.initial_q(), model.initial_v(), opt);
    auto energy = [&] { return 0.5 * kMass * integ->v().squaredNorm() + model.potential_energy(integ->q()); };
    const double e0 = energy();
    double e = e0, rise = 0.0;
    int turns = 0;
    double vx = 0.0;
    integ->on_step = [&](const StepRecord&) {
      const double now = energy();
      rise = std::max(rise, now - e);
      e = now;
      if (integ->v().x() * vx < 0.0) ++turns;
      vx = integ->v().x();
    };
    const StepResult r = integ->advance_to(1.0);
    ASSERT_EQ(r.outcome, Outcome::ok) << name << ": " << r.message;
    EXPECT_GE(turns, 1) << name;
    EXPECT_LE(rise, 1e-9 * e0) << name << ": a step gained " << rise << " J";
    // At rest in the stick zone, creeping at most at the speed where f₁ holds the spring.
    const double pull = k * std::hypot(integ->q().x(), integ->q().y()), hold = mu * kMass * kG;
    ASSERT_LT(pull, hold) << name << ": beyond the stick zone";
    const double creep = scene.obstacle_contact.friction_speed_m_per_s * (1.0 - std::sqrt(1.0 - pull / hold));
    EXPECT_LT(integ->v().norm(), 1.05 * creep + 1e-9) << name << ": not at rest";
  }
}

// A 9×9 cloth dropped from 1 mm onto an obstacle under its centre with be-linear
// for 0.06 s: the closest approach of any node after any step (by the
// obstacle's own distance) and the final node positions.
struct ClothDrop {
  double closest = 1.0;
  int steps = 0;
  Eigen::MatrixXd points;
};

ClothDrop drop_cloth(const ObstacleSpec& obstacle, const char* model_name) {
  Scene scene;
  scene.warps = scene.wefts = 9;
  scene.pose = Scene::Pose::flat;
  scene.height_m = 0.001;
  scene.terms.wind = false;
  scene.obstacles.push_back(obstacle);
  const Obstacle o(obstacle);
  auto model = make_model(scene, model_name);
  EXPECT_TRUE(model->constrains_steps());
  auto integ = make_integrator("be-linear");
  IntegratorOptions opt;
  opt.dt = 1e-3;
  integ->initialize(*model, 0.0, model->initial_q(), model->initial_v(), opt);
  ClothDrop out;
  integ->on_step = [&](const StepRecord& s) {
    const Frame f = model->frame(s.t, integ->q(), integ->v());
    for (Eigen::Index k = 0; k < f.points.rows(); ++k)
      out.closest = std::min(out.closest, o.signed_distance(f.points.row(k).transpose(), s.t));
    ++out.steps;
  };
  const StepResult r = integ->advance_to(0.06);
  EXPECT_EQ(r.outcome, Outcome::ok) << model_name << ": " << r.message;
  const Frame f = model->frame(integ->t(), integ->q(), integ->v());
  out.points = f.points;
  const auto it = std::find_if(f.point_data.begin(), f.point_data.end(),
                               [](const DataArray& a) { return a.name == "contact_force"; });
  EXPECT_NE(it, f.point_data.end());
  double up = 0.0;
  for (size_t k = 2; it != f.point_data.end() && k < it->values.size(); k += 3) up += it->values[k];
  EXPECT_GT(up, 0.0) << model_name << ": the obstacle pushes the cloth up";
  return out;
}

ObstacleSpec sphere_under_cloth() {  // radius 3 mm, top at z = 0 under the 9×9 cloth's centre
  ObstacleSpec sphere;
  sphere.shape = ObstacleSpec::Shape::sphere;
  sphere.center_m = {0.004, 0.004, -0.003};
  sphere.radius_m = 0.003;
  sphere.friction_coefficient = 0.3;
  return sphere;
}

// The drop on the sphere and on the shipped icosphere scaled to it (docs/models.md
// §3.11.9), both models: every node outside each after every step, and the
// cloth on the mesh where it lies on the analytic sphere up to the tessellation. The mesh's faces sit up
// to s = r(1 − h_min) = 14 µm inside the sphere (0.45 % of r), which moves a
// resting node at most s towards the centre; the tolerance allows 2 s.
TEST(ClothOnSphere, EveryNodeStaysOutsideTheSphereAndItsMeshAtEveryStep) {
  const ObstacleSpec sphere = sphere_under_cloth();
  ObstacleSpec mesh = test::mesh_obstacle(test::icosphere_file(), ObstacleSpec::Side::outside, sphere.radius_m,
                                          Vec3(sphere.center_m[0], sphere.center_m[1], sphere.center_m[2]));
  mesh.friction_coefficient = sphere.friction_coefficient;
  const double sagitta = 0.004528 * sphere.radius_m;  // r(1 − h_min) of the level-3 icosphere (obstacle_mesh_test)
  for (const char* model_name : {"yarn", "fem"}) {
    const ClothDrop on_mesh = drop_cloth(mesh, model_name), on_sphere = drop_cloth(sphere, model_name);
    for (const ClothDrop* d : {&on_sphere, &on_mesh}) {
      EXPECT_GT(d->closest, 0.0) << model_name;
      EXPECT_LT(d->closest, 0.5e-3) << model_name << ": the cloth never reached the obstacle";
      EXPECT_GE(d->steps, 60) << model_name;
    }
    const double gap = (on_mesh.points - on_sphere.points).rowwise().norm().maxCoeff();
    std::cout << model_name << ": closest approach mesh " << on_mesh.closest << " m, sphere " << on_sphere.closest
              << " m; largest node distance between the two drops " << gap << " m\n";
    EXPECT_LT(gap, 2.0 * sagitta) << model_name;
  }
}

TEST(ClothOnSphere, ANodeStartingInsideIsRejected) {
  ObstacleSpec sphere;
  sphere.shape = ObstacleSpec::Shape::sphere;
  sphere.center_m = {0.004, 0.004, 0.0};
  sphere.radius_m = 0.0025;
  sphere.line = 7;
  Scene scene;
  scene.source = "s.toml";
  scene.warps = scene.wefts = 9;
  scene.pose = Scene::Pose::flat;
  scene.obstacles.push_back(sphere);
  for (const char* m : {"yarn", "fem"}) {
    try {
      make_model(scene, m);
      ADD_FAILURE() << m << ": no error";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("s.toml:7: obstacles[0]"), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("inside"), std::string::npos) << e.what();
    }
  }
}

// A node on the rim of a disk (radius 10 mm, top at z = 1 mm), pulled to the
// disk's centre by a spring and started along the rim at 5 cm/s: it slides
// round the rim. There ∇²d ≈ (I − ∇d∇dᵀ)/d, so the barrier's κ b'∇²d gives
// the exact step matrix M − h²K a negative part of about h² κ b'/d, 2× the
// node's mass at 10 ms steps (docs/models.md §3.11.2).
Scene rim_scene(bool projected) {
  Scene s;
  ObstacleSpec disk;
  disk.shape = ObstacleSpec::Shape::disk;
  disk.radius_m = 0.01;
  disk.height_m = 0.002;
  s.obstacles.push_back(disk);
  s.obstacle_contact.projected_step_hessian = projected;
  return s;
}

const Vec3 kOnRim(0.01 + 0.4e-3, 0.0, 0.001 + 0.4e-3), kAlongRim(0.0, 0.05, 0.0);

// The projected stiffness enters the step matrices only (kStepStiffness,
// evaluate_step); the force and ∂f/∂q stay exact, evaluate_step's one pass
// equals the matrix formed from M, K, D apart, and forward sensitivities
// (which need the exact step) refuse the model.
TEST(ObstacleStepStiffness, OnlyTheStepMatrixTakesTheProjectedBarrierHessian) {
  NodeModel exact(rim_scene(false), kOnRim, kAlongRim, 1.0), projected(rim_scene(true), kOnRim, kAlongRim, 1.0);
  EXPECT_FALSE(exact.projects_step_stiffness());
  EXPECT_TRUE(projected.projects_step_stiffness());
  const Vec q = exact.initial_q(), v = exact.initial_v();
  Evaluation a, b;
  exact.evaluate(0.0, q, v, kForce | kDfdq | kDfdv, a);
  projected.evaluate(0.0, q, v, kForce | kDfdq | kDfdv, b);
  EXPECT_EQ(a.force, b.force);
  EXPECT_EQ(Eigen::MatrixXd(a.dfdq), Eigen::MatrixXd(b.dfdq));  // exact unless asked for a step
  exact.evaluate(0.0, q, v, kForce | kDfdq | kStepStiffness | kDfdv, a);
  projected.evaluate(0.0, q, v, kForce | kDfdq | kStepStiffness | kDfdv | EvalFlags::kMass, b);  // kMass: the node's
  const Eigen::Matrix3d k_exact(a.dfdq), k_step(b.dfdq);
  const Eigen::Vector3d lambda = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(-k_exact).eigenvalues();
  ASSERT_LT(lambda.minCoeff(), -1.0);  // the rim's negative curvature [N/m]
  const Eigen::Vector3d lambda_step = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(-k_step).eigenvalues();
  EXPECT_GE(lambda_step.minCoeff(), -1e-12 * lambda_step.maxCoeff());
  EXPECT_NEAR(lambda_step.maxCoeff(), lambda.maxCoeff(), 1e-12 * lambda.maxCoeff());

  const double h = 0.01;
  const StepWeights w{.mass = 1.0, .dfdv = -h, .dfdq = -h * h, .rhs_dfdq = h, .w = &v};
  SparseMatrix one_pass = projected.pattern(), apart = projected.pattern();
  Vec r_one, r_apart;
  Evaluation scratch;
  projected.evaluate_step(0.0, q, v, w, scratch, one_pass, r_one);
  form_step(b, w, apart, &r_apart);
  EXPECT_LT((Eigen::MatrixXd(one_pass) - Eigen::MatrixXd(apart)).norm(), 1e-15 * Eigen::MatrixXd(apart).norm());
  EXPECT_LT((r_one - r_apart).norm(), 1e-15 * r_apart.norm());
  EXPECT_EQ(Eigen::LLT<Eigen::MatrixXd>(Eigen::MatrixXd(one_pass)).info(), Eigen::Success);

  auto integ = make_integrator("be-linear");
  integ->track_sensitivities({"fem.density_kg_per_m2"});
  try {
    integ->initialize(projected, 0.0, q, v, IntegratorOptions{});
    ADD_FAILURE() << "sensitivities accepted a projected step matrix";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("step_hessian = \"exact\""), std::string::npos) << e.what();
  }
}

// The node pressed onto the rim is at an unstable equilibrium: the spring and
// gravity push it into a convex edge, so it slides off it (the barrier's
// negative curvature about the rim is the physics). With the projected step
// stiffness and 10 ms steps (be-linear, be-newton) it does, stays outside the
// disk, every step matrix is positive definite and no step raises the energy
// T + V. With the exact one (step_hessian = "exact") the step matrix is
// indefinite at 4 of the 50 states; be-linear gains 4·10⁻⁶ J in one step
// (the energy is about 5·10⁻⁵ J) and be-newton holds the node on the rim
// (backward Euler damps an unstable mode whose h²k/m exceeds 2).
TEST(ObstacleStepStiffness, ANodePressedOntoADiskRimSlidesOffWithoutGainingEnergy) {
  for (const char* name : {"be-linear", "be-newton"}) {
    NodeModel model(rim_scene(true), kOnRim, kAlongRim, 1.0);
    const Obstacle disk(rim_scene(true).obstacles[0]);
    auto integ = make_integrator(name);
    IntegratorOptions opt;
    opt.dt = 0.01;
    integ->initialize(model, 0.0, model.initial_q(), model.initial_v(), opt);
    auto energy = [&] { return 0.5 * kMass * integ->v().squaredNorm() + model.potential_energy(integ->q()); };
    const double e0 = energy();
    double e = e0, rise = 0.0, closest = 1.0, farthest = 0.0;
    int indefinite = 0;
    Evaluation scratch;
    SparseMatrix a = model.pattern();
    Vec r;
    integ->on_step = [&](const StepRecord& s) {
      const double d = disk.signed_distance(integ->q(), s.t);
      closest = std::min(closest, d);
      farthest = std::max(farthest, d);
      const double now = energy();
      rise = std::max(rise, now - e);
      e = now;
      const Vec v = integ->v();
      model.evaluate_step(s.t, integ->q(), v, {.mass = 1.0, .dfdv = -opt.dt, .dfdq = -opt.dt * opt.dt}, scratch, a, r);
      if (Eigen::LLT<Eigen::MatrixXd>(Eigen::MatrixXd(a)).info() != Eigen::Success) ++indefinite;
    };
    const StepResult res = integ->advance_to(0.5);
    ASSERT_EQ(res.outcome, Outcome::ok) << name << ": " << res.message;
    EXPECT_GT(closest, 0.0) << name;
    EXPECT_GT(farthest, 10.0 * kDhat) << name << ": held on the rim";
    EXPECT_EQ(indefinite, 0) << name;
    EXPECT_LE(rise, 1e-12 * std::abs(e0)) << name << ": a step gained " << rise << " J";
  }
}

}  // namespace
}  // namespace wl
