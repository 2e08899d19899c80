// Yarn–yarn contact between capsules (docs/models.md §11.10): the edge–edge
// barrier on the gap g = d − 2R against finite differences in every
// closest-feature region (interior–interior, endpoint–interior, endpoint–
// endpoint, parallel segments) on both sides of the switch between two regions
// and down to gaps of 10⁻³ d̂; parallel overlapping segments; the assembled
// term's force and step stiffness; two yarns fired at each other never pass
// through one another under be-linear, be-newton and sdirk2, and so do two
// yarns whose pairs are modelled (their barrier on the core distance D_c < 2R:
// their capsules may overlap, their cores never).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include <Eigen/Eigenvalues>

#include "integrators/integrator.h"
#include "models/common/obstacle_barrier.h"
#include "models/common/self_contact.h"
#include "models/core/term_model.h"
#include "tests/support/fd_check.h"
#include "tests/support/node_mass.h"

namespace wl {
namespace {

constexpr double kDhat = 1e-3, kKappa = 1e4, kLength = 1e-2, kRadius = 1e-3;

std::vector<double> flatten(const std::array<Vec3, 4>& x) {
  std::vector<double> q;
  for (const Vec3& p : x) q.insert(q.end(), p.data(), p.data() + 3);
  return q;
}

struct Case {
  const char* name;
  std::array<Vec3, 4> x;   // segments x0x1 and x2x3
  unsigned first, second;  // the expected support
  double distance;         // between the centrelines
};

// The segment pairs with centrelines d = 2R + g apart, one per region and two
// on each side of the switch from interior–interior to endpoint–interior
// (the crossing at ε = 10⁻³ L inside and outside the first segment's end).
std::vector<Case> cases(double g) {
  const double d = 2.0 * kRadius + g, a = 0.6 * d, b = 0.8 * d, L = kLength, eps = 1e-3 * L;
  const Vec3 o(0, 0, 0), ex(L, 0, 0);
  return {
      {"interior-interior", {o, ex, Vec3(0.5 * L, -0.5 * L, d), Vec3(0.5 * L, 0.5 * L, d)}, 0b0011u, 0b1100u, d},
      {"endpoint-interior", {o, ex, Vec3(0.5 * L, 0, d), Vec3(0.5 * L, 0.2 * L, d + L)}, 0b0011u, 0b0100u, d},
      {"endpoint-endpoint", {o, ex, Vec3(L + a, 0.6 * b, 0.8 * b), Vec3(2 * L, L, L)}, 0b0010u, 0b0100u, d},
      {"parallel, apart along their line", {o, ex, Vec3(L + a, 0, b), Vec3(2 * L + a, 0, b)}, 0b0010u, 0b0100u, d},
      {"switch, inside", {o, ex, Vec3(L - eps, -0.5 * L, d), Vec3(L - eps, 0.5 * L, d)}, 0b0011u, 0b1100u, d},
      {"switch, outside",
       {o, ex, Vec3(L + eps, -0.5 * L, d), Vec3(L + eps, 0.5 * L, d)},
       0b0010u,
       0b1100u,
       std::hypot(eps, d)},
  };
}

SelfContactPairTerm capsule_pair() {
  SelfContactPairTerm term(kDhat, kKappa, 2.0 * kRadius);
  term.add({0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11}, PairKind::edge_edge);
  return term;
}

TEST(CapsulePair, ForceAndJacobianMatchFiniteDifferencesInEveryRegionDownToSmallGaps) {
  for (double s : {1e-3, 0.1, 0.7})
    for (const Case& c : cases(s * kDhat)) {
      const ClosestPoints cp = closest_support(PairKind::edge_edge, c.x);
      EXPECT_EQ(cp.support.first, c.first) << c.name;
      EXPECT_EQ(cp.support.second, c.second) << c.name;
      EXPECT_NEAR(cp.distance, c.distance, 1e-15) << c.name;
      const SelfContactPairTerm term = capsule_pair();
      // Steps and random moves well inside the gap and the region: FD step
      // 10⁻³ g, moves up to 0.05 g (the switch cases are 10⁻³ L from it).
      const double gap = c.distance - 2.0 * kRadius, extent = 2.0 * kLength + c.distance;
      test::FdOptions opt;
      opt.rel_step = 1e-3 * gap / extent;
      opt.jitter = 0.05 * gap / extent;
      opt.rtol = 1e-5;
      const test::FdReport r = test::check_element(term, 0, {{flatten(c.x), std::vector<double>(12, 0.0)}}, opt);
      EXPECT_TRUE(r.ok) << c.name << " at g = " << s << " d̂: " << r.detail;
    }
}

// Across the switch the force is continuous: at ε inside and outside the
// first segment's end it differs by O(ε/L) of itself.
TEST(CapsulePair, ForceIsContinuousThroughTheSwitchOfRegions) {
  const std::vector<Case> all = cases(0.1 * kDhat);
  const SelfContactPairTerm term = capsule_pair();
  Eigen::Matrix<double, 12, 1> inside = Eigen::Matrix<double, 12, 1>::Zero(), outside = inside;
  term.evaluate(0, flatten(all[4].x).data(), nullptr, ElementOutput{inside.data()});
  term.evaluate(0, flatten(all[5].x).data(), nullptr, ElementOutput{outside.data()});
  ASSERT_GT(inside.norm(), 0.0);
  EXPECT_LT((inside - outside).norm(), 0.05 * inside.norm());
}

// Parallel overlapping segments: every point of the overlap is closest (the
// interiors' system is singular); the gap is their separation less 2R, the
// force on each segment is −κ b'(g) along it, and it is the gradient of the
// energy along translations of the second segment (the tie does not break).
TEST(CapsulePair, ParallelOverlappingSegmentsPushApartAlongTheirSeparation) {
  const double g = 0.3 * kDhat, sep = 2.0 * kRadius + g, dy = 0.6 * sep, dz = 0.8 * sep;
  const Vec3 n(0, 0.6, 0.8);
  for (double tilt : {0.0, 1e-9}) {
    const std::array<Vec3, 4> x = {Vec3(0, 0, 0), Vec3(kLength, 0, 0), Vec3(0.5 * kLength, dy, dz),
                                   Vec3(1.5 * kLength, dy, dz + tilt * kLength)};
    const SelfContactPairTerm term = capsule_pair();
    const std::vector<double> q = flatten(x);
    Eigen::Matrix<double, 12, 1> f = Eigen::Matrix<double, 12, 1>::Zero();
    term.evaluate(0, q.data(), nullptr, ElementOutput{f.data()});
    const Vec3 on_first = f.segment<3>(0) + f.segment<3>(3), on_second = f.segment<3>(6) + f.segment<3>(9);
    const double expected = -kKappa * contact_barrier(g, kDhat).db;
    ASSERT_GT(expected, 0.0);
    EXPECT_NEAR(on_second.dot(n), expected, 1e-6 * expected) << tilt;
    EXPECT_NEAR((on_first + on_second).norm(), 0.0, 1e-12 * expected) << tilt;
    const double h = 1e-4 * g;
    for (int c = 0; c < 3; ++c) {
      std::vector<double> qp = q, qm = q;
      for (int node : {2, 3}) qp[3 * node + c] += h, qm[3 * node + c] -= h;
      EXPECT_NEAR(on_second[c], -(term.energy(0, qp.data()) - term.energy(0, qm.data())) / (2 * h), 1e-6 * expected)
          << "tilt " << tilt << ", direction " << c;
    }
  }
}

// Two yarns of two segments each, crossing at right angles through their
// segments' interiors, 2 mm apart (gap 2 mm − 2R), fired at each other at
// 1 m/s each: a 1 ms step would carry them through each other. With
// `modelled` their four pairs are the modelled ones, in contact at the core
// distance kCore.
class TwoYarns : public test::HandBuiltModel<TwoYarns> {
 public:
  static constexpr double kR = 2e-4, kDh = 1e-4, kCore = 2e-4;
  explicit TwoYarns(bool modelled = false) : HandBuiltModel("two-yarns") {
    num_dofs_ = 18;
    q0_.resize(18);
    v0_ = Vec::Zero(18);
    const double L = kLength, h = 2e-3;
    const std::array<Vec3, 6> x = {
        Vec3(-L, 0, 0),           Vec3(0, 0, 0), Vec3(L, 0, 0), Vec3(0.3 * L, -0.7 * L, h), Vec3(0.3 * L, 0.3 * L, h),
        Vec3(0.3 * L, 1.3 * L, h)};
    for (int k = 0; k < 6; ++k) {
      q0_.segment<3>(3 * k) = x[k];
      v0_[3 * k + 2] = k < 3 ? 1.0 : -1.0;
    }
    terms_.push_back(std::make_unique<test::NodeMassTerm>(6, 1e-5));
    terms_.push_back(
        std::make_unique<SelfContactTerm>(ContactSurface{{}, {0, 3, 6, 9, 12, 15}}, kDh, kKappa, capsules(modelled)));
    finalize();
  }
  static ContactCapsules capsules(bool modelled) {
    ContactCapsules c{{{0, 1}, {1, 2}, {3, 4}, {4, 5}}, kR, {}, kCore};
    if (modelled) c.modelled = {{0, 2}, {0, 3}, {1, 2}, {1, 3}};
    return c;
  }
};

// Smallest distance d between the centrelines over the 4 segment pairs of the two yarns.
double yarn_distance(const Vec& q) {
  auto x = [&](int k) { return Vec3(q.segment<3>(3 * k)); };
  double d = 1.0;
  for (int i = 0; i < 2; ++i)
    for (int j = 3; j < 5; ++j)
      d = std::min(d, closest_support(PairKind::edge_edge, {x(i), x(i + 1), x(j), x(j + 1)}).distance);
  return d;
}

TEST(CapsuleSteps, YarnsFiredAtEachOtherNeverPassThrough) {
  for (bool modelled : {false, true})
    for (const char* name : {"be-linear", "be-newton", "sdirk2"}) {
      SCOPED_TRACE(std::string(name) + (modelled ? ", modelled pairs" : ", capsule pairs"));
      TwoYarns model(modelled);
      auto integ = make_integrator(name);
      IntegratorOptions opt;
      opt.dt = 1e-3;
      integ->initialize(model, 0.0, model.initial_q(), model.initial_v(), opt);
      double closest = 1.0;
      bool ordered = true;
      integ->on_step = [&](const StepRecord&) {
        const Vec& q = integ->q();
        closest = std::min(closest, yarn_distance(q));
        // The crossing point of the first yarn (x = 0.3 L on its second segment) below the second's.
        const double za = 0.7 * q[5] + 0.3 * q[8], zb = 0.7 * q[14] + 0.3 * q[11];
        ordered = ordered && za < zb;
      };
      const StepResult r = integ->advance_to(0.01);
      ASSERT_EQ(r.outcome, Outcome::ok) << r.message;
      const double contact = modelled ? TwoYarns::kCore : 2.0 * TwoYarns::kR;
      EXPECT_GT(closest, contact);
      EXPECT_LT(closest, contact + TwoYarns::kDh) << "they never met";
      EXPECT_TRUE(ordered);
      EXPECT_GT(integ->stats().rejected_steps, 0) << "the step was never retaken";
      EXPECT_LT(integ->v()[5], 0.0) << "the first yarn did not rebound";
    }
}

// The assembled term over capsules (docs/models.md §3.11.7, §11.10): the
// per-node force is −∇ of the summed pair energies κ b(d − D) (D = 2R, or the
// core distance for modelled pairs; central differences over the pairs the
// broad phase finds), and the step stiffness it assembles bounds their
// Hessian from above, for the two yarns brought to 0.3 d̂ from contact and
// tilted, where two segment pairs are active.
TEST(CapsuleTerm, ForceIsMinusTheGradientOfThePairsAndItsStiffnessBoundsTheirHessian) {
  for (bool modelled : {false, true}) {
    SCOPED_TRACE(modelled ? "modelled pairs" : "capsule pairs");
    TwoYarns model(modelled);
    const double dhat = TwoYarns::kDh, contact = modelled ? TwoYarns::kCore : 2.0 * TwoYarns::kR;
    Vec q = model.initial_q();
    for (int k = 3; k < 6; ++k) q[3 * k + 2] -= 2e-3 - contact - 0.3 * dhat;
    q[11] += 0.2 * dhat;
    q[8] -= 0.1 * dhat;
    const Vec v = Vec::Zero(18);
    const SelfContactTerm pairs(ContactSurface{{}, {0, 3, 6, 9, 12, 15}}, dhat, kKappa, TwoYarns::capsules(modelled));
    auto energy = [&](const Vec& x) {
      double e = 0.0;
      for (const auto& p : pairs.candidates(x, x, dhat)) {
        EXPECT_EQ(p.core, modelled);
        e += kKappa * contact_barrier(pairs.distance(p, x), dhat).b;
      }
      return e;
    };
    Evaluation at, plus, minus;
    for (Evaluation* e : {&at, &plus, &minus}) allocate_evaluation(model, *e);
    model.evaluate(0.0, q, v, kForce | kDfdq, at);
    const double f_max = at.force.cwiseAbs().maxCoeff();
    ASSERT_GT(f_max, 0.0) << "no pair is active";
    const double h = 1e-4 * dhat;
    Eigen::MatrixXd hessian(18, 18);
    for (int k = 0; k < 18; ++k) {
      Vec qp = q, qm = q;
      qp[k] += h;
      qm[k] -= h;
      EXPECT_NEAR(at.force[k], -(energy(qp) - energy(qm)) / (2 * h), 1e-6 * f_max) << "DoF " << k;
      model.evaluate(0.0, qp, v, kForce, plus);
      model.evaluate(0.0, qm, v, kForce, minus);
      hessian.col(k) = -(plus.force - minus.force) / (2 * h);
    }
    const Eigen::MatrixXd bound = -Eigen::MatrixXd(at.dfdq), h_sym = 0.5 * (hessian + hessian.transpose());
    const double lowest = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(bound - h_sym).eigenvalues().minCoeff();
    EXPECT_GE(lowest, -1e-6 * h_sym.norm());
    // Modelled pairs 0.3 d̂ from their cores overlap as capsules and count as
    // intersecting only once their cores do.
    EXPECT_EQ(pairs.overlapping_pairs(q), 0);
    if (modelled) {
      Vec deeper = q;
      for (int k = 3; k < 6; ++k) deeper[3 * k + 2] -= 0.5 * dhat;
      EXPECT_GT(pairs.overlapping_pairs(deeper), 0);
    }
  }
}

}  // namespace
}  // namespace wl
