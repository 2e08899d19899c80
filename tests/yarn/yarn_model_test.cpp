// Physics of the assembled yarn-level model under backward Euler:
// DoF counts, momentum balance, energy behaviour, the catenary,
// and the published hanging cloth.
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <numbers>
#include <random>

#include "integrators/backward_euler.h"
#include "integrators/integrator.h"
#include "models/scene/scene.h"
#include "models/yarn/terms/bending.h"
#include "models/yarn/terms/gravity.h"
#include "models/yarn/terms/segment_inertia.h"
#include "models/yarn/terms/stretch.h"
#include "models/yarn/yarn_model.h"
#include "tests/yarn/model_blocks.h"

namespace wl {
namespace {

Scene small_scene(int n, bool sliding) {
  Scene s;
  s.warps = s.wefts = n;
  s.sliding = sliding;
  s.yarn_types["default"] = YarnType{};
  s.gravity_m_per_s2 = {0, 0, 0};
  s.terms.gravity = s.terms.wind = s.terms.handles = false;
  s.pose = Scene::Pose::flat;
  return s;
}

Vec perturbed(const YarnModel& m, double amplitude, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> d(-amplitude, amplitude);
  Vec q = m.initial_q();
  for (int k = 0; k < m.grid().num_nodes(); ++k) {
    const int x = m.grid().dofs(k).x;
    for (int c = 0; c < 3; ++c) q[x + c] += d(rng);
  }
  return q;
}

double total_energy(YarnModel& m, const Vec& q, const Vec& v) {
  Evaluation scratch;
  return m.kinetic_energy(0.0, q, v, scratch) + m.potential_energy(q);
}

// Random velocities on every DoF, sliding ones included (std. dev. `sd`).
Vec random_velocity(const YarnModel& m, double sd, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> nd(0.0, sd);
  Vec v = Vec::Zero(m.num_dofs());
  for (int k = 0; k < v.size(); ++k) v[k] = nd(rng);
  return v;
}

// Linear momentum: the x rows of M(q)q̇ summed over the nodes.
Vec3 linear_momentum(YarnModel& m, const Vec& q, const Vec& v, Evaluation& ev) {
  m.evaluate(0.0, q, v, kMass, ev);
  const Vec p = ev.mass * v;
  Vec3 total = Vec3::Zero();
  for (int k = 0; k < m.grid().num_nodes(); ++k) total += p.segment<3>(m.grid().dofs(k).x);
  return total;
}

TEST(YarnModel, DofCountsMatchPhysicsTable) {
  // docs/models.md §2.1: l = 3rc + 2(r−2)(c−2); 17×17 → 1317.
  EXPECT_EQ(YarnModel(small_scene(17, true)).num_dofs(), 1317);
  EXPECT_EQ(YarnModel(small_scene(5, true)).num_dofs(), 93);
  EXPECT_EQ(YarnModel(small_scene(17, false)).num_dofs(), 3 * 289);
}

TEST(YarnModel, InternalForcesSumToZero) {
  // Without pins, handles, gravity and wind the internal forces balance: the
  // x-components summed over nodes vanish (translation invariance).
  for (bool sliding : {true, false}) {
    YarnModel m(small_scene(7, sliding));
    const Vec q = perturbed(m, 2e-4, 3);
    Evaluation ev;
    allocate_evaluation(m, ev);
    m.evaluate(0.0, q, Vec::Zero(m.num_dofs()), kForce, ev);
    Vec3 sum = Vec3::Zero(), scale = Vec3::Zero();
    for (int k = 0; k < m.grid().num_nodes(); ++k) {
      sum += ev.force.segment<3>(m.grid().dofs(k).x);
      scale += ev.force.segment<3>(m.grid().dofs(k).x).cwiseAbs();
    }
    EXPECT_GT(scale.norm(), 0.0);
    EXPECT_LT(sum.norm(), 1e-12 * scale.norm()) << "sliding=" << sliding;
  }
}

TEST(YarnModel, BackwardEulerNeverIncreasesEnergy) {
  // No gravity, wind, handles or friction damping: E = T + V must not grow.
  for (bool sliding : {false, true}) {
    Scene s = small_scene(6, sliding);
    s.terms.friction = false;
    s.contact.shear_model = ContactParams::ShearModel::cirio;  // Gong's F_n-lagged stiffness is not conservative
    YarnModel m(s);
    BackwardEuler be(BackwardEuler::Variant::newton);
    IntegratorOptions opt;
    opt.dt = 1e-4;
    opt.newton_tol = 1e-12;
    be.initialize(m, 0.0, perturbed(m, 5e-5, 7), Vec::Zero(m.num_dofs()), opt);
    double e_prev = total_energy(m, be.q(), be.v());
    const double e0 = e_prev;
    ASSERT_GT(e0, 0.0);
    for (int k = 0; k < 60; ++k) {
      ASSERT_EQ(be.step(opt.dt).outcome, Outcome::ok);
      const double e = total_energy(m, be.q(), be.v());
      EXPECT_LE(e, e_prev + 1e-9 * e0) << "step " << k << " sliding=" << sliding;
      e_prev = e;
    }
    EXPECT_LT(e_prev, e0);
  }
}

TEST(YarnModel, SlidingCoordinatesThatMeetAreAnInvalidStateNamingTheYarn) {
  YarnModel m(small_scene(7, true));
  Vec q = m.initial_q();
  EXPECT_EQ(m.invalid_state(q), "");
  // Crossing (3, 2) slides along warp 2 exactly onto crossing (4, 2): Δu = 0 (docs/models.md §2.2).
  const int u3 = m.grid().dofs(m.grid().node(3, 2)).u, u4 = m.grid().dofs(m.grid().node(4, 2)).u;
  q[u3] = q[u4];
  const std::string why = m.invalid_state(q);
  EXPECT_NE(why.find("warp 2 between crossings (3, 2) and (4, 2)"), std::string::npos) << why;
  // Past the outer ring's frozen coordinate: weft 1 at crossing (1, 1) beyond (1, 0)'s v = 0.
  q = m.initial_q();
  q[m.grid().dofs(m.grid().node(1, 1)).v] = -1e-4;
  EXPECT_NE(m.invalid_state(q).find("weft 1 between crossings (1, 0) and (1, 1)"), std::string::npos)
      << m.invalid_state(q);
  q[u3] = std::nan("");  // NaN is left to check_state
  q[m.grid().dofs(m.grid().node(1, 1)).v] = 1e-3;
  EXPECT_EQ(m.invalid_state(q), "");
  const YarnModel frozen(small_scene(7, false));
  EXPECT_EQ(frozen.invalid_state(frozen.initial_q()), "");
}

TEST(YarnModel, FreeClothConservesMomentum) {
  // Internal forces only, constant mass (no sliding): P = Σ M v is conserved by backward Euler.
  YarnModel m(small_scene(6, false));
  Evaluation ev;
  const Vec v = random_velocity(m, 0.05, 11);
  auto momentum = [&](const Vec& q, const Vec& vel) { return linear_momentum(m, q, vel, ev); };
  BackwardEuler be(BackwardEuler::Variant::linear);
  IntegratorOptions opt;
  opt.dt = 1e-3;
  be.initialize(m, 0.0, perturbed(m, 1e-4, 5), v, opt);
  const Vec3 p0 = momentum(be.q(), be.v());
  for (int k = 0; k < 50; ++k) ASSERT_EQ(be.step(opt.dt).outcome, Outcome::ok);
  EXPECT_LT((momentum(be.q(), be.v()) - p0).norm(), 1e-9 * p0.norm());
}

// IDA at rtol 1e-10 from (q0, v0).
std::unique_ptr<Integrator> accurate_ida(YarnModel& m, const Vec& q0, const Vec& v0) {
  auto ida = make_integrator("ida");
  IntegratorOptions opt;
  opt.adaptive = true;
  opt.dt = 1e-6;
  opt.rtol = 1e-10;
  opt.atol = 1e-14;
  ida->initialize(m, 0.0, q0, v0, opt);
  return ida;
}

TEST(YarnModel, AccurateIntegratorConservesEnergyWithSlidingAndNoDissipation) {
  // Every conservative term on (stretch, bending, Cirio shear, parallel contact,
  // inertia with sliding), nothing dissipative (no friction, wind, damping):
  // E = T + V is a constant of the motion, so IDA at rtol 1e-10 must hold it.
  // Backward Euler's damping cannot hide an energy-injecting error here.
  Scene s = small_scene(6, true);
  s.terms.friction = false;
  s.contact.shear_model = ContactParams::ShearModel::cirio;  // Gong's F_n-lagged stiffness is not conservative
  YarnModel m(s);
  auto ida = accurate_ida(m, perturbed(m, 5e-5, 7), random_velocity(m, 1e-3, 8));
  const double e0 = total_energy(m, ida->q(), ida->v());
  double worst = 0.0;
  for (int k = 1; k <= 10; ++k) {
    ASSERT_EQ(ida->advance_to(2e-4 * k).outcome, Outcome::ok);
    worst = std::max(worst, std::abs(total_energy(m, ida->q(), ida->v()) - e0));
  }
  std::cout << "energy drift over 2 ms: " << worst / e0 << " of E0\n";
  EXPECT_LT(worst, 1e-7 * e0);  // measured 1.1e-8
}

TEST(YarnModel, FreeSlidingClothConservesMomentum) {
  // Sliding on, Gong shear and parallel contact on: internal forces are
  // translation invariant, parallel contact acts on u, v only, and T depends on
  // x only through differences x1 − x0, so P = Σ over x rows of M(q)q̇ is
  // constant in time (docs/models.md §3.1.2). IDA at rtol 1e-10. (Friction is
  // off: its damping d_f on sliding DoFs of 1e-6 kg, against sliding speeds of
  // 5 cm/s, has a nanosecond time scale IDA cannot start on.)
  Scene s = small_scene(6, true);
  s.terms.friction = false;
  YarnModel m(s);
  Evaluation ev;
  auto momentum = [&](const Vec& q, const Vec& vel) { return linear_momentum(m, q, vel, ev); };
  auto ida = accurate_ida(m, perturbed(m, 1e-4, 5), random_velocity(m, 0.05, 11));
  const Vec3 p0 = momentum(ida->q(), ida->v());
  const StepResult r = ida->advance_to(1e-3);
  ASSERT_EQ(r.outcome, Outcome::ok) << to_string(r.outcome) << ": " << r.message;
  const double drift = (momentum(ida->q(), ida->v()) - p0).norm() / p0.norm();
  std::cout << "momentum drift over 1 ms: " << drift << " of |P0|\n";
  EXPECT_LT(drift, 1e-8);  // measured 5e-10
}

// Still-air drag f = −c ẋ on one node: lets a test settle to its static
// equilibrium quickly; vanishes at rest, so the equilibrium is unchanged.
class NodeDragTerm : public StencilTerm<3> {
 public:
  explicit NodeDragTerm(double c) : c_(c) {}
  void add(const std::array<int, 3>& s) { stencils_.push_back(s); }
  std::unique_ptr<Term> clone() const override { return std::make_unique<NodeDragTerm>(*this); }
  std::string name() const override { return "drag"; }
  bool conservative() const override { return false; }
  bool has_velocity_jacobian() const override { return true; }
  double energy(int, const double*) const override { return 0.0; }
  void evaluate(int, const double*, const double* v, const ElementOutput& out) const override {
    VecMap(out.force) = -c_ * ConstVecMap(v);
    if (out.dfdv) MatMap(out.dfdv) = -c_ * LMat::Identity();
  }

