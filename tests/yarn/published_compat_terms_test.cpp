// The [compat] switches of single terms (docs/published_code.md rows 6, 8, 9, 12, 22, 23): their
// scene keys; each switched term against the published formula written out here independently
// (closed forms, or the published expressions transcribed operation by operation), and against
// differences of its own force.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

#include <Eigen/Geometry>

#include "models/scene/scene.h"
#include "models/yarn/terms/bending.h"
#include "models/yarn/terms/parallel_contact.h"
#include "models/yarn/terms/shear_gong.h"
#include "models/yarn/yarn_model.h"
#include "tests/support/fd_check.h"
#include "tests/yarn/crossing_states.h"

namespace wl {
namespace {

constexpr double kPi = std::numbers::pi;

struct KeyCase {
  const char* key;
  const char* lab;
  const char* published;
  bool CompatSettings::*flag;
};

const KeyCase kKeys[] = {
    {"bending_sliding_force", "theta_squared", "theta", &CompatSettings::bending_sliding_theta},
    {"parallel_contact_sign", "repulsive", "attractive", &CompatSettings::parallel_contact_attractive},
    {"ring_over_under", "pattern", "none", &CompatSettings::ring_unsigned},
    {"shear_lock_angle", "mirrored", "actual", &CompatSettings::shear_lock_actual_angle},
    {"shear_lock_derivative", "exact", "published", &CompatSettings::shear_lock_published_derivative},
    {"shear_quadrants", "every_node", "interior", &CompatSettings::shear_interior_only},
    {"normal_force_bending_uv", "current", "rest", &CompatSettings::normal_force_bending_at_rest},
};

std::string compat(const std::string& key, const std::string& value) {
  return "[compat]\n\n" + key + " = \"" + value + "\"\n";
}

TEST(CompatKeys, EachTermKeyIsReadDefaultsToTheLabAndRefusesOtherValues) {
  for (const KeyCase& k : kKeys) {
    EXPECT_FALSE(parse_scene("", "s.toml").compat.*k.flag) << k.key;
    EXPECT_FALSE(parse_scene(compat(k.key, k.lab), "s.toml").compat.*k.flag) << k.key;
    EXPECT_TRUE(parse_scene(compat(k.key, k.published), "s.toml").compat.*k.flag) << k.key;
    try {
      parse_scene(compat(k.key, std::string(k.published) + "s"), "s.toml");
      ADD_FAILURE() << "no error for " << k.key;
    } catch (const SceneError& e) {
      EXPECT_EQ(e.key, std::string("compat.") + k.key);
      EXPECT_EQ(e.line, 3);
      EXPECT_NE(e.expected.find(k.published), std::string::npos) << e.what();
    }
  }
}

// Bending stencil with the angle θ between x1 − x0 and x0 − x2, in a rotated frame.
test::LocalState bending_state(double theta, double u1, double u2) {
  const Eigen::Matrix3d R = Eigen::AngleAxisd(0.4, Eigen::Vector3d(1, -2, 1).normalized()).toRotationMatrix();
  const Eigen::Vector3d x0(0.1, 0.2, -0.1), x1 = x0 + 1.1 * R * Eigen::Vector3d(1, 0, 0),
                                            x2 = x0 - 0.9 * R * Eigen::Vector3d(std::cos(theta), std::sin(theta), 0);
  test::LocalState s;
  s.q = {x0[0], x0[1], x0[2], x1[0], x1[1], x1[2], x2[0], x2[1], x2[2], u1, u2};
  s.v.assign(11, 0.0);
  return s;
}

TEST(CompatBending, SlidingForceIsKbThetaOverUSquaredAndPositionsAreTheEnergys) {
  // Published F_u1 = −F_u2 = k_b θ/U² (docs/published_code.md row 6); the lab's is k_b θ²/U².
  const double kb = 2.0, u1 = 1.3, u2 = -0.7, U = u1 - u2;
  BendingTerm published(true), lab;
  published.add({0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10}, kb);
  lab.add({0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10}, kb);
  for (double theta : {0.02, 0.3, 1.1, 2.5}) {
    const test::LocalState s = bending_state(theta, u1, u2);
    Eigen::Matrix<double, 11, 1> fp = Eigen::Matrix<double, 11, 1>::Zero(), fl = fp;
    published.evaluate(0, s.q.data(), s.v.data(), ElementOutput{fp.data()});
    lab.evaluate(0, s.q.data(), s.v.data(), ElementOutput{fl.data()});
    const double expected = kb * theta / (U * U);
    EXPECT_NEAR(fp[9], expected, 1e-12 * expected) << theta;
    EXPECT_NEAR(fp[10], -expected, 1e-12 * expected) << theta;
    EXPECT_NEAR(fl[9], expected * theta, 1e-12 * expected * theta) << theta;
    EXPECT_LT((fp.head<9>() - fl.head<9>()).norm(), 1e-14 * fl.head<9>().norm()) << theta;
  }
  EXPECT_FALSE(published.conservative());
  const auto r = test::check_element(
      published, 0, {bending_state(0.3, u1, u2), bending_state(1.1, u1, u2), bending_state(2.5, 0.4, -1.2)});
  EXPECT_TRUE(r.ok) << r.detail;
}

TEST(CompatParallelContact, AttractiveForceIsTheNegativeOfThePenaltys) {
  // Published F_u0 = +k_cL·ReLU(d − Δu) = −(the lab's), docs/published_code.md row 12.
  const double kcL = 3.0, d = 2.0;
  ParallelContactTerm published(-1.0), lab;
  published.add({0, 1}, kcL, d);
  lab.add({0, 1}, kcL, d);
  for (double du : {0.5, 1.5, 2.5}) {
    const double q[2] = {0.2, 0.2 + du}, v[2] = {0.0, 0.0};
    double fp[2] = {0, 0}, fl[2] = {0, 0};
    published.evaluate(0, q, v, ElementOutput{fp});
    lab.evaluate(0, q, v, ElementOutput{fl});
    const double expected = kcL * std::max(0.0, d - du);
    EXPECT_DOUBLE_EQ(fp[0], expected) << du;
    EXPECT_DOUBLE_EQ(fp[1], -expected) << du;
    EXPECT_DOUBLE_EQ(fl[0], -expected) << du;
  }
  const auto r = test::check_element(published, 0, {{{0.1, 0.9}, {0.0, 0.0}}, {{-0.3, 1.2}, {0.0, 0.0}}});
  EXPECT_TRUE(r.ok) << r.detail;
}

// Gong's locked shear force as the published code writes it (docs/published_code.md rows 8–9),
// transcribed expression by expression: c = 3, σ = 0.6, φ̄ = π/2, φ_l = 2 asin(R/L), γ and g at φ
// itself, and ∂k/∂x with 1 − f²·∂g/∂x (chain_slip) or (1 − f²)·∂g/∂x.
Eigen::Matrix<double, 9, 1> published_lock_force(const test::LocalState& s, double Fn, double S_pi_R2, double L,
                                                 double R, bool chain_slip) {
  using V3 = Eigen::Vector3d;
  const V3 x0(s.q.data()), x1(s.q.data() + 3), x3(s.q.data() + 6);
  const double l1 = (x1 - x0).norm(), l3 = (x3 - x0).norm();
  const V3 d1 = (x1 - x0) / l1, d3 = (x3 - x0) / l3;
  const Eigen::Matrix3d P1 = Eigen::Matrix3d::Identity() - d1 * d1.transpose(),
                        P3 = Eigen::Matrix3d::Identity() - d3 * d3.transpose();
  const double phi = std::acos(d1.dot(d3)), pb = kPi / 2, pl = 2.0 * std::asin(R / L), sig = 0.6;
  const V3 phi_x1 = -P1 * d3 / (l1 * std::sin(phi)), phi_x3 = -P3 * d1 / (l3 * std::sin(phi));
  const double gamma = (L * std::sqrt(2.0) - 2 * L * std::sin(0.5 * phi)) / R;
  const V3 gamma_x1 = -(L / R) * std::cos(0.5 * phi) * phi_x1, gamma_x3 = -(L / R) * std::cos(0.5 * phi) * phi_x3;
  const double phi_s = phi * (phi - pl) * (phi - pb);
  const V3 phi_s_x1 = phi_x1 * (phi - pl) * (phi - pb) + phi * phi_x1 * (phi - pb) + phi * (phi - pl) * phi_x1;
  const V3 phi_s_x3 = phi_x3 * (phi - pl) * (phi - pb) + phi * phi_x3 * (phi - pb) + phi * (phi - pl) * phi_x3;
  const double num = std::pow(pb, 5) * (phi - pl), den = phi_s * phi_s + std::pow(pb, 4) * sig * sig;
  const double f = std::tanh(num / den);
  const V3 g_x1 = (std::pow(pb, 5) * phi_x1 * den - num * 2 * phi_s * phi_s_x1) / (den * den);
  const V3 g_x3 = (std::pow(pb, 5) * phi_x3 * den - num * 2 * phi_s * phi_s_x3) / (den * den);
  const double C = 0.5 * (Fn + 1.0) * S_pi_R2, g3 = std::pow(gamma, 3);
  const double kx = C * ((1 + g3) + (1 - g3) * f);
  const auto tanh_part = [&](const V3& g_x) -> V3 {
    return chain_slip ? V3(V3::Ones() - f * f * g_x) : V3((1 - f * f) * g_x);
  };
  const V3 kx_x1 = C * (3 * gamma * gamma * gamma_x1 - 3 * gamma * gamma * gamma_x1 * f + (1 - g3) * tanh_part(g_x1));
  const V3 kx_x3 = C * (3 * gamma * gamma * gamma_x3 - 3 * gamma * gamma * gamma_x3 * f + (1 - g3) * tanh_part(g_x3));
  const double a = phi - pb;
  const V3 F1 = -0.5 * kx_x1 * L * a * a + (kx * L * a) / (l1 * std::sin(phi)) * (P1 * d3);
  const V3 F3 = -0.5 * kx_x3 * L * a * a + (kx * L * a) / (l3 * std::sin(phi)) * (P3 * d1);
  Eigen::Matrix<double, 9, 1> F;
  F << -(F1 + F3), F1, F3;
  return F;
}

TEST(CompatShear, LockedForceIsThePublishedFormula) {
  const double L = 1e-3, R = 5e-4, Fn = 0.4, S_pi_R2 = 1000.0 * kPi * R * R;
  const std::vector<double> fn{Fn};
  for (const bool slip : {false, true}) {
    GongShearTerm t(L, R, 3.0, 0.6, GongShearTerm::Published{true, slip});
    t.add({0, 1, 2, 3, 4, 5, 6, 7, 8}, 0, S_pi_R2, true);
    t.prepare(EvalContext{0.0, nullptr, nullptr, nullptr, fn});
    for (double phi : {1.2, 1.45, 1.6, 1.75, 2.1}) {
      const test::LocalState s = test::nudged(test::crossing_state(phi, 1.1 * L, 0.9 * L), 0.02 * L);
      Eigen::Matrix<double, 9, 1> f = Eigen::Matrix<double, 9, 1>::Zero();
      t.evaluate(0, s.q.data(), s.v.data(), ElementOutput{f.data()});
      const Eigen::Matrix<double, 9, 1> expected = published_lock_force(s, Fn, S_pi_R2, L, R, slip);
      ASSERT_GT(expected.norm(), 0.0);
      EXPECT_LT((f - expected).norm(), 1e-10 * expected.norm()) << "phi " << phi << " slip " << slip;
    }
  }
}

TEST(CompatShear, PublishedLockMatchesDifferencesOfItsForce) {
  const double L = 1e-3, R = 5e-4;
  const std::vector<double> fn{0.3};
  GongShearTerm t(L, R, 3.0, 0.6, GongShearTerm::Published{true, true});
  t.add({0, 1, 2, 3, 4, 5, 6, 7, 8}, 0, 1000.0 * kPi * R * R, true);
  t.prepare(EvalContext{0.0, nullptr, nullptr, nullptr, fn});
  EXPECT_FALSE(t.conservative());
  test::FdOptions opt;
  opt.rel_step = 1e-7;  // as for the lab's lock at yarn scale (shear_gong_test.cpp)
  opt.floor = 1e-16;
  std::vector<test::LocalState> states;
  for (double phi : {1.0, 1.3, 1.7, 2.2}) states.push_back(test::crossing_state(phi, 1.1 * L, 0.9 * L));
  const auto r = test::check_element(t, 0, states, opt);
  EXPECT_TRUE(r.ok) << r.detail;
}

TEST(CompatShear, ActualAngleNeedsAnIntegerExponent) {
  try {
    parse_scene("[contact]\nlock_exponent = 2.5\n[compat]\nshear_lock_angle = \"actual\"\n", "s.toml");
    ADD_FAILURE() << "no error for a fractional exponent at the actual angle";
  } catch (const SceneError& e) {
    EXPECT_EQ(e.key, "compat.shear_lock_angle");
    EXPECT_EQ(e.line, 4);
    EXPECT_NE(e.expected.find("lock_exponent"), std::string::npos) << e.what();
  }
  EXPECT_THROW(GongShearTerm(1e-3, 5e-4, 2.5, 0.6, GongShearTerm::Published{true, false}), std::invalid_argument);
  EXPECT_NO_THROW(GongShearTerm(1e-3, 5e-4, 2.5, 0.6));
}

Scene plain(int n, const std::string& compat_lines) {
  return parse_scene("[cloth]\nwarps = " + std::to_string(n) + "\nwefts = " + std::to_string(n) +
                         "\nspacing_m = 0.001\nradius_m = 0.0005\n[compat]\n" + compat_lines,
                     "s.toml");
}

int shear_elements(const YarnModel& m) {
  int n = 0;
  for (const auto& t : m.terms())
    if (t->name() == "shear") n += t->num_elements();
  return n;
}

TEST(CompatGrid, RingSignsAndShearQuadrants) {
  const int n = 6;
  const YarnModel lab(plain(n, "")),
      published(plain(n, "ring_over_under = \"none\"\nshear_quadrants = \"interior\"\n"));
  int ring_changed = 0;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const bool ring = i == 0 || j == 0 || i == n - 1 || j == n - 1;
      EXPECT_EQ(lab.grid().sign(i, j), (i + j) % 2 == 0 ? 1 : -1);
      EXPECT_EQ(published.grid().sign(i, j), ring ? 1 : lab.grid().sign(i, j)) << i << "," << j;
      ring_changed += published.grid().sign(i, j) != lab.grid().sign(i, j);
    }
  EXPECT_EQ(ring_changed, 2 * (n - 1));  // the odd ring nodes
  // Every node has one quadrant per pair of neighbours: 4 inside, 2 on an edge, 1 at a corner.
  EXPECT_EQ(shear_elements(lab), 4 * (n - 2) * (n - 2) + 2 * 4 * (n - 2) + 4);
  EXPECT_EQ(shear_elements(published), 4 * (n - 2) * (n - 2));
}

}  // namespace
}  // namespace wl
