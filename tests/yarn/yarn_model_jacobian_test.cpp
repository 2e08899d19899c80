// The assembled Jacobians and mass of the shipped scene (hanging_wind.toml: Gong
// shear, Gong friction, inertia with sliding, wind, handles) against finite
// differences, block by block (x, u, v rows × x, u, v columns), each block with
// its own relative error.
//
// F_n and F_u are evaluated once per force evaluation and held frozen in the
// Jacobians (docs/models.md §5.4), so the assembled Jacobian is the exact
// derivative of the force with F_n, F_u frozen: that is what is checked to
// 1e-6 per block. The part it neglects (∂F_n/∂q, ∂F_u/∂q, ∂F_u/∂v) is measured
// separately against differences of the full force and must stay the size
// docs/models.md §5.4 states.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <iostream>
#include <random>

#include "calibration/scene_parameters.h"
#include "integrators/backward_euler.h"
#include "models/scene/scene.h"
#include "models/yarn/yarn_model.h"
#include "tests/yarn/model_blocks.h"

namespace wl {
namespace {

using test::Blocks;
using test::dof_kinds;
using test::frozen_force;
using test::kDofKind;

class ShippedScene : public ::testing::Test {
 protected:
  // The shipped scene after 20 steps of its integrator: sheared, stretched and
  // sliding, with F_n > 0 at the crossings; velocities from the motion.
  static void SetUpTestSuite() {
    model_ = new YarnModel(load_scene(WEAVELAB_SOURCE_DIR "/experiments/scenes/hanging_wind.toml"));
    BackwardEuler be(BackwardEuler::Variant::linear);
    IntegratorOptions opt;
    opt.dt = 1e-3;
    be.initialize(*model_, 0.0, model_->initial_q(), model_->initial_v(), opt);
    ASSERT_EQ(be.advance_to(0.02).outcome, Outcome::ok);
    q_ = new Vec(be.q());
    v_ = new Vec(be.v());
  }
  static void TearDownTestSuite() {
    delete model_;
    delete q_;
    delete v_;
  }
  // Seeded sample of free columns, `per_kind` of each kind.
  std::vector<int> sample_columns(int per_kind) const {
    const std::vector<int> kind = dof_kinds(*model_);
    std::vector<std::vector<int>> by_kind(3);
    std::vector<char> fixed(model_->num_dofs(), 0);
    for (int f : model_->fixed_dofs()) fixed[f] = 1;
    for (int k = 0; k < model_->num_dofs(); ++k)
      if (!fixed[k]) by_kind[kind[k]].push_back(k);
    std::mt19937 rng(17);
    std::vector<int> cols;
    for (auto& list : by_kind) {
      std::shuffle(list.begin(), list.end(), rng);
      cols.insert(cols.end(), list.begin(), list.begin() + std::min<int>(per_kind, list.size()));
    }
    return cols;
  }
  static double extent(const Vec& x) { return x.maxCoeff() - x.minCoeff(); }
  // The shipped scene with F_n and F_u differentiated or frozen (docs/models.md §3.6.1).
  static Scene shipped(bool exact) {
    Scene s = load_scene(WEAVELAB_SOURCE_DIR "/experiments/scenes/hanging_wind.toml");
    s.exact_contact_jacobian = exact;
    return s;
  }

