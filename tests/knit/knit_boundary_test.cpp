// Pins and handles on a knit (docs/models.md §11.7): the contact a scene's
// node = [i, j] names, the DoFs a pin holds, the handle springs' pull and the
// assembled Jacobian with them against finite differences.
#include "models/knit/knit_boundary.h"

#include <gtest/gtest.h>

#include <algorithm>

#include "models/knit/knit_model.h"
#include "tests/support/fd_check.h"

namespace wl {
namespace {

Scene held_knit() {
  return parse_scene(
      "[cloth]\nspacing_m = 2e-3\nradius_m = 2e-4\n[cloth.pattern]\nkind = \"stockinette\"\ncourses = 3\n"
      "wales = 3\n[pose]\nkind = \"flat\"\n[[pins]]\nnode = [0, 0]\n[[pins]]\nnode = [2, 3]\n"
      "[[handles]]\nnode = [3, 5]\nstiffness_N_per_m = 40\nvelocity_m_per_s = [0, 0.1, 0]\n",
      "held.toml");
}

// node = [i, j]: contact row i (0 below the first course), column j (wale j/2, side j%2).
TEST(KnitBoundary, PinsHoldBothNodesOfTheirContactWithTheirCoordinates) {
  const Scene s = held_knit();
  const KnitModel m(s);
  const KnitGraph& g = m.graph();
  const auto [a, b] = knit_contact_nodes(g, NodeRef{2, 3});
  EXPECT_EQ(a, g.contact_node(1, 1, 1, 0));
  EXPECT_EQ(b, g.contact_node(1, 1, 1, 1));
  // The contact between courses 1 and 2, right side of wale 1: x = W + W/4, y = 1.5 C ∓ C/6.
  EXPECT_NEAR(g.node(a).x.x(), 1.25 * s.spacing_m, 1e-15);
  EXPECT_NEAR(g.node(b).x.y(), 1.5 * s.knit->course_spacing_m + s.knit->course_spacing_m / 6.0, 1e-15);
  std::vector<int> expected;
  for (const NodeRef& p : s.pins)
    for (int n : knit_contact_nodes(g, p)) {
      for (int k = 0; k < 3; ++k) expected.push_back(g.node(n).x_dof + k);
      for (int c : g.node(n).coord)
        if (is_dof(c)) expected.push_back(c);
    }
  std::vector<int> fixed(m.fixed_dofs().begin(), m.fixed_dofs().end());
  std::sort(fixed.begin(), fixed.end());
  std::sort(expected.begin(), expected.end());
  EXPECT_EQ(fixed, expected);
  // The interior contact (2, 3) carries two sliding coordinates per node, both held.
  EXPECT_EQ(expected.size(), 2u * 3u + 2u * 3u + 4u);
}

// The handle's target moves at w: at time t the springs (k/2 on each node)
// pull the contact with k·w·t in total.
TEST(KnitBoundary, AHandlePullsItsContactWithItsStiffness) {
  const Scene s = held_knit();
  KnitModel m(s);
  Scene free = s;
  free.handles.clear();
  KnitModel without(free);
  const Vec q = m.initial_q(), v = Vec::Zero(m.num_dofs());
  Evaluation e, e0;
  allocate_evaluation(m, e);
  allocate_evaluation(without, e0);
  const double t = 0.01;
  m.evaluate(t, q, v, kForce, e);
  without.evaluate(t, q, v, kForce, e0);
  const Vec pull = e.force - e0.force;
  Vec3 total = Vec3::Zero();
  for (int n : knit_contact_nodes(m.graph(), s.handles[0].node)) {
    const Vec3 f = pull.segment<3>(m.graph().node(n).x_dof);
    EXPECT_NEAR(f.y(), 0.5 * 40.0 * 0.1 * t, 1e-12);
    total += f;
  }
  EXPECT_NEAR(total.y(), 40.0 * 0.1 * t, 1e-12);
  EXPECT_NEAR(pull.cwiseAbs().sum(), total.y(), 1e-12);  // nothing else pulled
}

TEST(KnitBoundary, AssembledJacobianWithHandlesMatchesFiniteDifferences) {
  const Scene s = held_knit();
  KnitModel m(s);
  const int n = m.num_dofs();
  Vec q = m.initial_q();
  for (int k = 0; k < n; ++k) q[k] += 2e-5 * std::sin(0.7 * k);
  const Vec v = Vec::Zero(n);
  Evaluation eval;
  allocate_evaluation(m, eval);
  m.evaluate(0.02, q, v, kForce | kDfdq, eval);
  const SparseMatrix K = eval.dfdq;
  auto force = [&](const Vec& x) {
    Evaluation e;
    allocate_evaluation(m, e);
    m.evaluate(0.02, x, v, kForce, e);
    return Vec(e.force);
  };
  std::vector<int> cols;
  for (int node : knit_contact_nodes(m.graph(), s.handles[0].node))
    for (int k = 0; k < 3; ++k) cols.push_back(m.graph().node(node).x_dof + k);
  test::FdOptions opt;
  opt.rel_step = 1e-7;
  opt.rtol = 1e-5;
  const auto r = test::check_jacobian_columns(
      force, q, [&](int j) { return Vec(K.col(j)); }, cols, opt);
  EXPECT_TRUE(r.ok) << r.detail;
  EXPECT_GT(K.col(cols[0]).norm(), 40.0 * 0.4);  // the handle's k/2 at least, not a zero column
}

}  // namespace
}  // namespace wl
