// Cloth–cloth contact (docs/models.md §3.11.7): the pair barrier's force and
// Jacobian against finite differences per distance type (point–triangle with
// the closest point on a vertex, an edge, the face; edge–edge on two interiors,
// an interior and an endpoint, two endpoints) near the barrier's limit; the
// distance of parallel edges; two triangles thrown at each other never cross
// under the implicit step; a d̂ the flat cloth would feel at rest is refused.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <Eigen/Eigenvalues>

#include "integrators/integrator.h"
#include "models/common/obstacle_barrier.h"
#include "models/common/self_contact.h"
#include "models/core/term_model.h"
#include "models/model_factory.h"
#include "models/scene/scene.h"
#include "tests/support/fd_check.h"
#include "tests/support/node_mass.h"

namespace wl {
namespace {

constexpr double kDhat = 1e-3, kKappa = 1e4, kSide = 1e-2;

std::vector<double> flatten(const std::array<Vec3, 4>& x) {
  std::vector<double> q;
  for (const Vec3& p : x) q.insert(q.end(), p.data(), p.data() + 3);
  return q;
}

struct Case {
  const char* name;
  PairKind kind;
  std::array<Vec3, 4> x;
  unsigned first, second;  // the expected support
};

// The pair at distance ≈ s·d̂ in each distance type (s = 0.1: near the barrier's limit).
std::vector<Case> cases(double s) {
  const double d = s * kDhat, a = 0.6 * d, b = 0.8 * d;  // a² + b² = d²
  const Vec3 o(0, 0, 0), ex(kSide, 0, 0), ey(0, kSide, 0);
  return {
      {"point-face", PairKind::point_triangle, {Vec3(0.2 * kSide, 0.3 * kSide, d), o, ex, ey}, 0b0001u, 0b1110u},
      {"point-edge", PairKind::point_triangle, {Vec3(0.5 * kSide, -a, b), o, ex, ey}, 0b0001u, 0b0110u},
      {"point-vertex", PairKind::point_triangle, {Vec3(-a, -0.6 * b, 0.8 * b), o, ex, ey}, 0b0001u, 0b0010u},
      {"edge-edge",
       PairKind::edge_edge,
       {o, ex, Vec3(0.5 * kSide, -0.5 * kSide, d), Vec3(0.5 * kSide, 0.5 * kSide, d)},
       0b0011u,
       0b1100u},
      {"edge-endpoint",
       PairKind::edge_edge,
       {o, ex, Vec3(0.5 * kSide, 0, d), Vec3(0.5 * kSide, 0.2 * kSide, d + kSide)},
       0b0011u,
       0b0100u},
      {"endpoint-endpoint",
       PairKind::edge_edge,
       {o, ex, Vec3(kSide + a, 0.6 * b, 0.8 * b), Vec3(2 * kSide, kSide, kSide)},
       0b0010u,
       0b0100u},
  };
}

TEST(SelfContactPair, ForceAndJacobianMatchFiniteDifferencesPerDistanceType) {
  for (double s : {0.1, 0.7})
    for (const Case& c : cases(s)) {
      const ClosestPoints cp = closest_support(c.kind, c.x);
      EXPECT_EQ(cp.support.first, c.first) << c.name;
      EXPECT_EQ(cp.support.second, c.second) << c.name;
      EXPECT_NEAR(cp.distance, s * kDhat, 1e-12) << c.name;
      SelfContactPairTerm term(kDhat, kKappa);
      std::array<int, 12> st;
      for (int k = 0; k < 12; ++k) st[k] = k;
      term.add(st, c.kind);
      test::FdOptions opt;
      opt.rtol = 1e-5;
      const test::FdReport r = test::check_element(term, 0, {{flatten(c.x), std::vector<double>(12, 0.0)}}, opt);
      EXPECT_TRUE(r.ok) << c.name << " at d = " << s << " d̂: " << r.detail;
    }
}

// Parallel edges: the affine system of the two interiors is singular; the
// distance is that of an endpoint, and the force on the two edges is opposite
// and along their separation.
TEST(SelfContactPair, ParallelEdgesHaveTheirSeparationAsDistance) {
  const double dy = 3e-4, dz = 4e-4;
  for (double tilt : {0.0, 1e-9}) {
    const std::array<Vec3, 4> x = {Vec3(0, 0, 0), Vec3(kSide, 0, 0), Vec3(0.5 * kSide, dy, dz),
                                   Vec3(1.5 * kSide, dy, dz + tilt * kSide)};
    const ClosestPoints cp = closest_support(PairKind::edge_edge, x);
    EXPECT_NEAR(cp.distance, 5e-4, 1e-15) << tilt;
    SelfContactPairTerm term(kDhat, kKappa);
    term.add({0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11}, PairKind::edge_edge);
    Eigen::Matrix<double, 12, 1> f = Eigen::Matrix<double, 12, 1>::Zero();
    term.evaluate(0, flatten(x).data(), nullptr, ElementOutput{f.data()});
    const Vec3 on_first = f.segment<3>(0) + f.segment<3>(3), on_second = f.segment<3>(6) + f.segment<3>(9);
    const double expected = -kKappa * contact_barrier(5e-4, kDhat).db;  // > 0: repelling
    EXPECT_NEAR(on_second.dot(Vec3(0, dy, dz) / 5e-4), expected, 1e-9 * expected) << tilt;
    EXPECT_NEAR((on_first + on_second).norm(), 0.0, 1e-12 * expected) << tilt;
  }
}

// Two free triangles, the second above the first and turned by 180° about the
// vertical through their common centroid (each vertex over the other's edge):
// the first moves up at w, the second down at w.
class TwoTriangles : public test::HandBuiltModel<TwoTriangles> {
 public:
  explicit TwoTriangles(double w) : HandBuiltModel("two-triangles") {
    num_dofs_ = 18;
    q0_.resize(18);
    v0_ = Vec::Zero(18);
    const Vec3 c(kSide / 3, kSide / 3, 0);
    const std::array<Vec3, 3> t = {Vec3(0, 0, 0), Vec3(kSide, 0, 0), Vec3(0, kSide, 0)};
    for (int k = 0; k < 3; ++k) {
      q0_.segment<3>(3 * k) = t[k];
      q0_.segment<3>(9 + 3 * k) = 2 * c - t[k] + Vec3(0, 0, 2e-3);
      v0_[3 * k + 2] = w;
      v0_[9 + 3 * k + 2] = -w;
    }
    terms_.push_back(std::make_unique<test::NodeMassTerm>(6, 1e-3));
    terms_.push_back(std::make_unique<SelfContactTerm>(ContactSurface{{{0, 1, 2}, {3, 4, 5}}, {0, 3, 6, 9, 12, 15}},
                                                       0.5 * kDhat, kKappa));
    finalize();
  }
};

// Smallest distance between the two triangles: the 6 point–triangle and 9 edge–edge pairs.
double gap(const Vec& q) {
  auto x = [&](int k) { return Vec3(q.segment<3>(3 * k)); };
  double d = 1.0;
  for (int side = 0; side < 2; ++side) {
    const int p0 = 3 * side, t0 = 3 - p0;
    for (int i = 0; i < 3; ++i)
      d = std::min(d, closest_support(PairKind::point_triangle, {x(p0 + i), x(t0), x(t0 + 1), x(t0 + 2)}).distance);
  }
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      d = std::min(d,
                   closest_support(PairKind::edge_edge, {x(i), x((i + 1) % 3), x(3 + j), x(3 + (j + 1) % 3)}).distance);
  return d;
}

// Head-on at 2 m/s relative, 2 mm apart: a 1 ms step would carry them through
// each other. Every accepted step keeps them apart, the first below the second,
// and they part again (the barrier is elastic).
TEST(SelfContactSteps, TrianglesThrownAtEachOtherNeverCross) {
  for (const char* name : {"be-linear", "be-newton"}) {
    TwoTriangles model(1.0);
    auto integ = make_integrator(name);
    IntegratorOptions opt;
    opt.dt = 1e-3;
    integ->initialize(model, 0.0, model.initial_q(), model.initial_v(), opt);
    double closest = 1.0;
    bool ordered = true;
    integ->on_step = [&](const StepRecord&) {
      const Vec& q = integ->q();
      closest = std::min(closest, gap(q));
      ordered = ordered && (q[2] + q[5] + q[8]) < (q[11] + q[14] + q[17]);
    };
    const StepResult r = integ->advance_to(0.01);
    ASSERT_EQ(r.outcome, Outcome::ok) << name << ": " << r.message;
    EXPECT_GT(closest, 0.0) << name;
    EXPECT_LT(closest, 0.5 * kDhat) << name << ": they never met";
    EXPECT_TRUE(ordered) << name;
    EXPECT_GT(integ->stats().rejected_steps, 0) << name << ": the step was never retaken";
    EXPECT_LT(integ->v()[2], 0.0) << name << ": the lower triangle did not rebound";
  }
}

// The assembled term against its pairs (docs/models.md §3.11.7): the per-node
// force is −∇ of the summed pair energies κ b(d) (central differences over the
// pairs the broad phase finds), and the step stiffness −∂f/∂q it assembles,
// block-diagonal, bounds the pairs' Hessian H from above (−∂f/∂q − H ⪰ 0),
// for two tilted triangles 0.3–0.5 d̂ apart, where several pairs are active.
TEST(SelfContactTerm, ForceIsMinusTheGradientOfThePairsAndItsStiffnessBoundsTheirHessian) {
  TwoTriangles model(0.0);
  const double dhat = 0.5 * kDhat;
  Vec q = model.initial_q();
  for (int k = 0; k < 3; ++k) q[9 + 3 * k + 2] -= 2e-3 - 0.3 * dhat;  // 0.3 d̂ above the first
  q[11] += 0.2 * dhat;                                                // tilted
  q[5] -= 0.1 * dhat;
  const Vec v = Vec::Zero(18);
  const SelfContactTerm pairs(ContactSurface{{{0, 1, 2}, {3, 4, 5}}, {0, 3, 6, 9, 12, 15}}, dhat, kKappa);
  auto energy = [&](const Vec& x) {
    double e = 0.0;
    for (const auto& p : pairs.candidates(x, x, dhat)) e += kKappa * contact_barrier(pairs.distance(p, x), dhat).b;
    return e;
  };
  auto force = [&](const Vec& x, Evaluation& ev) { model.evaluate(0.0, x, v, kForce | kDfdq, ev); };
  Evaluation at;
  allocate_evaluation(model, at);
  force(q, at);
  const double f_max = at.force.cwiseAbs().maxCoeff();
  ASSERT_GT(f_max, 0.0) << "no pair is active";
  const double h = 1e-4 * dhat;
  Eigen::MatrixXd hessian(18, 18);
  Evaluation plus, minus;
  allocate_evaluation(model, plus);
  allocate_evaluation(model, minus);
  for (int k = 0; k < 18; ++k) {
    Vec qp = q, qm = q;
    qp[k] += h;
    qm[k] -= h;
    EXPECT_NEAR(at.force[k], -(energy(qp) - energy(qm)) / (2 * h), 1e-6 * f_max) << "DoF " << k;
    force(qp, plus);
    force(qm, minus);
    hessian.col(k) = -(plus.force - minus.force) / (2 * h);
  }
  const Eigen::MatrixXd bound = -Eigen::MatrixXd(at.dfdq), h_sym = 0.5 * (hessian + hessian.transpose());
  EXPECT_GT((bound - h_sym).norm(), 1e-3 * h_sym.norm()) << "the bound is the Hessian itself";
  const double lowest = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(bound - h_sym).eigenvalues().minCoeff();
  EXPECT_GE(lowest, -1e-6 * h_sym.norm());
}

// A d̂ ≥ the distance of two primitives of the initial cloth that share no
// node is refused, naming the key: √½ ℓ in the flat cloth (a node and the
// diagonal of its cell), 0.3 mm for two triangles that start that far apart;
// ℓ/2 in the flat cloth is accepted; self-contact is off by default.
TEST(SelfContactScene, ADistanceTheFlatClothWouldFeelIsRefused) {
  const std::string base =
      "[cloth]\nwarps = 6\nwefts = 6\nspacing_m = 0.001\n[pose]\nkind = \"flat\"\n[self_contact]\nenabled = true\n";
  for (const char* model : {"yarn", "fem"}) {
    EXPECT_FALSE(parse_scene("[cloth]\nwarps = 3\nwefts = 3\n", "s.toml").self_contact.enabled);
    const Scene fine = parse_scene(base + "activation_distance_m = 0.0005\n", "s.toml");
    EXPECT_NE(make_model(fine, model)->describe().at("terms").find("self_contact"), std::string::npos) << model;
    Scene coarse = fine;  // past the scene reader's own check (SelfContactScene.ADistanceNoModelCanTake...)
    coarse.self_contact.activation_distance_m = 0.00075;
    try {
      make_model(coarse, model);
      ADD_FAILURE() << model << ": accepted";
    } catch (const std::invalid_argument& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find("s.toml:7: self_contact.activation_distance_m"), std::string::npos) << what;
      EXPECT_NE(what.find("below 0.000707107 m, the distance at which two surface primitives that share no node"),
                std::string::npos)
          << what;
    }
  }
  Scene s = parse_scene(base, "s.toml");
  Vec q0 = Vec::Zero(18);
  const std::array<Vec3, 3> t = {Vec3(0, 0, 0), Vec3(kSide, 0, 0), Vec3(0, kSide, 0)};
  for (int k = 0; k < 3; ++k) {
    q0.segment<3>(3 * k) = t[k];
    q0.segment<3>(9 + 3 * k) = t[k] + Vec3(0, 0, 3e-4);
  }
  std::vector<std::unique_ptr<Term>> terms;
  try {
    add_self_contact(s, {5e-4, 1.0, 1e-3}, kSide, {{{0, 1, 2}, {3, 4, 5}}, {0, 3, 6, 9, 12, 15}}, q0, terms);
    ADD_FAILURE() << "accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("s.toml:7: self_contact.activation_distance_m: d̂ = 0.0005 m; expected d̂ "
                                         "below 0.0003 m, the distance at which"),
              std::string::npos)
        << e.what();
  }
  EXPECT_TRUE(terms.empty());
}