  static YarnModel* model_;
  static Vec* q_;
  static Vec* v_;
};
YarnModel* ShippedScene::model_ = nullptr;
Vec* ShippedScene::q_ = nullptr;
Vec* ShippedScene::v_ = nullptr;

TEST_F(ShippedScene, JacobiansMatchDifferencesOfTheFrozenForcePerBlock) {
  YarnModel& m = *model_;
  const Vec &q = *q_, &v = *v_;
  const std::vector<int> kind = dof_kinds(m);
  Evaluation ev;
  allocate_evaluation(m, ev);
  m.evaluate(0.02, q, v, kForce | kDfdq | kDfdv | kMass, ev);  // F_n, F_u frozen here
  const Vec f0 = ev.force;
  const SparseMatrix K = ev.dfdq, D = ev.dfdv;
  ASSERT_LT((frozen_force(m, q, v) - f0).norm(), 1e-12 * f0.norm()) << "the frozen force is the model's force";

  // Velocity steps are large: every force is at most quadratic in v (exact under central
  // differences) except the wind's, smooth on the scale of the wind speed; small steps
  // would drown the small u–x inertia entries in the rounding of the large friction damping.
  const double hq = 1e-6 * extent(q), hv = 1e-2 * extent(v);
  Blocks dq, dv;
  Blocks neglected_q, neglected_v;  // full force (F_n, F_u recomputed) against the frozen one
  std::vector<std::pair<Vec, Vec>> frozen_cols;
  const std::vector<int> cols = sample_columns(40);
  for (int c : cols) {
    Vec qp = q, qm = q, vp = v, vm = v;
    qp[c] += hq;
    qm[c] -= hq;
    vp[c] += hv;
    vm[c] -= hv;
    const Vec fq = (frozen_force(m, qp, v) - frozen_force(m, qm, v)) / (2 * hq);
    const Vec fv = (frozen_force(m, q, vp) - frozen_force(m, q, vm)) / (2 * hv);
    dq.add(kind, c, fq, Vec(K.col(c)));
    dv.add(kind, c, fv, Vec(D.col(c)));
    frozen_cols.emplace_back(fq, fv);
  }
  // Differences of the full force: each evaluation recomputes F_n and F_u.
  for (size_t k = 0; k < cols.size(); ++k) {
    const int c = cols[k];
    Evaluation ep, em;
    Vec qp = q, qm = q, vp = v, vm = v;
    qp[c] += hq;
    qm[c] -= hq;
    vp[c] += hv;
    vm[c] -= hv;
    m.evaluate(0.02, qp, v, kForce, ep);
    m.evaluate(0.02, qm, v, kForce, em);
    neglected_q.add(kind, c, (ep.force - em.force) / (2 * hq), frozen_cols[k].first);
    m.evaluate(0.02, q, vp, kForce, ep);
    m.evaluate(0.02, q, vm, kForce, em);
    neglected_v.add(kind, c, (ep.force - em.force) / (2 * hv), frozen_cols[k].second);
  }

  double worst_neglected = 0.0;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) {
      const std::string block = std::string(kDofKind[r]) + "-" + kDofKind[c];
      // No term couples a crossing's u with its v (docs/models.md §2.4): those two blocks
      // are zero in both; every other block of ∂f/∂q is non-zero on the shipped scene.
      if (r + c == 3 && r != 0) {
        EXPECT_EQ(dq.ref[r][c] + dq.diff[r][c], 0.0) << "df/dq " << block << " should be zero";
        continue;
      }
      ASSERT_GT(dq.ref[r][c], 0.0) << "df/dq " << block;
      EXPECT_LT(dq.relative(r, c), 1e-6) << "df/dq " << block;
      if (dv.ref[r][c] > 0.0) EXPECT_LT(dv.relative(r, c), 1e-6) << "df/dv " << block;
      else EXPECT_EQ(dv.diff[r][c], 0.0) << "df/dv " << block << " should be zero";
      const double nq = neglected_q.relative(r, c);
      const double nv = neglected_v.ref[r][c] > 0.0 ? neglected_v.relative(r, c) : 0.0;
      worst_neglected = std::max({worst_neglected, nq, nv});
      std::cout << "block " << block << ": df/dq rel. error " << dq.relative(r, c) << ", df/dv rel. error "
                << (dv.ref[r][c] > 0.0 ? dv.relative(r, c) : 0.0) << "; neglected part (frozen F_n, F_u) " << nq
                << " of df/dq, " << nv << " of df/dv\n";
    }
  // docs/models.md §5.4: the neglected part is real (F_n and F_u do depend on the
  // state; measured 9.0e-5 of the x–u block) and below 2e-4 of every block here.
  EXPECT_GT(worst_neglected, 1e-5);
  EXPECT_LT(worst_neglected, 2e-4);
}

TEST_F(ShippedScene, MassBlocksMatchTheInertialForce) {
  // f_inertia(q, v) = ∂T/∂q − Ṁq̇ with T = ½ q̇ᵀM(q)q̇ (docs/models.md §3.1.2), with M the
  // assembled mass differenced in q and along q̇; compared per row kind.
  // The motion's sliding velocities are tiny, so ∂T/∂u and Ṁq̇ nearly cancel on u, v rows;
  // seeded random velocities of 5 cm/s on every DoF make the inertial force of
  // each row kind as large as its parts.
  YarnModel& m = *model_;
  const Vec& q = *q_;
  Vec v = *v_;
  std::mt19937 rng(5);
  std::normal_distribution<double> nd(0.0, 0.05);
  for (int k = 0; k < v.size(); ++k) v[k] += nd(rng);
  const std::vector<int> kind = dof_kinds(m);
  Evaluation ev, ep, em;
  m.evaluate(0.02, q, v, kForce | kMass, ev);
  const SparseMatrix M = ev.mass;
  EXPECT_EQ((M - SparseMatrix(M.transpose())).norm(), 0.0) << "mass symmetric";
  const Vec f_inertia = frozen_force(m, q, v, true);
  const double hq = 1e-6 * extent(q);
  const std::vector<int> cols = sample_columns(40);
  std::array<double, 3> ref{}, diff{};
  const double eps = hq / v.lpNorm<Eigen::Infinity>();
  m.evaluate(0.02, q + eps * v, v, kMass, ep);
  m.evaluate(0.02, q - eps * v, v, kMass, em);
  const Vec mdot_v = (ep.mass - em.mass) * v / (2 * eps);
  for (int c : cols) {
    Vec qp = q, qm = q;
    qp[c] += hq;
    qm[c] -= hq;
    m.evaluate(0.02, qp, v, kMass, ep);
    m.evaluate(0.02, qm, v, kMass, em);
    const double expected = 0.5 * v.dot((ep.mass - em.mass) * v) / (2 * hq) - mdot_v[c];
    ref[kind[c]] += expected * expected;
    diff[kind[c]] += (f_inertia[c] - expected) * (f_inertia[c] - expected);
  }
  for (int r = 0; r < 3; ++r) {
    ASSERT_GT(ref[r], 0.0) << kDofKind[r];
    std::cout << "inertial force on " << kDofKind[r] << " rows: rel. error " << std::sqrt(diff[r] / ref[r]) << "\n";
    EXPECT_LT(std::sqrt(diff[r] / ref[r]), 1e-6) << "inertial force on " << kDofKind[r] << " rows";
  }
}

// With time.exact_contact_jacobian the assembled Jacobians are the derivative of
// the full force, F_n and F_u recomputed at every evaluation (docs/models.md
// §3.6.1): within 1e-6 of each block, a tolerance the frozen Jacobians miss
// by far (their neglected part is 1e-5 to 2e-4, docs/models.md §5.4).
TEST_F(ShippedScene, ExactContactJacobianMatchesDifferencesOfTheFullForce) {
  YarnModel exact(shipped(true)), frozen(shipped(false));
  ASSERT_GT(exact.pattern().nonZeros(), frozen.pattern().nonZeros());
  const Vec &q = *q_, &v = *v_;
  const std::vector<int> kind = dof_kinds(exact);
  Evaluation ee, ef;
  exact.evaluate(0.02, q, v, kForce | kDfdq | kDfdv, ee);
  frozen.evaluate(0.02, q, v, kForce | kDfdq | kDfdv, ef);
  ASSERT_EQ((ee.force - ef.force).norm(), 0.0) << "the option changes no force";
  // The full force curves more in u than the frozen one (F_u moves with the
  // state): a step 10× smaller than above (truncation measured 7.5e-6 of the
  // u–u block at 1e-6, 1.5e-7 at 1e-7).
  const double hq = 1e-7 * extent(q), hv = 1e-2 * extent(v);
  Blocks eq, fq, ev, fv;
  for (int c : sample_columns(40)) {
    Evaluation ep, em;
    Vec qp = q, qm = q, vp = v, vm = v;
    qp[c] += hq, qm[c] -= hq, vp[c] += hv, vm[c] -= hv;
    frozen.evaluate(0.02, qp, v, kForce, ep);
    frozen.evaluate(0.02, qm, v, kForce, em);
    const Vec dq = (ep.force - em.force) / (2 * hq);
    frozen.evaluate(0.02, q, vp, kForce, ep);
    frozen.evaluate(0.02, q, vm, kForce, em);
    const Vec dv = (ep.force - em.force) / (2 * hv);
    eq.add(kind, c, dq, Vec(ee.dfdq.col(c)));
    fq.add(kind, c, dq, Vec(ef.dfdq.col(c)));
    ev.add(kind, c, dv, Vec(ee.dfdv.col(c)));
    fv.add(kind, c, dv, Vec(ef.dfdv.col(c)));
  }
  constexpr double kTol = 1e-6;
  double worst_exact = 0.0, worst_frozen = 0.0;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) {
      const std::string block = std::string(kDofKind[r]) + "-" + kDofKind[c];
      const double e1 = eq.ref[r][c] > 0.0 ? eq.relative(r, c) : 0.0, f1 = fq.ref[r][c] > 0.0 ? fq.relative(r, c) : 0.0;
      const double e2 = ev.ref[r][c] > 0.0 ? ev.relative(r, c) : 0.0, f2 = fv.ref[r][c] > 0.0 ? fv.relative(r, c) : 0.0;
      EXPECT_LT(std::max(e1, e2), kTol) << block;
      worst_exact = std::max({worst_exact, e1, e2});
      worst_frozen = std::max({worst_frozen, f1, f2});
      std::cout << "block " << block << ": exact df/dq " << e1 << ", df/dv " << e2 << "; frozen df/dq " << f1
                << ", df/dv " << f2 << "\n";
    }
  std::cout << "worst block error: exact " << worst_exact << ", frozen " << worst_frozen << " (tolerance " << kTol
            << ")\n";
  EXPECT_GT(worst_frozen, 10 * kTol) << "the frozen Jacobians fail this tolerance";
}