 private:
  double c_;
};

// A single yarn of N nodes hanging from its two ends (frozen u, 3 DoFs per node).
class HangingYarn : public TermModel {
 public:
  HangingYarn(int n, double length, double span, double rho, double ks, double kb, double drag = 0.0) {
    const double du = length / (n - 1);
    num_dofs_ = 3 * n;
    q0_ = Vec::Zero(num_dofs_);
    v0_ = Vec::Zero(num_dofs_);
    constants_.resize(n);
    // Start unstretched on a V between the supports (a straight compressed yarn
    // would be an unstable equilibrium that Newton can converge to).
    const double depth = std::sqrt(0.25 * length * length - 0.25 * span * span);
    for (int i = 0; i < n; ++i) {
      constants_[i] = i * du;
      const double s = double(i) / (n - 1);
      q0_.segment<3>(3 * i) = Vec3(span * s, 0.0, -depth * (1.0 - std::abs(2.0 * s - 1.0)));
    }
    auto inertia = std::make_unique<SegmentInertiaTerm>();
    auto stretch = std::make_unique<StretchTerm>();
    auto gravity = std::make_unique<GravityTerm>(Vec3(0, 0, -9.81));
    auto bending = std::make_unique<BendingTerm>();
    for (int i = 0; i + 1 < n; ++i) {
      const std::array<int, 8> s{3 * i,     3 * i + 1, 3 * i + 2,          3 * i + 3,
                                 3 * i + 4, 3 * i + 5, encode_constant(i), encode_constant(i + 1)};
      inertia->add(s, rho);
      stretch->add(s, ks);
      gravity->add(s, rho);
    }
    for (int i = 1; i + 1 < n; ++i)
      bending->add({3 * i, 3 * i + 1, 3 * i + 2, 3 * i + 3, 3 * i + 4, 3 * i + 5, 3 * i - 3, 3 * i - 2, 3 * i - 1,
                    encode_constant(i + 1), encode_constant(i - 1)},
                   kb);
    terms_.push_back(std::move(inertia));
    terms_.push_back(std::move(stretch));
    terms_.push_back(std::move(gravity));
    terms_.push_back(std::move(bending));
    if (drag > 0) {
      auto d = std::make_unique<NodeDragTerm>(drag);
      for (int i = 0; i < n; ++i) d->add({3 * i, 3 * i + 1, 3 * i + 2});
      terms_.push_back(std::move(d));
    }
    fixed_ = {0, 1, 2, 3 * n - 3, 3 * n - 2, 3 * n - 1};
    finalize();
  }
  std::unique_ptr<Model> clone() const override { return std::make_unique<HangingYarn>(*this); }
  std::string name() const override { return "hanging-yarn"; }
  bool mass_depends_on_q() const override { return false; }
  Frame frame(double, const Vec&, const Vec&) const override { return {}; }
  std::map<std::string, std::string> describe() const override { return {}; }
};

TEST(YarnModel, HangingYarnSettlesToCatenary) {
  // Nearly inextensible yarn (strain ~1e-5; the sag moves by a few 1e-5 relative) of length S between supports D apart:
  // sag = a(cosh(D/2a) − 1) with S = 2a sinh(D/2a).
  const int n = 41;
  const double S = 0.1, D = 0.08, rho = 0.002, ks = 5.0, kb = 1e-10;
  // Drag near critical for the swinging mode (ω ≈ √(g/sag) ≈ 20 /s, node mass 5e-6 kg).
  HangingYarn m(n, S, D, rho, ks, kb, 2e-4);
  BackwardEuler be(BackwardEuler::Variant::linear);
  IntegratorOptions opt;
  opt.dt = 2e-3;
  be.initialize(m, 0.0, m.initial_q(), m.initial_v(), opt);
  for (int k = 0; k < 1000; ++k) {
    const StepResult r = be.step(opt.dt);
    ASSERT_EQ(r.outcome, Outcome::ok) << "step " << k << ": " << r.message;
  }
  EXPECT_LT(be.v().lpNorm<Eigen::Infinity>(), 1e-6);
  const double sag = -be.q()[3 * (n / 2) + 2];
  double lo = 1e-4, hi = 10.0;  // bisection for a: 2a sinh(D/2a) decreases in a
  for (int it = 0; it < 200; ++it) {
    const double a = 0.5 * (lo + hi);
    (2 * a * std::sinh(D / (2 * a)) > S ? lo : hi) = a;
  }
  const double a = 0.5 * (lo + hi);
  const double expected = a * (std::cosh(D / (2 * a)) - 1.0);
  EXPECT_NEAR(sag, expected, 0.01 * expected) << "sag " << sag << " vs catenary " << expected;
}

TEST(YarnModel, PublishedHangingClothSwingsDownwind) {
  Scene s = load_scene(std::string(WEAVELAB_SOURCE_DIR) + "/experiments/scenes/hanging_wind.toml");
  for (const char* name : {"be-linear", "be-newton"}) {
    YarnModel m(s);
    BackwardEuler be(std::string(name) == "be-linear" ? BackwardEuler::Variant::linear
                                                      : BackwardEuler::Variant::newton);
    IntegratorOptions opt;
    opt.dt = s.dt_s;
    be.initialize(m, 0.0, m.initial_q(), m.initial_v(), opt);
    const StepResult r = be.advance_to(0.1);
    ASSERT_EQ(r.outcome, Outcome::ok) << name << ": " << r.message;
    ASSERT_TRUE(be.q().allFinite());
    double mean_dy = 0.0;
    for (int k = 0; k < m.grid().num_nodes(); ++k)
      mean_dy += be.q()[m.grid().dofs(k).x + 1] - m.initial_q()[m.grid().dofs(k).x + 1];
    EXPECT_GT(mean_dy / m.grid().num_nodes(), 0.0) << name;
  }
}

}  // namespace
}  // namespace wl

