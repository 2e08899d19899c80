// Stacked stitches (docs/models.md §11.1, §11.4, §11.6): a stitch contact whose
// nodes carry n = 3 yarns (a decrease). The pairs of its yarns and their share
// of the stack; the pair elements of the roll and the contact compression
// against finite differences at random states, and their sums against the
// energy of every pair (a dropped pair fails); every term at a patch around a
// three-yarn stitch, assembled: force against the energy, Jacobian and
// parameter derivatives against finite differences.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <random>

#include "models/core/term_model.h"
#include "models/knit/stack_pairs.h"
#include "models/knit/terms/stitch_compression.h"
#include "models/knit/terms/stitch_length.h"
#include "models/knit/terms/stitch_roll.h"
#include "models/yarn/terms/bending.h"
#include "models/yarn/terms/stretch.h"
#include "tests/support/fd_check.h"

namespace wl {
namespace {

constexpr double kR = 0.2e-3, kD = 2.0 * kR;  // yarn radius, contact distance [m]

TEST(StackPairs, EveryPairOfTheYarnsOnceWithItsShareOfTheStack) {
  const std::vector<StackPair> two = stack_pairs(2);
  ASSERT_EQ(two.size(), 1u);
  EXPECT_EQ(two[0].i, 0);
  EXPECT_EQ(two[0].j, 1);
  EXPECT_EQ(two[0].share, 1.0);
  const std::vector<StackPair> three = stack_pairs(3);
  ASSERT_EQ(three.size(), 3u);
  const int expected[3][2] = {{0, 1}, {0, 2}, {1, 2}};
  const double share[3] = {0.5, 1.0, 0.5};  // neighbours in the stack half its height apart, the outer pair all of it
  for (int p = 0; p < 3; ++p) {
    EXPECT_EQ(three[p].i, expected[p][0]);
    EXPECT_EQ(three[p].j, expected[p][1]);
    EXPECT_EQ(three[p].share, share[p]);
  }
  EXPECT_EQ(stack_pairs(4).size(), 6u);
}

std::array<int, 24> identity24() {
  std::array<int, 24> s{};
  for (int a = 0; a < 24; ++a) s[a] = a;
  return s;
}

// A stitch contact (a, b) in a flat loop, its stack of height h through the
// cloth (σ = `stitch`; the contact on the other side of the loop along
// `side`·x), every node moved at random by up to 0.05 mm.
std::vector<double> random_stack_state(double h, int side, int stitch, std::mt19937& rng) {
  std::uniform_real_distribution<double> jitter(-0.05e-3, 0.05e-3);
  const double nodes[8][3] = {{0, 0, -0.5 * h}, {0, 0.5e-3, 0.5 * h}, {1e-3, 0, 0},   {1e-3, 0.5e-3, 0},
                              {0, -1.6e-3, 0},  {0, -1.1e-3, 0},      {0, 1.6e-3, 0}, {0, 2.1e-3, 0}};
  std::vector<double> q(24);
  for (int k = 0; k < 8; ++k) {
    q[3 * k] = side * nodes[k][0] + jitter(rng);
    q[3 * k + 1] = nodes[k][1] + jitter(rng);
    q[3 * k + 2] = stitch * nodes[k][2] + (k < 2 ? 0.1 : 1.0) * jitter(rng);
  }
  return q;
}

// One element per pair of a three-yarn stack (stack_pairs.h), as the knit model adds them.
StitchCompressionTerm stacked_compression(double kappa, int side, int stitch) {
  StitchCompressionTerm t;
  for (const StackPair& p : stack_pairs(3)) {
    t.add(identity24(), kappa, kD, side, stitch, p.share);
    t.tag_last("knit.compression_stiffness_N_per_m", kappa);
  }
  return t;
}

TEST(StackedStitchCompression, PairForcesJacobiansAndParameterDerivativesMatchFiniteDifferences) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> height(0.15 * kD, 0.85 * kD);  // every pair squeezed
  for (const auto& [side, stitch] : {std::pair{1, 1}, std::pair{-1, -1}, std::pair{-1, 1}}) {
    std::vector<test::LocalState> states;
    for (int s = 0; s < 3; ++s) states.push_back({random_stack_state(height(rng), side, stitch, rng), {}});
    for (auto& s : states) s.v.assign(24, 0.0);
    const StitchCompressionTerm t = stacked_compression(150.0, side, stitch);
    test::FdOptions opt;
    opt.rel_step = 1e-7;
    opt.floor = 1e-14;
    for (int e = 0; e < 3; ++e) {
      for (const auto& s : states) EXPECT_GT(t.energy(e, s.q.data()), 0.0) << "pair " << e << " should be squeezed";
      auto r = test::check_element(t, e, states, opt);
      EXPECT_TRUE(r.ok) << "pair " << e << ": " << r.detail;
      auto make = [&](double k) {
        return std::unique_ptr<Term>(new StitchCompressionTerm(stacked_compression(k, side, stitch)));
      };
      r = test::check_parameter_derivative(make, 150.0, 0, e, states, opt);
      EXPECT_TRUE(r.ok) << "pair " << e << ": " << r.detail;
    }
  }
}

TEST(StackedStitchCompression, EnergyIsTheSumOverEveryPairOfTheStack) {
  // A flat loop, the stack h = 0.3 mm through it: the neighbouring pairs
  // 0.15 mm apart, the outer pair 0.3 mm, each against 2R = 0.4 mm.
  std::vector<double> q(24);
  const double nodes[8][3] = {{0, 0, -0.15}, {0, 0.5, 0.15}, {1, 0, 0},   {1, 0.5, 0},
                              {0, -1.6, 0},  {0, -1.1, 0},   {0, 1.6, 0}, {0, 2.1, 0}};
  for (int k = 0; k < 8; ++k)
    for (int d = 0; d < 3; ++d) q[3 * k + d] = 1e-3 * nodes[k][d];
  const double kappa = 200.0;
  const StitchCompressionTerm t = stacked_compression(kappa, 1, 1);
  double total = 0.0;
  for (int e = 0; e < t.num_elements(); ++e) total += t.energy(e, q.data());
  const double near = 0.4e-3 - 0.15e-3, outer = 0.4e-3 - 0.3e-3;
  EXPECT_NEAR(total, 2.0 * 0.5 * kappa * near * near + 0.5 * kappa * outer * outer, 1e-15);
  // Opened to h = 0.6 mm: only the neighbouring pairs (0.3 mm apart) still push.
  q[2] = -0.3e-3;
  q[5] = 0.3e-3;
  total = 0.0;
  for (int e = 0; e < t.num_elements(); ++e) total += t.energy(e, q.data());
  EXPECT_NEAR(total, 2.0 * 0.5 * kappa * 0.1e-3 * 0.1e-3, 1e-15);
  // The force on b: F = Σ κ (D − φh) φ n = 2 κ (0.1 mm) ½ along +z.
  double fz = 0.0;
  for (int e = 0; e < t.num_elements(); ++e) {
    std::vector<double> f(24, 0.0), v(24, 0.0);
    t.evaluate(e, q.data(), v.data(), ElementOutput{f.data()});
    fz += f[5];
  }
  EXPECT_NEAR(fz, kappa * 0.1e-3, 1e-12);
}

// Three yarns through a stitch segment x0→x1 (millimetre scale), leaving it
// towards y0, y1 (the two heads of a decrease) and y2 (the leg): 15 entries.
std::vector<double> three_yarn_stitch() {
  return {0.0,     0.0,    -0.3e-3, 0.0,    0.5e-3,  0.3e-3, 1.0e-3, 0.7e-3,
          -0.1e-3, 0.9e-3, 0.9e-3,  0.2e-3, -0.3e-3, 1.4e-3, 0.4e-3};
}

// The roll element of pair (i, j): x0, x1, the next node of yarn i, of yarn j.
std::vector<double> roll_local(const std::vector<double>& x, const StackPair& p) {
  std::vector<double> l(x.begin(), x.begin() + 6);
  l.insert(l.end(), x.begin() + 6 + 3 * p.i, x.begin() + 9 + 3 * p.i);
  l.insert(l.end(), x.begin() + 6 + 3 * p.j, x.begin() + 9 + 3 * p.j);
  return l;
}

// The roll of every pair of the three yarns, rest angles at `rest`.
StitchRollTerm stacked_roll(const std::vector<double>& rest, double kt, double length) {
  StitchRollTerm t;
  for (const StackPair& p : stack_pairs(3))
    t.add({0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11}, kt, length, StitchRollTerm::angle(roll_local(rest, p).data()),
          StitchRollTerm::opening(roll_local(rest, p).data()));
  return t;
}

// Yarn k's next node turned by `angle` about the stitch segment.
std::vector<double> turned(std::vector<double> x, int k, double angle) {
  const Eigen::Vector3d x0(x[0], x[1], x[2]), x1(x[3], x[4], x[5]);
  const Eigen::Vector3d y(x[6 + 3 * k], x[7 + 3 * k], x[8 + 3 * k]);
  const Eigen::Vector3d r = x0 + Eigen::AngleAxisd(angle, (x1 - x0).normalized()) * (y - x0);
  for (int d = 0; d < 3; ++d) x[6 + 3 * k + d] = r[d];
  return x;
}

TEST(StackedStitchRoll, PairForcesAndJacobiansMatchFiniteDifferences) {
  const std::vector<double> rest = three_yarn_stitch();
  const StitchRollTerm t = stacked_roll(rest, 0.02, 0.58e-3);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> turn(-1.0, 1.0), jitter(-0.05e-3, 0.05e-3);
  std::vector<std::vector<double>> stacks;
  for (int s = 0; s < 3; ++s) {
    std::vector<double> x = rest;
    for (int k = 0; k < 3; ++k) x = turned(x, k, turn(rng));
    for (double& c : x) c += jitter(rng);
    stacks.push_back(x);
  }
  test::FdOptions opt;
  opt.floor = 1e-14;
  const std::vector<StackPair> pairs = stack_pairs(3);
  for (int e = 0; e < 3; ++e) {
    std::vector<test::LocalState> states;
    for (const auto& x : stacks) states.push_back({roll_local(x, pairs[e]), std::vector<double>(12, 0.0)});
    const auto r = test::check_element(t, e, states, opt);
    EXPECT_TRUE(r.ok) << "pair " << e << ": " << r.detail;
  }
}

TEST(StackedStitchRoll, TurningOneYarnTurnsItAgainstBothOthers) {
  // Each yarn turned alone by δ about the segment turns two pairs by δ:
  // V = 2 k_t L (1 − cos δ) (≈ 2 · ½ k_t L δ², §11.4.1), whichever yarn (a dropped pair leaves half of that
  // for two of them).
  const std::vector<double> rest = three_yarn_stitch();
  const double kt = 0.02, L = 0.58e-3, delta = 0.3;
  const StitchRollTerm t = stacked_roll(rest, kt, L);
  const std::vector<StackPair> pairs = stack_pairs(3);
  for (int k = 0; k < 3; ++k) {
    const std::vector<double> x = turned(rest, k, delta);
    double total = 0.0;
    for (int e = 0; e < 3; ++e) total += t.energy(e, roll_local(x, pairs[e]).data());
    EXPECT_NEAR(total, 2.0 * kt * L * (1.0 - std::cos(delta)), 1e-12 * kt * L) << "yarn " << k;
  }
  // The three pair angles are not independent: with θ_k the azimuth of yarn k's
  // plane about the segment, ψ_ij = θ_i − θ_j + π, so ψ02 = ψ01 + ψ12 − π (mod 2π).
  const double psi01 = StitchRollTerm::angle(roll_local(rest, pairs[0]).data());
  const double psi02 = StitchRollTerm::angle(roll_local(rest, pairs[1]).data());
  const double psi12 = StitchRollTerm::angle(roll_local(rest, pairs[2]).data());
  EXPECT_NEAR(std::remainder(psi02 - psi01 - psi12 + M_PI, 2.0 * M_PI), 0.0, 1e-12);
}

// A patch around one three-yarn stitch contact (a, b), every term that acts at
// its slots assembled as the knit model wires them (docs/models.md §11.4):
// yarn i comes from p_i, passes a then b in its slot i and leaves to y_i;
// stretch on its three segments, bending at a and b, its stitch-length penalty
// on a→b; the roll and the contact compression per pair of the yarns, the
// compression with the contact on the other side of the loop (a', b') and
// those below (da, db) and above (ua, ub). Nodes: a, b, p0..p2, y0..y2, a', b',
// da, db, ua, ub (3 DoFs each), then the coordinates: a's three slots, b's
// three, one on each p_i and y_i.
struct StackParameters {
  double ks = 0.06, kb = 2e-8, kl = 0.1, kt = 1e-3, kappa = 100.0;
};

class StackedStitchPatch : public TermModel {
 public:
  explicit StackedStitchPatch(const StackParameters& k) {
    const double mm = 1e-3;
    const double x[14][3] = {{0, 0, -0.4},       {0, 0.5, 0.4},    {-0.5, -0.9, 0.1}, {0.5, -0.9, 0.05},
                             {-0.1, -0.6, -0.5}, {1.0, 0.8, -0.2}, {1.0, 0.7, -0.45}, {-0.3, 1.3, 0.3},
                             {1.0, 0.0, 0.0},    {1.0, 0.5, 0.0},  {0.0, -1.6, 0.0},  {0.0, -1.1, 0.0},
                             {0.0, 1.6, 0.0},    {0.0, 2.1, 0.0}};
    num_dofs_ = 14 * 3 + 12;
    q0_ = Vec::Zero(num_dofs_);
    v0_ = Vec::Zero(num_dofs_);
    for (int n = 0; n < 14; ++n)
      for (int d = 0; d < 3; ++d) q0_[3 * n + d] = mm * x[n][d];
    auto pos = [&](int n) { return Vec3(q0_.segment<3>(3 * n)); };
    auto xs = [](int n) { return std::array<int, 3>{3 * n, 3 * n + 1, 3 * n + 2}; };
    auto stretch = std::make_unique<StretchTerm>();
    auto bending = std::make_unique<BendingTerm>();
    auto length = std::make_unique<StitchLengthTerm>();
    for (int i = 0; i < 3; ++i) {
      const int p = 2 + i, y = 5 + i, ua = u_a(i), ub = u_a(i) + 3, up = 48 + i, uy = 51 + i;
      // Arc lengths along p_i → a → b → y_i, each segment 2 % longer than its chord (a slack yarn).
      q0_[up] = 0.0;
      q0_[ua] = 1.02 * (pos(0) - pos(p)).norm();
      q0_[ub] = q0_[ua] + 1.02 * (pos(1) - pos(0)).norm();
      q0_[uy] = q0_[ub] + 1.02 * (pos(y) - pos(1)).norm();
      const int seg[3][4] = {{p, 0, up, ua}, {0, 1, ua, ub}, {1, y, ub, uy}};
      for (const auto& s : seg) {
        const auto x0 = xs(s[0]), x1 = xs(s[1]);
        stretch->add({x0[0], x0[1], x0[2], x1[0], x1[1], x1[2], s[2], s[3]}, k.ks);
        stretch->tag_last("stretch", k.ks);
      }
      // Bending at a (neighbours b, p_i) and at b (neighbours y_i, a), the knit model's stencil.
      const int bend[2][5] = {{0, 1, p, ub, up}, {1, y, 0, uy, ua}};
      for (const auto& s : bend) {
        const auto c = xs(s[0]), nx = xs(s[1]), pv = xs(s[2]);
        bending->add({c[0], c[1], c[2], nx[0], nx[1], nx[2], pv[0], pv[1], pv[2], s[3], s[4]}, k.kb);
        bending->tag_last("bending", k.kb);
      }
      length->add({ua, ub}, k.kl, (pos(1) - pos(0)).norm());
      length->tag_last("stitch_length", k.kl);
    }
    auto roll = std::make_unique<StitchRollTerm>();
    auto compression = std::make_unique<StitchCompressionTerm>();
    std::array<int, 24> st{};
    for (int e = 0; e < 8; ++e)
      for (int d = 0; d < 3; ++d) st[3 * e + d] = 3 * (e < 2 ? e : e + 6) + d;
    for (const StackPair& pr : stack_pairs(3)) {
      const auto x0 = xs(0), x1 = xs(1), x3 = xs(5 + pr.i), x5 = xs(5 + pr.j);
      Eigen::Matrix<double, 12, 1> rest;
      rest << pos(0), pos(1), pos(5 + pr.i), pos(5 + pr.j);
      roll->add({x0[0], x0[1], x0[2], x1[0], x1[1], x1[2], x3[0], x3[1], x3[2], x5[0], x5[1], x5[2]}, k.kt,
                (pos(1) - pos(0)).norm(), StitchRollTerm::angle(rest.data()), StitchRollTerm::opening(rest.data()));
      roll->tag_last("roll", k.kt);
      compression->add(st, k.kappa, kD, 1, 1, pr.share);
      compression->tag_last("compression", k.kappa);
    }
    terms_.push_back(std::move(stretch));
    terms_.push_back(std::move(bending));
    terms_.push_back(std::move(length));
    terms_.push_back(std::move(roll));
    terms_.push_back(std::move(compression));
    finalize();
  }
  static int u_a(int slot) { return 42 + slot; }
  std::unique_ptr<Model> clone() const override { return std::make_unique<StackedStitchPatch>(*this); }
  std::string name() const override { return "stacked-stitch"; }
  bool mass_depends_on_q() const override { return false; }
  Frame frame(double, const Vec&, const Vec&) const override { return {}; }
  std::map<std::string, std::string> describe() const override { return {}; }
};

Vec patch_force(const StackedStitchPatch& m, const Vec& q, SparseMatrix* dfdq = nullptr) {
  Evaluation e;
  allocate_evaluation(m, e);
  StackedStitchPatch copy = m;
  copy.evaluate(0.0, q, Vec::Zero(q.size()), dfdq ? kForce | kDfdq : kForce, e);
  if (dfdq) *dfdq = e.dfdq;
  return e.force;
}

// Random states about the generated patch: positions moved by up to 0.08 mm,
// coordinates by up to 0.03 mm, the stack squeezed to h = 0.2 ± 0.16 mm (< 2R: every pair pushes).
std::vector<Vec> random_patch_states(const StackedStitchPatch& m) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> move(-1.0, 1.0);
  std::vector<Vec> states;
  for (int s = 0; s < 3; ++s) {
    Vec q = m.initial_q();
    q[2] = -0.1e-3;
    q[5] = 0.1e-3;
    for (int k = 0; k < q.size(); ++k) q[k] += (k < 42 ? 0.08e-3 : 0.03e-3) * move(rng);
    states.push_back(q);
  }
  return states;
}