// ∂f/∂p of the exact model against differences of the full force in p, for
// every parameter; the frozen model misses what passes through F_n and F_u.
TEST_F(ShippedScene, ExactContactParameterDerivativesMatchDifferences) {
  const Scene s = shipped(false);
  YarnModel exact(shipped(true)), frozen(s);
  const Vec &q = *q_, &v = *v_;
  Evaluation ev;
  exact.evaluate(0.02, q, v, kForce, ev);
  frozen.evaluate(0.02, q, v, kForce, ev);
  double worst_frozen = 0.0;
  for (const std::string& key : exact.parameter_keys()) {
    const double p = scene_parameter(s, key), eps = 1e-6;
    Scene hi = s, lo = s;
    set_scene_parameter(hi, key, p * (1 + eps));
    set_scene_parameter(lo, key, p * (1 - eps));
    YarnModel mh(hi), ml(lo);
    Evaluation eh, el;
    mh.evaluate(0.02, q, v, kForce, eh);
    ml.evaluate(0.02, q, v, kForce, el);
    const Vec fd = (eh.force - el.force) / (2 * eps * p);
    Vec de, df;
    exact.force_parameter_derivative(key, 0.02, q, v, de);
    frozen.force_parameter_derivative(key, 0.02, q, v, df);
    ASSERT_GT(fd.norm(), 0.0) << key;
    const double err = (de - fd).norm() / fd.norm(), err_frozen = (df - fd).norm() / fd.norm();
    std::cout << key << ": exact " << err << ", frozen " << err_frozen << "\n";
    EXPECT_LT(err, 1e-6) << key;
    worst_frozen = std::max(worst_frozen, err_frozen);
  }
  EXPECT_GT(worst_frozen, 1e-5);
}

}  // namespace
}  // namespace wl
