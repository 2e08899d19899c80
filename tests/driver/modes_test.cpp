// The modal comparison (driver/modes.h, docs/models.md §10): the
// linearization about the hanging equilibrium predicts the free vibration of
// the nonlinear model; each model's modes against themselves have MAC 1 on the
// diagonal; on a small cloth the yarn level's lowest modes find continuum
// partners of the same shape.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "driver/modes.h"
#include "integrators/integrator.h"
#include "models/model_factory.h"
#include "models/scene/scene.h"
#include "tests/support/test_scenes.h"

namespace wl {
namespace {

Scene small_cloth(int n) { return modal_scene(parse_scene(test::hanging_cloth_toml(n, 0.1), "test.toml")); }

LinearizedModes modes_of(const Scene& scene, const std::string& name, int count) {
  std::unique_ptr<Model> model = make_model(scene, name);
  ModalOptions o;
  o.count = count;
  return linearized_modes(*model, compared_crossings(scene), o);
}

// Released from q* + a φ₀ at rest, the continuum swings with the lowest mode's
// period 2π/ω₀: the modal coordinate φ₀ᵀM(q − q*) crosses zero every half period.
TEST(Modes, TheLowestModePredictsTheFreeVibrationOfTheContinuum) {
  const Scene scene = small_cloth(5);
  const LinearizedModes lm = modes_of(scene, "fem", 3);
  ASSERT_TRUE(lm.equilibrium.converged) << lm.equilibrium.message;
  ASSERT_TRUE(lm.modes.ok) << lm.modes.message;
  ASSERT_GT(lm.modes.eigenvalues[0], 0.0);
  const double period = 2 * std::numbers::pi / std::sqrt(lm.modes.eigenvalues[0]);
  const Vec phi = lm.modes.shapes.col(0);
  std::unique_ptr<Model> model = make_model(scene, "fem");
  Evaluation e;
  allocate_evaluation(*model, e);
  model->evaluate(0.0, lm.q, Vec::Zero(model->num_dofs()), kMass, e);
  const Vec m_phi = e.mass * phi;
  const double amplitude = 2e-6 / phi.cwiseAbs().maxCoeff();  // 2 µm at the largest DoF
  auto integrator = make_integrator("sdirk2");
  IntegratorOptions o;
  o.adaptive = true;
  o.rtol = 1e-7;
  o.atol = 1e-12;
  o.dt = period / 200;
  integrator->initialize(*model, 0.0, lm.q + amplitude * phi, Vec::Zero(model->num_dofs()), o);
  std::vector<double> crossings;
  double last = amplitude, t_last = 0;
  const int samples = 120;
  for (int s = 1; s <= samples; ++s) {
    const double t = 2.6 * period * s / samples;
    ASSERT_EQ(integrator->advance_to(t).outcome, Outcome::ok);
    const double a = m_phi.dot(integrator->q() - lm.q);
    if ((a < 0) != (last < 0)) crossings.push_back(t_last + (t - t_last) * last / (last - a));
    last = a, t_last = t;
  }
  ASSERT_GE(crossings.size(), 4u);
  const double measured = 2 * (crossings.back() - crossings.front()) / double(crossings.size() - 1);
  EXPECT_NEAR(measured / period, 1.0, 5e-3) << "linearized " << period << " s, simulated " << measured << " s";
}

TEST(Modes, ShapesAgainstThemselvesAreTheIdentityOnTheDiagonalAndPairInOrder) {
  const Scene scene = small_cloth(5);
  for (const char* name : {"yarn", "fem"}) {
    SCOPED_TRACE(name);
    const LinearizedModes lm = modes_of(scene, name, 6);
    ASSERT_TRUE(lm.modes.ok) << lm.equilibrium.message << lm.modes.message;
    const Eigen::MatrixXd mac = mac_matrix(lm.crossing_shapes, lm.crossing_shapes);
    for (int k = 0; k < 6; ++k) EXPECT_NEAR(mac(k, k), 1.0, 1e-12);
    for (const ModePair& p : match_modes(mac)) EXPECT_EQ(p.a, p.b);
  }
}

// The K of the linearization against central differences of the full force
// (frozen contact forces recomputed): exact for the continuum (a Hessian, up
// to the differences' own error); for the yarn level off by the frozen part
// only (docs/models.md §5.4: 1e-5 to 2e-4 of its blocks), which also makes
// the exact K slightly non-symmetric. Neither moves the lowest frequency.
TEST(Modes, TheLinearizedStiffnessIsTheForcesDerivative) {
  const Scene scene = small_cloth(5);
  for (const char* name : {"yarn", "fem"}) {
    SCOPED_TRACE(name);
    std::unique_ptr<Model> model = make_model(scene, name);
    ModalOptions o;
    o.count = 3;
    const LinearizedModes lm = linearized_modes(*model, compared_crossings(scene), o, 0.0, true);
    ASSERT_TRUE(lm.modes.ok) << lm.equilibrium.message << lm.modes.message;
    ASSERT_EQ(lm.fd.eigenvalues.size(), 3u);
    EXPECT_LT(lm.asymmetry, 1e-12);  // the assembled K is symmetric at rest
    if (std::string(name) == "fem") {
      EXPECT_LT(lm.fd.difference, 1e-8);
      EXPECT_LT(lm.fd.asymmetry, 1e-8);
    } else {
      EXPECT_GT(lm.fd.difference, 1e-7);  // the frozen part is there, and small
      EXPECT_LT(lm.fd.difference, 1e-3);
      EXPECT_GT(lm.fd.asymmetry, 1e-7);
      EXPECT_LT(lm.fd.asymmetry, 1e-3);
    }
    EXPECT_NEAR(lm.fd.eigenvalues[0] / lm.modes.eigenvalues[0], 1.0, 1e-4);
  }
}

// Share of a shape's squared amplitude that lies out of the cloth's plane (y).
double out_of_plane(const Eigen::VectorXd& shape) {
  double y = 0;
  for (Eigen::Index c = 1; c < shape.size(); c += 3) y += shape[c] * shape[c];
  return y / shape.squaredNorm();
}

// On a 7×7 cloth the yarn level and the first-guess continuum hang in the
// plane of the cloth, so each mode is out of plane or in plane (no coupling:
// MAC 0 between the kinds). Their lowest mode of each kind has one shape:
// - the lowest in-plane modes pair with MAC ≥ 0.99 (measured 0.9994): a
//   membrane mode both models discretize alike; a permuted crossing or a wrong
//   DoF map would break it;
// - the lowest out-of-plane modes (the sway about the held corners) pair with
//   MAC ≥ 0.6 (measured 0.72): at this size bending is as strong as the hang's
//   tension over one spacing, and the continuum's diagonal hinges charge folds
//   along a diagonal that the yarn level resists only through its yarns' bending
//   and shear (docs/models.md §10.4), so even the first sway differs; its
//   frequency ratio is 1.39.
TEST(Modes, YarnLevelAndContinuumLowestModesPairUpOnASmallCloth) {
  const Scene scene = small_cloth(7);
  const LinearizedModes yarn = modes_of(scene, "yarn", 10), fem = modes_of(scene, "fem", 10);
  for (const LinearizedModes* lm : {&yarn, &fem}) {
    SCOPED_TRACE(lm->model);
    ASSERT_TRUE(lm->equilibrium.converged) << lm->equilibrium.message;
    ASSERT_TRUE(lm->modes.ok) << lm->modes.message;
    EXPECT_LT(lm->equilibrium.residual, 1e-12);
    EXPECT_GT(lm->modes.eigenvalues[0], 0.0);  // a stable equilibrium
  }
  EXPECT_LT(fem.asymmetry, 1e-12);  // a conservative model: K is a Hessian
  const Eigen::MatrixXd mac = mac_matrix(yarn.crossing_shapes, fem.crossing_shapes);
  int lowest_in[2] = {-1, -1}, lowest_out[2] = {-1, -1};
  for (int side = 0; side < 2; ++side) {
    const Eigen::MatrixXd& shapes = side == 0 ? yarn.crossing_shapes : fem.crossing_shapes;
    for (int k = static_cast<int>(shapes.cols()) - 1; k >= 0; --k) {
      const double y = out_of_plane(shapes.col(k));
      ASSERT_TRUE(y > 1 - 1e-9 || y < 1e-9) << "mode " << k << " is " << y << " out of plane";
      (y > 0.5 ? lowest_out : lowest_in)[side] = k;
    }
  }
  ASSERT_GE(lowest_in[0], 0);
  ASSERT_GE(lowest_in[1], 0);
  for (int a = 0; a < mac.rows(); ++a) {
    for (int b = 0; b < mac.cols(); ++b) {
      if ((out_of_plane(yarn.crossing_shapes.col(a)) > 0.5) != (out_of_plane(fem.crossing_shapes.col(b)) > 0.5)) {
        EXPECT_LT(mac(a, b), 1e-12) << a << " " << b;
      }
    }
  }
  EXPECT_GE(mac(lowest_in[0], lowest_in[1]), 0.99);
  EXPECT_GE(mac(lowest_out[0], lowest_out[1]), 0.6);
  const std::vector<ModePair> pairs = match_modes(mac);
  EXPECT_EQ(pairs[lowest_out[0]].b, lowest_out[1]);  // the sways pair with each other
  EXPECT_EQ(pairs[lowest_in[0]].b, lowest_in[1]);
}

}  // namespace
}  // namespace wl
