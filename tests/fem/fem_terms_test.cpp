// Finite-difference checks of every FEM term (tests/support/fd_check.h) at
// states near and far from rest, plus per-term properties.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include <Eigen/Geometry>

#include "models/fem/deformation_gradient.h"
#include "models/fem/fem_material.h"
#include "models/fem/terms/border_stretch.h"
#include "models/fem/terms/grid_line_bending.h"
#include "models/fem/terms/hinge_bending.h"
#include "models/fem/terms/in_plane_shear.h"
#include "models/fem/terms/lumped_mass.h"
#include "models/fem/terms/nodal_gravity.h"
#include "models/fem/terms/warp_weft_stretch.h"
#include "tests/support/fd_check.h"

namespace wl {
namespace {

// A general (not right-angled) UV triangle, in metres.
const Vec2 kUv0(0.001, 0.002), kUv1(0.013, 0.001), kUv2(0.004, 0.011);

// Rest positions: the UV layout placed in 3-D (flat, z = 0.5).
std::vector<double> rest_triangle() {
  return {kUv0.x(), kUv0.y(), 0.5, kUv1.x(), kUv1.y(), 0.5, kUv2.x(), kUv2.y(), 0.5};
}

// States near rest, moderately deformed, far from rest (compressed, stretched, sheared).
std::vector<test::LocalState> triangle_states() {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> d(-1.0, 1.0);
  std::vector<test::LocalState> states;
  for (double amp : {1e-4, 2e-3, 6e-3}) {
    test::LocalState s{rest_triangle(), std::vector<double>(9, 0.0)};
    for (int k = 0; k < 9; ++k) s.q[k] += amp * d(rng);
    states.push_back(s);
  }
  // strongly sheared and stretched
  test::LocalState s{rest_triangle(), std::vector<double>(9, 0.0)};
  s.q[6] += 0.008;
  s.q[3] *= 1.4;
  states.push_back(s);
  return states;
}

std::array<int, 9> iota9() { return {0, 1, 2, 3, 4, 5, 6, 7, 8}; }

TEST(DeformationGradient, ColumnsMatchSeedExample) {
  // Optitex note worked example: u0=(0,0), u1=(1,0), u2=(0,1); p1 = (1.1,0,0) → w_u = (1.1,0,0), w_v = (0,1,0)
  const TriangleRest r = triangle_rest(Vec2(0, 0), Vec2(1, 0), Vec2(0, 1));
  const double q[9] = {0, 0, 0, 1.1, 0, 0, 0, 1, 0};
  EXPECT_NEAR((warp_vector(r, q) - Vec3(1.1, 0, 0)).norm(), 0.0, 1e-15);
  EXPECT_NEAR((weft_vector(r, q) - Vec3(0, 1, 0)).norm(), 0.0, 1e-15);
  EXPECT_DOUBLE_EQ(r.area, 0.5);
}

TEST(DeformationGradient, MapsUvEdgesToCurrentEdges) {
  // F·du_k = dx_k for an arbitrary affine map and a general triangle.
  const TriangleRest r = triangle_rest(kUv0, kUv1, kUv2);
  Eigen::Matrix<double, 3, 2> F;
  F << 1.2, 0.3, -0.1, 0.8, 0.5, 0.2;
  const Vec3 t(0.1, -0.2, 0.3);
  double q[9];
  const Vec2 uv[3] = {kUv0, kUv1, kUv2};
  for (int k = 0; k < 3; ++k) Eigen::Map<Vec3>(q + 3 * k) = F * uv[k] + t;
  EXPECT_NEAR((warp_vector(r, q) - F.col(0)).norm(), 0.0, 1e-12);
  EXPECT_NEAR((weft_vector(r, q) - F.col(1)).norm(), 0.0, 1e-12);
}

TEST(DeformationGradient, RejectsDegenerateAndClockwiseTriangles) {
  EXPECT_THROW(triangle_rest(Vec2(0, 0), Vec2(1, 0), Vec2(2, 0)), std::invalid_argument);
  EXPECT_THROW(triangle_rest(Vec2(0, 0), Vec2(0, 1), Vec2(1, 0)), std::invalid_argument);
}

TEST(WarpWeftStretchTerm, ForcesMatchEnergyGradient) {
  WarpWeftStretchTerm t(120.0, 45.0);
  t.add(iota9(), triangle_rest(kUv0, kUv1, kUv2));
  auto r = test::check_element(t, 0, triangle_states());
  EXPECT_TRUE(r.ok) << r.detail;
}

TEST(WarpWeftStretchTerm, SeparateWarpAndWeftStiffness) {
  // Unit right triangle stretched 10 % along u only: V = A·½k_u·0.01, independent of k_v.
  WarpWeftStretchTerm t(200.0, 1e6);
  t.add(iota9(), triangle_rest(Vec2(0, 0), Vec2(1, 0), Vec2(0, 1)));
  const double q[9] = {0, 0, 0, 1.1, 0, 0, 0, 1, 0};
  EXPECT_NEAR(t.energy(0, q), 0.5 * 0.5 * 200.0 * 0.01, 1e-12);
}

TEST(InPlaneShearTerm, ForcesMatchEnergyGradient) {
  InPlaneShearTerm t(30.0);
  t.add(iota9(), triangle_rest(kUv0, kUv1, kUv2));
  auto r = test::check_element(t, 0, triangle_states());
  EXPECT_TRUE(r.ok) << r.detail;
}

TEST(InPlaneShearTerm, LockingForcesMatchEnergyGradient) {
  for (double m : {0.5, 1.0, 3.0}) {
    InPlaneShearTerm t(30.0, 0.3, m);
    t.add(iota9(), triangle_rest(kUv0, kUv1, kUv2));
    auto r = test::check_element(t, 0, triangle_states());
    EXPECT_TRUE(r.ok) << "m = " << m << "\n" << r.detail;
  }
}

TEST(InPlaneShearTerm, PsiDerivativesAndLockResponse) {
  const double gl = 0.3, m = 2.0, sl = std::sin(gl);
  InPlaneShearTerm t(1.0, gl, m);
  for (double s : {-0.7, -0.1, 0.0, 0.2, 0.5}) {
    double p, dp, ddp, pp, dpp, ddpp, pm, dpm, ddpm;
    const double h = 1e-6;
    t.psi(s, &p, &dp, &ddp);
    t.psi(s + h, &pp, &dpp, &ddpp);
    t.psi(s - h, &pm, &dpm, &ddpm);
    EXPECT_NEAR(dp, (pp - pm) / (2 * h), 1e-6);
    EXPECT_NEAR(ddp, (dpp - dpm) / (2 * h), 1e-5);
    // effective stiffness ψ'/(2s) = 1 + (s/s_l)^{2m}
    if (s != 0.0) {
      EXPECT_NEAR(dp / (2 * s), 1.0 + std::pow(s / sl, 2 * m), 1e-12);
    }
  }
  InPlaneShearTerm off(1.0);
  double p, dp, ddp;
  off.psi(0.9, &p, &dp, &ddp);
  EXPECT_DOUBLE_EQ(p, 0.81);
}

TEST(InPlaneShearTerm, EnergyIsHalfStiffnessShearAngleSquared) {
  // Simple shear by angle γ of the unit right triangle: s = sin γ, V = A·½k sin²γ.
  InPlaneShearTerm t(10.0);
  t.add(iota9(), triangle_rest(Vec2(0, 0), Vec2(1, 0), Vec2(0, 1)));
  const double g = 0.2;
  const double q[9] = {0, 0, 0, 1, 0, 0, std::sin(g), std::cos(g), 0};
  EXPECT_NEAR(t.energy(0, q), 0.5 * 0.5 * 10.0 * std::sin(g) * std::sin(g), 1e-12);
}

// Hinge around the edge x0=(0,0,0) → x1=(0,h,0); wings at x=∓w, lifted to angle θ.
std::vector<double> hinge(double theta, double w = 0.01, double h = 0.012) {
  return {0, 0, 0, 0, h, 0, -w, 0.4 * h, 0, w * std::cos(theta), 0.7 * h, w * std::sin(theta)};
}

std::vector<test::LocalState> hinge_states() {
  std::vector<test::LocalState> states;
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> d(-1.0, 1.0);
  for (double th : {0.0, 0.05, 0.8, 2.6, -1.9}) {
    test::LocalState s{hinge(th), std::vector<double>(12, 0.0)};
    if (th != 0.0)
      for (auto& x : s.q) x += 0.002 * d(rng);
    states.push_back(s);
  }
  return states;
}

std::array<int, 12> iota12() { return {0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11}; }

TEST(HingeBendingTerm, ForcesMatchEnergyGradient) {
  HingeBendingTerm t(2e-5, 7e-6);
  t.add(iota12(), Vec2(0.0, 0.012), 0.5 * 0.012 * 0.02);
  auto r = test::check_element(t, 0, hinge_states(), {.rel_step = 1e-7, .rtol = 2e-5, .floor = 1e-14});
  EXPECT_TRUE(r.ok) << r.detail;
  HingeBendingTerm t2(2e-5, 7e-6);
  t2.add(iota12(), Vec2(0.008, 0.012), 1.3e-4, 0.4);  // nonzero rest angle too
  r = test::check_element(t2, 0, hinge_states(), {.rel_step = 1e-7, .rtol = 2e-5, .floor = 1e-14});
  EXPECT_TRUE(r.ok) << r.detail;
}

TEST(HingeBendingTerm, DiagonalStiffnessForcesMatchEnergyGradient) {
  // The law with the 45° hinges' own stiffness, on a 45° edge and on one in between.
  for (const Vec2& edge : {Vec2(0.012, 0.012), Vec2(0.008, 0.012)}) {
    HingeBendingTerm t(2e-5, 7e-6, 3e-6);
    t.add(iota12(), edge, 1.3e-4, 0.4);
    const auto r = test::check_element(t, 0, hinge_states(), {.rel_step = 1e-7, .rtol = 2e-5, .floor = 1e-14});
    EXPECT_TRUE(r.ok) << r.detail;
  }
}

TEST(HingeBendingTerm, DihedralAngleIsTheFoldAngle) {
  for (double th : {0.0, 0.3, -1.2, 2.5}) {
    const auto q = hinge(th);
    EXPECT_NEAR(std::abs(HingeBendingTerm::dihedral_angle(q.data())), std::abs(th), 1e-12) << th;
  }
}

TEST(HingeBendingTerm, FlatHingeHasNoForce) {
  HingeBendingTerm t(1.0, 1.0);
  t.add(iota12(), Vec2(0.0, 0.012), 1e-4);
  const auto q = hinge(0.0);
  const std::vector<double> v(12, 0.0);
  Eigen::Matrix<double, 12, 1> f = Eigen::Matrix<double, 12, 1>::Zero();
  Eigen::Matrix<double, 12, 12> k = Eigen::Matrix<double, 12, 12>::Zero();
  t.evaluate(0, q.data(), v.data(), {f.data(), k.data()});
  EXPECT_EQ(f.norm(), 0.0);
  EXPECT_TRUE(k.allFinite());
}

TEST(HingeBendingTerm, StiffnessFollowsEdgeDirectionInUv) {
  HingeBendingTerm t(3.0, 1.0);
  EXPECT_DOUBLE_EQ(t.edge_stiffness(Vec2(0, 2)), 3.0);  // along v: crossed by warps
  EXPECT_DOUBLE_EQ(t.edge_stiffness(Vec2(5, 0)), 1.0);  // along u: crossed by wefts
  EXPECT_NEAR(t.edge_stiffness(Vec2(1, 1)), 2.0, 1e-15);
  // With its own diagonal stiffness: the same along u and v, k_diag at 45° either way, and
  // the mean law again when k_diag is the mean.
  HingeBendingTerm d(3.0, 1.0, 0.25);
  EXPECT_NEAR(d.edge_stiffness(Vec2(0, 2)), 3.0, 1e-15);
  EXPECT_NEAR(d.edge_stiffness(Vec2(5, 0)), 1.0, 1e-15);
  EXPECT_NEAR(d.edge_stiffness(Vec2(1, 1)), 0.25, 1e-15);
  EXPECT_NEAR(d.edge_stiffness(Vec2(1, -1)), 0.25, 1e-15);
  HingeBendingTerm mean(3.0, 1.0, 2.0);
  for (const Vec2& e : {Vec2(1, 2), Vec2(3, -1), Vec2(1, 1)})
    EXPECT_NEAR(mean.edge_stiffness(e), t.edge_stiffness(e), 1e-14);
}

// ∂f/∂p of every material parameter through the generic checker (calibration's sensitivities).
TEST(FemTermParameters, StretchDerivativesMatchFiniteDifferences) {
  for (int k = 0; k < 2; ++k) {
    auto make = [&](double p) {
      auto t = std::make_unique<WarpWeftStretchTerm>(k == 0 ? p : 120.0, k == 1 ? p : 45.0);
      t->add(iota9(), triangle_rest(kUv0, kUv1, kUv2));
      return std::unique_ptr<Term>(std::move(t));
    };
    const auto r = test::check_parameter_derivative(make, k == 0 ? 120.0 : 45.0, k, 0, triangle_states());
    EXPECT_TRUE(r.ok) << r.detail;
  }
}

TEST(FemTermParameters, ShearDerivativesMatchFiniteDifferences) {
  const double base[3] = {30.0, 0.3, 2.0};  // k_sh, γ_lock, m
  for (int k = 0; k < 3; ++k) {
    auto make = [&](double p) {
      double v[3] = {base[0], base[1], base[2]};
      v[k] = p;
      auto t = std::make_unique<InPlaneShearTerm>(v[0], v[1], v[2]);
      t->add(iota9(), triangle_rest(kUv0, kUv1, kUv2));
      return std::unique_ptr<Term>(std::move(t));
    };
    const auto r = test::check_parameter_derivative(make, base[k], k, 0, triangle_states());
    EXPECT_TRUE(r.ok) << r.detail;
  }
}

TEST(FemTermParameters, BendingDerivativesMatchFiniteDifferences) {
  for (int k = 0; k < 2; ++k) {
    auto make = [&](double p) {
      auto t = std::make_unique<HingeBendingTerm>(k == 0 ? p : 2e-5, k == 1 ? p : 7e-6);
      t->add(iota12(), Vec2(0.008, 0.012), 1.3e-4, 0.4);  // a diagonal edge: both stiffnesses act
      return std::unique_ptr<Term>(std::move(t));
    };
    const auto r =
        test::check_parameter_derivative(make, k == 0 ? 2e-5 : 7e-6, k, 0, hinge_states(), {1e-7, 1e-5, 1e-14});
    EXPECT_TRUE(r.ok) << r.detail;
  }
}

TEST(FemTermParameters, DiagonalBendingDerivativesMatchFiniteDifferences) {
  const double base[3] = {2e-5, 7e-6, 3e-6};  // k_warp, k_weft, k_diag
  for (int k = 0; k < 3; ++k) {
    auto make = [&](double p) {
      double v[3] = {base[0], base[1], base[2]};
      v[k] = p;
      auto t = std::make_unique<HingeBendingTerm>(v[0], v[1], v[2]);
      t->add(iota12(), Vec2(0.008, 0.012), 1.3e-4, 0.4);  // all three stiffnesses act
      return std::unique_ptr<Term>(std::move(t));
    };
    const auto r = test::check_parameter_derivative(make, base[k], k, 0, hinge_states(), {1e-7, 1e-5, 1e-14});
    EXPECT_TRUE(r.ok) << r.detail;
  }
  EXPECT_EQ(HingeBendingTerm(1, 1, 0.5).parameter_keys().back(), kFemDiagonalBending);
  EXPECT_EQ(HingeBendingTerm(1, 1).parameter_keys().size(), 2u);  // off: not a parameter
}

// Three vertices of a grid line: middle, next, previous; bent by θ with some scatter.
std::vector<test::LocalState> line_states() {
  std::vector<test::LocalState> states;
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> d(-1.0, 1.0);
  for (double th : {0.0, 0.04, 0.7, -1.5}) {
    const double l = 0.004;
    test::LocalState s{{0, 0, 0, l * std::cos(th), 0, l * std::sin(th), -l, 0, 0}, std::vector<double>(9, 0.0)};
    if (th != 0.0)
      for (auto& x : s.q) x += 0.0004 * d(rng);
    states.push_back(s);
  }
  return states;
}

TEST(GridLineBendingTerm, ForcesJacobianAndParameterDerivativeMatchFiniteDifferences) {
  const std::array<int, 9> s{0, 1, 2, 3, 4, 5, 6, 7, 8};
  GridLineBendingTerm t;
  t.add(s, 2e-7 * 0.004, 0.004);
  auto r = test::check_element(t, 0, line_states(), {.rel_step = 1e-7, .rtol = 2e-5, .floor = 1e-14});
  EXPECT_TRUE(r.ok) << r.detail;
  auto make = [&](double k) {
    auto term = std::make_unique<GridLineBendingTerm>();
    term->add(s, k * 0.004, 0.004);  // a line of width 4 mm
    term->tag_last(kFemWarpBending, k);
    return std::unique_ptr<Term>(std::move(term));
  };
  r = test::check_parameter_derivative(make, 2e-7, 0, 0, line_states(), {1e-7, 1e-5, 1e-14});
  EXPECT_TRUE(r.ok) << r.detail;
}

TEST(GridLineBendingTerm, EnergyIsTheYarnLawOfTheTurningAngle) {
  // V = k θ²/(2l) for a line of stiffness k (N·m²) turning by θ at its middle vertex.
  const double l = 0.004, k = 3e-9, th = 0.3;
  GridLineBendingTerm t;
  t.add({0, 1, 2, 3, 4, 5, 6, 7, 8}, k, l);
  const double q[9] = {0, 0, 0, l * std::cos(th), l * std::sin(th), 0, -l, 0, 0};
  EXPECT_NEAR(t.energy(0, q), k * th * th / (2 * l), 1e-12 * k * th * th / l);
}

TEST(BorderStretchTerm, ForcesAndParameterDerivativesMatchFiniteDifferences) {
  std::vector<test::LocalState> states;
  for (double stretch : {1.0001, 1.03, 0.97})
    states.push_back({{0.001, 0.002, 0.5, 0.001 + 0.004 * stretch, 0.0025, 0.5001}, std::vector<double>(6, 0.0)});
  for (bool along_u : {true, false}) {
    BorderStretchTerm t(120.0, 45.0, 5e-4);
    t.add({0, 1, 2, 3, 4, 5}, 0.004, along_u);
    auto r = test::check_element(t, 0, states);
    EXPECT_TRUE(r.ok) << r.detail;
    const int k = along_u ? 0 : 1;
    auto make = [&](double p) {
      auto b = std::make_unique<BorderStretchTerm>(k == 0 ? p : 120.0, k == 1 ? p : 45.0, 5e-4);
      b->add({0, 1, 2, 3, 4, 5}, 0.004, along_u);
      return std::unique_ptr<Term>(std::move(b));
    };
    r = test::check_parameter_derivative(make, k == 0 ? 120.0 : 45.0, k, 0, states);
    EXPECT_TRUE(r.ok) << r.detail;
  }
}

TEST(BorderStretchTerm, UniformStretchCarriesHalfASpacingOfMembraneForce) {
  // A bar of rest length ℓ₀ stretched by ε pulls with K·ε = k·w·ε.
  BorderStretchTerm t(200.0, 1.0, 5e-4);
  t.add({0, 1, 2, 3, 4, 5}, 0.002, true);
  const double q[6] = {0, 0, 0, 0.002 * 1.01, 0, 0};
  double f[6] = {};
  t.evaluate(0, q, nullptr, ElementOutput{f});
  EXPECT_NEAR(f[0], 200.0 * 5e-4 * 0.01, 1e-12);
  EXPECT_NEAR(f[3], -200.0 * 5e-4 * 0.01, 1e-12);
}

TEST(LumpedMassTerm, EachVertexGetsItsShareOnTheDiagonal) {
  LumpedMassTerm t;
  t.add(iota9(), {0.1, 0.2, 0.05});
  const std::vector<double> q(9, 0.0), v(9, 0.0);
  Eigen::Matrix<double, 9, 1> f = Eigen::Matrix<double, 9, 1>::Zero();
  Eigen::Matrix<double, 9, 9> m = Eigen::Matrix<double, 9, 9>::Zero();
  t.evaluate(0, q.data(), v.data(), {f.data(), nullptr, nullptr, m.data()});
  Eigen::Matrix<double, 9, 1> expected;
  expected << 0.1, 0.1, 0.1, 0.2, 0.2, 0.2, 0.05, 0.05, 0.05;
  EXPECT_NEAR((m - Eigen::Matrix<double, 9, 9>(expected.asDiagonal())).norm(), 0.0, 1e-15);
  EXPECT_EQ(f.norm(), 0.0);
  auto r = test::check_element(t, 0, triangle_states());
  EXPECT_TRUE(r.ok) << r.detail;
}

TEST(NodalGravityTerm, ForcesMatchEnergyGradient) {
  NodalGravityTerm t(Vec3(0.1, 0, -9.81));
  t.add({0, 1, 2}, 0.02);
  test::FdOptions opt;
  opt.constant_force = true;
  auto r = test::check_element(t, 0, {{{0.1, 0.2, 0.3}, {0, 0, 0}}, {{-1, 2, 5}, {1, 1, 1}}}, opt);
  EXPECT_TRUE(r.ok) << r.detail;
  const double q[3] = {0, 0, 2.0};
  EXPECT_NEAR(t.energy(0, q), 0.02 * 9.81 * 2.0, 1e-14);
}

// Rigid motions of a deformed triangle/hinge change neither energy nor force magnitude;
// at rest, rigid motions give zero force.
Mat3 rotation() { return (Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized())).toRotationMatrix(); }

TEST(FemTermsPatch, RigidMotionsOfRestGiveZeroForce) {
  const TriangleRest rest = triangle_rest(kUv0, kUv1, kUv2);
  WarpWeftStretchTerm st(120.0, 45.0);
  InPlaneShearTerm sh(30.0, 0.3, 2.0);
  st.add(iota9(), rest);
  sh.add(iota9(), rest);
  auto q = rest_triangle();
  const Mat3 R = rotation();
  const Vec3 t(0.3, -1.0, 2.0);
  for (int k = 0; k < 3; ++k) Eigen::Map<Vec3>(q.data() + 3 * k) = R * Eigen::Map<Vec3>(q.data() + 3 * k) + t;
  const std::vector<double> v(9, 0.0);
  for (Term* term : std::initializer_list<Term*>{&st, &sh}) {
    Eigen::Matrix<double, 9, 1> f = Eigen::Matrix<double, 9, 1>::Zero();
    term->evaluate(0, q.data(), v.data(), {f.data()});
    EXPECT_LT(f.norm(), 1e-10) << term->name();
  }
  HingeBendingTerm hb(1e-4, 1e-4);
  hb.add(iota12(), Vec2(0, 0.012), 1e-4);
  auto qh = hinge(0.0);
  for (int k = 0; k < 4; ++k) Eigen::Map<Vec3>(qh.data() + 3 * k) = R * Eigen::Map<Vec3>(qh.data() + 3 * k) + t;
  Eigen::Matrix<double, 12, 1> f = Eigen::Matrix<double, 12, 1>::Zero();
  const std::vector<double> vh(12, 0.0);
  hb.evaluate(0, qh.data(), vh.data(), {f.data()});
  EXPECT_LT(f.norm(), 1e-12);
}

TEST(FemTermsPatch, DeformedForcesAreRigidInvariantAndBalanced) {
  const TriangleRest rest = triangle_rest(kUv0, kUv1, kUv2);
  WarpWeftStretchTerm st(120.0, 45.0);
  InPlaneShearTerm sh(30.0, 0.3, 2.0);
  st.add(iota9(), rest);
  sh.add(iota9(), rest);
  HingeBendingTerm hb(1e-4, 3e-5);
  hb.add(iota12(), Vec2(0.003, 0.012), 1e-4);
  const Mat3 R = rotation();
  const Vec3 tr(0.3, -1.0, 2.0);
  auto check = [&](const Term& term, std::vector<double> q) {
    const int n = term.stencil_size();
    const std::vector<double> v(n, 0.0);
    Eigen::VectorXd f0 = Eigen::VectorXd::Zero(n), f1 = Eigen::VectorXd::Zero(n);
    term.evaluate(0, q.data(), v.data(), {f0.data()});
    Eigen::Vector3d total = Eigen::Vector3d::Zero(), torque = Eigen::Vector3d::Zero();
    for (int k = 0; k < n / 3; ++k) {
      total += f0.segment<3>(3 * k);
      torque += Eigen::Map<Vec3>(q.data() + 3 * k).cross(f0.segment<3>(3 * k));
    }
    EXPECT_LT(total.norm(), 1e-9 * f0.norm()) << term.name();
    EXPECT_LT(torque.norm(), 1e-9 * f0.norm()) << term.name();
    const double e0 = term.energy(0, q.data());
    for (int k = 0; k < n / 3; ++k) Eigen::Map<Vec3>(q.data() + 3 * k) = R * Eigen::Map<Vec3>(q.data() + 3 * k) + tr;
    term.evaluate(0, q.data(), v.data(), {f1.data()});
    EXPECT_NEAR(term.energy(0, q.data()), e0, 1e-9 * std::abs(e0)) << term.name();
    for (int k = 0; k < n / 3; ++k)
      EXPECT_LT((f1.segment<3>(3 * k) - R * f0.segment<3>(3 * k)).norm(), 1e-8 * f0.norm()) << term.name();
  };
  auto q = triangle_states()[2].q;
  check(st, q);
  check(sh, q);
  auto qh = hinge(0.9);
  qh[7] += 0.003;
  check(hb, qh);
}

}  // namespace
}  // namespace wl