// The scene reader refuses a d̂ that no model of the scene can take, where it
// is set (a file, or a scene edit in Python), at the bound the models apply on
// the flat grid: √½ ℓ with ℓ the continuum's node spacing stride · spacing_m.
// Just below it, both models at stride 1 build.
TEST(SelfContactScene, ADistanceNoModelCanTakeIsRefusedByTheSceneReader) {
  const std::string base =
      "[cloth]\nwarps = 5\nwefts = 5\nspacing_m = 0.001\n[pose]\nkind = \"flat\"\n[self_contact]\nenabled = true\n";
  try {
    parse_scene(base + "activation_distance_m = 0.00075\n", "s.toml");
    ADD_FAILURE() << "accepted";
  } catch (const SceneError& e) {
    EXPECT_EQ(std::string(e.what()).rfind("s.toml:9: key 'self_contact.activation_distance_m': got 0.00075, expected a "
                                          "number below 0.000707107 m: √½ × the node spacing 0.001 m",
                                          0),
              0u)
        << e.what();
  }
  const Scene below = parse_scene(base + "activation_distance_m = 0.000707\n", "s.toml");
  for (const char* model : {"yarn", "fem"})
    EXPECT_NE(make_model(below, model)->describe().at("terms").find("self_contact"), std::string::npos) << model;
  // The continuum at stride 2 takes d̂ up to √½ · 2 ℓ: the reader lets 1.2 ℓ pass, the yarn level refuses it.
  const Scene strided = parse_scene(base + "activation_distance_m = 0.0012\n[fem]\nstride = 2\n", "s.toml");
  EXPECT_THROW(make_model(strided, "yarn"), std::invalid_argument);
  EXPECT_THROW(parse_scene(base + "activation_distance_m = 0.0015\n[fem]\nstride = 2\n", "s.toml"), SceneError);
  EXPECT_NO_THROW(make_model(strided, "fem"));
  EXPECT_NO_THROW(parse_scene("[cloth]\nwarps = 5\n[self_contact]\nenabled = false\nactivation_distance_m = 0.01\n",
                              "s.toml"));  // off: nothing to refuse
}

}  // namespace
}  // namespace wl
