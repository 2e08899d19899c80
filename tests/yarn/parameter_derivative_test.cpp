// Parameter derivatives of the yarn terms (docs/models.md §9.1): ∂f/∂p and, for
// inertia, ∂M/∂p against central differences in p, with the generic checker,
// once per term; and the model's keys and their assembly.
#include <gtest/gtest.h>

#include <cmath>

#include "models/scene/parameter_keys.h"
#include "models/yarn/terms/bending.h"
#include "models/yarn/terms/friction_cirio.h"
#include "models/yarn/terms/friction_gong.h"
#include "models/yarn/terms/gravity.h"
#include "models/yarn/terms/segment_inertia.h"
#include "models/yarn/terms/shear_cirio.h"
#include "models/yarn/terms/shear_gong.h"
#include "models/yarn/terms/stretch.h"
#include "models/yarn/yarn_model.h"
#include "tests/support/fd_check.h"
#include "tests/yarn/crossing_states.h"

namespace wl {
namespace {

using test::LocalState;

// Segment states (x0, x1, u0, u1) away from rest, with velocities for inertia.
std::vector<LocalState> segment_states() {
  return {
      {{0.0, 0.0, 0.0, 1.02e-3, 0.1e-3, -0.05e-3, 0.3e-3, 1.3e-3}, {0.1, -0.2, 0.3, 0.2, 0.1, -0.4, 0.02, -0.05}},
      {{0.1e-3, -0.2e-3, 0.3e-3, 1.2e-3, 0.9e-3, 0.8e-3, -0.4e-3, 0.8e-3}, {0.0, 0.3, -0.1, 0.5, 0.2, 0.1, 0.1, 0.0}}};
}

template <class T, class... Args>
std::function<std::unique_ptr<Term>(double)> one_element(std::function<void(T&, double)> add, Args... ctor) {
  return [=](double p) {
    auto t = std::make_unique<T>(ctor...);
    add(*t, p);
    return std::unique_ptr<Term>(std::move(t));
  };
}

TEST(YarnTermParameters, StretchBendingGravityInertiaShearMatchFiniteDifferences) {
  const std::array<int, 8> seg{0, 1, 2, 3, 4, 5, 6, 7};
  const double Y = 5e5, area = M_PI * 2.5e-7;
  {
    auto make = one_element<StretchTerm>([&](StretchTerm& t, double p) {
      t.add(seg, p * area);
      t.tag_last(yarn_type_key("a", kStretchModulusField), p);
    });
    auto r = test::check_parameter_derivative(make, Y, 0, 0, segment_states());
    EXPECT_TRUE(r.ok) << r.detail;
  }
  {
    auto make = one_element<SegmentInertiaTerm>([&](SegmentInertiaTerm& t, double p) {
      t.add(seg, p);
      t.tag_last(yarn_type_key("a", kDensityField), p);
    });
    auto r = test::check_parameter_derivative(make, 2e-3, 0, 0, segment_states(), {1e-7, 1e-5, 1e-14});
    EXPECT_TRUE(r.ok) << r.detail;
  }
  {
    auto make = one_element<GravityTerm>(
        [&](GravityTerm& t, double p) {
          t.add(seg, p);
          t.tag_last(yarn_type_key("a", kDensityField), p);
        },
        Vec3(0.0, 0.0, -9.81));
    auto r = test::check_parameter_derivative(make, 2e-3, 0, 0, segment_states(), {1e-7, 1e-5, 1e-14});
    EXPECT_TRUE(r.ok) << r.detail;
  }
  {
    auto make = one_element<BendingTerm>([&](BendingTerm& t, double p) {
      t.add({0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10}, p * area);
      t.tag_last(yarn_type_key("a", kBendingModulusField), p);
    });
    const std::vector<double> v(11, 0.0);
    const std::vector<LocalState> bent = {
        {{0.0, 0.0, 0.0, 1e-3, 0.2e-3, 0.0, -1e-3, 0.1e-3, 0.05e-3, 1.02e-3, -0.98e-3}, v}};
    auto r = test::check_parameter_derivative(make, 1.4e-4, 0, 0, bent, {1e-7, 1e-5, 1e-16});
    EXPECT_TRUE(r.ok) << r.detail;
  }
  const std::vector<LocalState> crossings = {test::crossing_state(1.2, 1e-3, 1.1e-3),
                                             test::crossing_state(0.7, 1e-3, 0.9e-3)};
  {
    auto make = one_element<CirioShearTerm>([&](CirioShearTerm& t, double p) {
      t.add({0, 1, 2, 3, 4, 5, 6, 7, 8}, p * area * 1e-3);
      t.tag_last(kShearModulusKey, p);
    });
    auto r = test::check_parameter_derivative(make, 1000.0, 0, 0, crossings, {1e-7, 1e-5, 1e-16});
    EXPECT_TRUE(r.ok) << r.detail;
  }
  {
    static const std::vector<double> Fn{0.3};
    auto make = one_element<GongShearTerm>(
        [&](GongShearTerm& t, double p) {
          t.add({0, 1, 2, 3, 4, 5, 6, 7, 8}, 0, p * area, true);
          t.tag_last(kShearModulusKey, p);
          t.prepare(EvalContext{0.0, nullptr, nullptr, nullptr, Fn});
        },
        1e-3, 0.3e-3, 3.0, 0.6);
    auto r = test::check_parameter_derivative(make, 1000.0, 0, 0, crossings, {1e-7, 1e-5, 1e-16});
    EXPECT_TRUE(r.ok) << r.detail;
  }
}

// Friction: ∂F/∂μ at frozen F_u, F_n in each regime of Gong's law, and for
// Cirio's law while slipping (after a step that broke the stick).
TEST(YarnTermParameters, FrictionCoefficientMatchesFiniteDifferences) {
  static const std::vector<double> Fn{1.0};
  for (double pull : {0.05, 0.5, 2.0, -2.0}) {
    auto make = [&](double mu) {
      auto t = std::make_unique<GongFrictionTerm>(mu, 1000, 1000, 10);
      t->add(0, 0, 0.0);
      const Vec Fu = Vec::Constant(1, pull), q = Vec::Zero(1), v = Vec::Zero(1);
      t->prepare(EvalContext{0.0, &q, &v, &Fu, Fn});
      return std::unique_ptr<Term>(std::move(t));
    };
    auto r = test::check_parameter_derivative(make, 0.5, 0, 0, {{{-0.02}, {0.1}}, {{0.01}, {0.0}}, {{0.2}, {-0.3}}});
    EXPECT_TRUE(r.ok) << "F_u = " << pull << "\n" << r.detail;
  }
  auto make = [&](double mu) {
    auto t = std::make_unique<CirioFrictionTerm>(mu, 1000, 1000, 10);
    t->add(0, 0, 0.0);
    const Vec Fu = Vec::Zero(1), q = Vec::Constant(1, 0.01), v = Vec::Zero(1);
    t->prepare(EvalContext{0.0, &q, &v, &Fu, Fn});
    t->accept_step(EvalContext{0.0, &q, &v, &Fu, Fn}, 1e-3);  // k_f·0.01 = 10 N > μF_n: slipping
    return std::unique_ptr<Term>(std::move(t));
  };
  auto r = test::check_parameter_derivative(make, 0.5, 0, 0, {{{0.012}, {0.1}}});
  EXPECT_TRUE(r.ok) << r.detail;
}

// The model names every key of its scene that the force depends on, and a
// two-type cloth keeps the types apart: ∂f/∂Y of one type vanishes on the
// other type's yarns and both sum to ∂f/∂Y of the single-type cloth.
TEST(YarnModelParameters, KeysPerYarnTypeAddUpToTheSingleTypeDerivative) {
  Scene s = parse_scene("[cloth]\nwarps = 5\nwefts = 5\n[time]\nduration_s = 0.01\n", "keys.toml");
  s.yarn_types["b"] = s.yarn_types.at("default");
  s.warp_yarn_types = {"default", "b"};
  YarnModel two(s);
  const std::vector<std::string> keys = two.parameter_keys();
  for (const std::string& k : {yarn_type_key("default", kStretchModulusField), yarn_type_key("b", kStretchModulusField),
                               yarn_type_key("b", kDensityField), yarn_type_key("b", kBendingModulusField),
                               std::string(kShearModulusKey), std::string(kFrictionCoefficientKey)})
    EXPECT_NE(std::find(keys.begin(), keys.end(), k), keys.end()) << k;

  Vec q = two.initial_q(), v = two.initial_v();
  for (Eigen::Index i = 0; i < q.size(); ++i) q[i] += 1e-5 * std::sin(3.0 * i);  // off rest
  Evaluation ev;
  two.evaluate(0.0, q, v, kForce, ev);
  Vec da, db;
  two.force_parameter_derivative(yarn_type_key("default", kStretchModulusField), 0.0, q, v, da);
  two.force_parameter_derivative(yarn_type_key("b", kStretchModulusField), 0.0, q, v, db);
  EXPECT_GT(da.norm(), 0.0);
  EXPECT_GT(db.norm(), 0.0);

  s.warp_yarn_types = {"default"};
  s.yarn_types.erase("b");
  YarnModel one(s);
  one.evaluate(0.0, q, v, kForce, ev);
  Vec d1;
  one.force_parameter_derivative(yarn_type_key("default", kStretchModulusField), 0.0, q, v, d1);
  EXPECT_LT((da + db - d1).norm(), 1e-12 * d1.norm());
}

}  // namespace
}  // namespace wl