namespace wl {
namespace {

// The assembled ∂f/∂q and ∂f/∂v against central differences of the assembled
// force, block by block over the DoF kinds `kind` (tests/yarn/model_blocks.h;
// empty: one block). h perturbs q; velocities use 1e3·h (the velocity
// dependence is smooth and the static forces are large, so a tiny step would
// only measure roundoff). A block that is zero must be zero in both.
void expect_model_jacobians_match(Model& m, const Vec& q, const Vec& v, double h, double rtol,
                                  std::vector<int> kind = {}) {
  if (kind.empty()) kind.assign(q.size(), 0);
  const double hv = 1e3 * h;
  Evaluation ev, ep, em;
  m.evaluate(0.0, q, v, kForce | kDfdq | kDfdv, ev);
  test::Blocks dq, dv;
  for (int j = 0; j < q.size(); ++j) {
    Vec qp = q, qm = q, vp = v, vm = v;
    qp[j] += h;
    qm[j] -= h;
    vp[j] += hv;
    vm[j] -= hv;
    m.evaluate(0.0, qp, v, kForce, ep);
    m.evaluate(0.0, qm, v, kForce, em);
    dq.add(kind, j, (ep.force - em.force) / (2 * h), Vec(ev.dfdq.col(j)));
    m.evaluate(0.0, q, vp, kForce, ep);
    m.evaluate(0.0, q, vm, kForce, em);
    dv.add(kind, j, (ep.force - em.force) / (2 * hv), Vec(ev.dfdv.col(j)));
  }
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) {
      const std::string block = std::string(test::kDofKind[r]) + "-" + test::kDofKind[c];
      for (const auto& [what, b] : {std::pair{"df/dq ", &dq}, std::pair{"df/dv ", &dv}}) {
        if (b->ref[r][c] > 0.0) EXPECT_LT(b->relative(r, c), rtol) << what << block;
        else EXPECT_EQ(b->diff[r][c], 0.0) << what << block << " should be zero";
      }
    }
}

TEST(YarnModel, AssembledJacobiansMatchFiniteDifferences) {
  for (bool sliding : {false, true}) {
    Scene s = small_scene(5, sliding);
    s.terms.friction = false;  // friction and Gong shear read lagged F_u, F_n (not differentiated)
    s.contact.shear_model = ContactParams::ShearModel::cirio;
    s.terms.gravity = s.terms.wind = s.terms.handles = true;
    s.gravity_m_per_s2 = {0, 0, -9.8};
    s.wind_velocity_m_per_s = {0, 5, 0};
    s.air_density_kg_per_m3 = 2;
    s.wind_drag_Ns_per_m3 = 0.5;
    YarnModel m(s);
    Vec v = Vec::Zero(m.num_dofs());
    std::mt19937 rng(2);
    std::normal_distribution<double> nd(0.0, 0.01);
    for (int k = 0; k < v.size(); ++k) v[k] = nd(rng);
    for (int f : m.fixed_dofs()) v[f] = 0;
    expect_model_jacobians_match(m, perturbed(m, 1e-4, 9), v, 1e-8, 1e-5, test::dof_kinds(m));
  }
}

TEST(YarnModel, HangingYarnJacobiansMatchFiniteDifferences) {
  HangingYarn m(7, 0.1, 0.08, 0.002, 50.0, 1e-6, 1e-4);
  Vec v = Vec::Constant(m.num_dofs(), 0.01);
  for (int f : m.fixed_dofs()) v[f] = 0;
  expect_model_jacobians_match(m, m.initial_q(), v, 1e-7, 1e-5);
}

}  // namespace
}  // namespace wl
