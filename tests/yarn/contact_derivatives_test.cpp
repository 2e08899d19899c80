// Exact derivatives of the contact normal force F_n and of friction's F_u
// (docs/models.md §3.6.1): ∂F_n/∂q and ∂F_n/∂k of ContactNormals against
// differences of F_n; the terms' ∂f/∂F_n and ∂f/∂F_u against differences of
// their force in the frozen input; each through the generic checker.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "models/yarn/contact_normals.h"
#include "models/yarn/terms/friction_cirio.h"
#include "models/yarn/terms/friction_gong.h"
#include "models/yarn/terms/shear_gong.h"
#include "tests/support/fd_check.h"
#include "tests/yarn/crossing_states.h"

namespace wl {
namespace {

constexpr double kL = 1e-3, kR = 0.5e-3;  // docs/models.md §8.4
constexpr double kKsU = 0.39, kKbU = 1.1e-10, kKsV = 0.13, kKbV = 0.9e-10;

WovenGrid plain_grid(int n) {
  Scene s;
  s.wefts = s.warps = n;
  s.spacing_m = kL;
  s.radius_m = kR;
  s.pattern.kind = Pattern::Kind::plain;
  return WovenGrid(s);
}

ContactNormals normals(const WovenGrid& g, double scale_ks_u = 1, double scale_kb_u = 1, double scale_ks_v = 1,
                       double scale_kb_v = 1) {
  return ContactNormals(g, std::vector<double>(g.nv(), kKsU * scale_ks_u),
                        std::vector<double>(g.nv(), kKbU * scale_kb_u), std::vector<double>(g.nu(), kKsV * scale_ks_v),
                        std::vector<double>(g.nu(), kKbV * scale_kb_v), kR);
}

// A 7×7 plain weave stretched 2 % along the warps, bent and moved at random by
// up to 0.05 L, sliding coordinates moved by up to 0.02 L: F_n > 0 at most crossings.
Vec generic_state(const WovenGrid& g) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Vec q = Vec::Zero(g.num_dofs());
  for (int j = 0; j < g.nv(); ++j)
    for (int i = 0; i < g.nu(); ++i) {
      const NodeDofs& d = g.dofs(g.node(i, j));
      q.segment<3>(d.x) = Vec3(1.02 * i * kL, j * kL, 0.1 * kL * std::sin(0.7 * i) * std::cos(0.5 * j)) +
                          0.05 * kL * Vec3(u(rng), u(rng), u(rng));
      if (is_dof(d.u)) q[d.u] = i * kL + 0.02 * kL * u(rng);
      if (is_dof(d.v)) q[d.v] = j * kL + 0.02 * kL * u(rng);
    }
  return q;
}

TEST(ContactNormalsGradient, MatchesDifferencesOfTheNormalForce) {
  const WovenGrid g = plain_grid(7);
  ContactNormals cn = normals(g);
  const Vec q = generic_state(g);
  cn.compute(q);
  cn.compute_gradient(q);
  int active = 0;
  for (double fn : cn.normal_force()) active += fn > 0.0;
  ASSERT_GE(active, 15) << "most inner crossings carry a normal force";
  Eigen::MatrixXd G = Eigen::MatrixXd::Zero(g.num_nodes(), g.num_dofs());
  for (int id = 0; id < g.num_nodes(); ++id)
    for (size_t k = 0; k < cn.gradient()[id].dof.size(); ++k)
      G(id, cn.gradient()[id].dof[k]) += cn.gradient()[id].value[k];
  ContactNormals probe = normals(g);
  auto fn_of = [&](const Eigen::VectorXd& x) {
    probe.compute(x);
    return Eigen::Map<const Eigen::VectorXd>(probe.normal_force().data(), g.num_nodes()).eval();
  };
  std::vector<int> cols(g.num_dofs());
  for (int c = 0; c < g.num_dofs(); ++c) cols[c] = c;
  test::FdOptions opt;
  opt.rel_step = 1e-7;
  opt.rtol = 1e-6;
  opt.floor = 1e-12;
  const test::FdReport r = test::check_jacobian_columns(
      fn_of, q, [&](int c) { return G.col(c).eval(); }, cols, opt);
  std::printf("[ F_n ] dF_n/dq relative error %.2e over %d columns\n", r.dfdq_error, g.num_dofs());
  EXPECT_TRUE(r.ok) << r.detail;
}

// ∂F_n/∂k_s and ∂F_n/∂k_b of the warps and the wefts from the proportional parts.
TEST(ContactNormalsGradient, StiffnessPartsGiveTheParameterDerivatives) {
  const WovenGrid g = plain_grid(7);
  const Vec q = generic_state(g);
  ContactNormals cn = normals(g);
  cn.compute(q);
  cn.compute_gradient(q);
  const double h = 1e-5;
  for (int which = 0; which < 4; ++which) {
    std::array<double, 4> up{1, 1, 1, 1}, down{1, 1, 1, 1};
    up[which] += h, down[which] -= h;
    ContactNormals hi = normals(g, up[0], up[1], up[2], up[3]), lo = normals(g, down[0], down[1], down[2], down[3]);
    hi.compute(q), lo.compute(q);
    double diff2 = 0.0, ref2 = 0.0;
    for (int id = 0; id < g.num_nodes(); ++id) {
      const auto& p = cn.stiffness_parts()[id];
      const double part = std::array<double, 4>{p.warp_stretch, p.warp_bending, p.weft_stretch, p.weft_bending}[which];
      // ∂F_n/∂(ln k) = part, against differences in the relative scale of k.
      const double fd = (hi.normal_force()[id] - lo.normal_force()[id]) / (2 * h);
      diff2 += (part - fd) * (part - fd);
      ref2 += fd * fd;
    }
    ASSERT_GT(ref2, 0.0) << "stiffness " << which;
    EXPECT_LT(std::sqrt(diff2 / ref2), 1e-6) << "stiffness " << which;
  }
}

// Term level: ∂f/∂F_n of Gong's shear (k_sh ∝ 1 + F_n), locked and free.
TEST(FrozenInputDerivatives, GongShearNormalForce) {
  for (bool lock : {true, false}) {
    auto make = [&](double fn) {
      auto t = std::make_unique<GongShearTerm>(kL, kR, 3.0, 0.6);
      t->add({0, 1, 2, 3, 4, 5, 6, 7, 8}, 0, 1000.0 * M_PI * kR * kR, lock);
      const std::vector<double> Fn{fn};
      t->prepare(EvalContext{0.0, nullptr, nullptr, nullptr, Fn});
      return std::unique_ptr<Term>(std::move(t));
    };
    std::vector<test::LocalState> states;
    for (double phi : {0.9, 1.3, 1.9, 2.4}) states.push_back(test::crossing_state(phi, 1.1 * kL, 0.9 * kL));
    const test::FdReport r = test::check_frozen_input_derivative(make, 0.4, 0, 0, states);
    EXPECT_TRUE(r.ok) << (lock ? "locked: " : "free: ") << r.detail;
  }
}

// Gong's friction in every regime: ∂F/∂F_n and ∂F/∂F_u.
TEST(FrozenInputDerivatives, GongFrictionNormalAndTangentialForce) {
  const double mu = 0.5, kf = 10, df = 1e-3, p = 20;  // K₂ turns over 0.05 N, K_δ over 5 cm
  for (double pull : {0.1, 0.47, 0.53, 2.0, -0.52}) {
    auto make = [&](double fn, double fu) {
      auto t = std::make_unique<GongFrictionTerm>(mu, kf, df, p);
      t->add(0, 0, 0.0);
      const Vec Fu = Vec::Constant(1, fu), q = Vec::Zero(1), v = Vec::Zero(1);
      const std::vector<double> Fn{fn};
      t->prepare(EvalContext{0.0, &q, &v, &Fu, Fn});
      return std::unique_ptr<Term>(std::move(t));
    };
    std::vector<test::LocalState> states;
    for (double d : {-0.1, -0.005, 0.015, 0.2}) states.push_back({{d}, {0.01}});
    test::FdOptions opt;
    opt.random_states = 0;
    const test::FdReport rn =
        test::check_frozen_input_derivative([&](double fn) { return make(fn, pull); }, 1.0, 0, 0, states, opt);
    EXPECT_TRUE(rn.ok) << "F_u = " << pull << ": " << rn.detail;
    if (std::abs(std::abs(pull) - mu) > 0.1) continue;  // K₂ saturated: ∂F/∂F_u vanishes
    const test::FdReport ru =
        test::check_frozen_input_derivative([&](double fu) { return make(1.0, fu); }, pull, 1, 0, states, opt);
    EXPECT_TRUE(ru.ok) << "F_u = " << pull << ": " << ru.detail;
  }
}

// Cirio's friction while slipping: F = −sign μF_n − d_f u̇, so ∂F/∂F_n = −sign μ.
TEST(FrozenInputDerivatives, CirioFrictionNormalForceWhileSlipping) {
  auto make = [&](double fn) {
    auto t = std::make_unique<CirioFrictionTerm>(0.5, 1000, 1e-3, 10);
    t->add(0, 0, 0.0);
    const Vec Fu = Vec::Zero(1), q = Vec::Constant(1, 0.01), v = Vec::Constant(1, 1.0);
    const std::vector<double> Fn{fn};
    t->prepare(EvalContext{0.0, &q, &v, &Fu, Fn});
    t->accept_step(EvalContext{0.0, &q, &v, &Fu, Fn}, 1e-3);  // k_f|u − ū| = 10 N > μF_n: slips
    t->prepare(EvalContext{0.0, &q, &v, &Fu, Fn});
    return std::unique_ptr<Term>(std::move(t));
  };
  ASSERT_NE(static_cast<const CirioFrictionTerm&>(*make(1.0)).slip_direction(0), 0);
  std::vector<test::LocalState> states{{{0.02}, {0.5}}, {{0.03}, {-0.1}}};
  const test::FdReport r = test::check_frozen_input_derivative(make, 1.0, 0, 0, states);
  EXPECT_TRUE(r.ok) << r.detail;
}

}  // namespace
}  // namespace wl