TEST(StackedStitchPatch, AssembledForceJacobianAndParameterDerivativesMatchFiniteDifferences) {
  const StackParameters k;
  const StackedStitchPatch m(k);
  ASSERT_EQ(m.terms().size(), 5u);
  std::vector<int> all(m.num_dofs());
  for (int j = 0; j < m.num_dofs(); ++j) all[j] = j;
  test::FdOptions opt;
  opt.rel_step = 1e-7;
  opt.rtol = 1e-5;
  for (const Vec& q : random_patch_states(m)) {
    // Every term active at the state (a check of something) …
    const Vec zero = Vec::Zero(m.num_dofs());
    for (const auto& term : m.terms()) {
      std::vector<double> lq(term->stencil_size()), lv(term->stencil_size());
      for (int e = 0; e < term->num_elements(); ++e) {
        m.gather_local(*term, e, q, zero, lq.data(), lv.data());
        EXPECT_GT(term->energy(e, lq.data()), 0.0) << term->name() << " element " << e;
      }
    }
    // … the force against the energy, ∂f/∂q against differences of the force …
    SparseMatrix K;
    const Vec f = patch_force(m, q, &K);
    auto energy = [&](const Vec& x) { return Vec::Constant(1, m.potential_energy(x)); };
    auto r = test::check_jacobian_columns(
        energy, q, [&](int j) { return Vec::Constant(1, -f[j]); }, all, opt);
    EXPECT_TRUE(r.ok) << "force: " << r.detail;
    r = test::check_jacobian_columns([&](const Vec& x) { return patch_force(m, x); }, q,
                                     [&](int j) { return Vec(K.col(j)); }, all, opt);
    EXPECT_TRUE(r.ok) << "dfdq: " << r.detail;
    // … and ∂f/∂p of every term's parameter against differences over rebuilt patches.
    for (const auto& [key, field] :
         {std::pair{"stretch", &StackParameters::ks}, std::pair{"bending", &StackParameters::kb},
          std::pair{"stitch_length", &StackParameters::kl}, std::pair{"roll", &StackParameters::kt},
          std::pair{"compression", &StackParameters::kappa}}) {
      // In the parameter's scale s (p = s·p₀, s = 1): ∂f/∂s = p₀ ∂f/∂p (x = (s, 0): the
      // checker's step is relative to the extent of x).
      Vec dfdp;
      ASSERT_TRUE(m.force_parameter_derivative(key, 0.0, q, zero, dfdp)) << key;
      auto force_at = [&](const Vec& s) {
        StackParameters kp = k;
        kp.*field = s[0] * k.*field;
        return patch_force(StackedStitchPatch(kp), q);
      };
      r = test::check_jacobian_columns(
          force_at, Vec::Unit(2, 0), [&](int) { return Vec(k.*field * dfdp); }, {0}, opt);
      EXPECT_TRUE(r.ok) << key << ": " << r.detail;
    }
  }
}

}  // namespace
}  // namespace wl
