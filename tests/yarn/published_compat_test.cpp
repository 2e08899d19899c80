// The [compat] switches (docs/published_code.md): normal_force_stretch = "centre_line" (rows 1–2,
// the contact normal force with the stretch part on the actual centre lines and the ring uncrimped)
// and wind_diagonals = "alternating" (row 13), as the authors' published code computes them: their
// scene keys, closed forms, and the model with both against differences of its own force.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <random>

#include "integrators/backward_euler.h"
#include "models/scene/scene.h"
#include "models/yarn/contact_normals.h"
#include "models/yarn/terms/bending.h"
#include "models/yarn/yarn_model.h"
#include "tests/yarn/model_blocks.h"

namespace wl {
namespace {

constexpr double kL = 1e-3, kR = 0.5e-3;       // docs/models.md §8.4
constexpr double kKsU = 0.39, kKbU = 1.1e-10;  // warp k_s (N), k_b (N·m²)
constexpr double kKsV = 0.13, kKbV = 0.9e-10;  // weft

SceneError scene_error(const std::string& text) {
  try {
    parse_scene(text, "s.toml");
  } catch (const SceneError& e) {
    return e;
  }
  ADD_FAILURE() << "no error for\n" << text;
  return SceneError("", 0, "", "", "");
}

TEST(CompatKeys, NormalForceStretchIsReadAndDefaultsToTheCrimpedCopies) {
  EXPECT_FALSE(parse_scene("", "s.toml").compat.normal_force_on_centre_lines);
  EXPECT_FALSE(
      parse_scene("[compat]\nnormal_force_stretch = \"crimped\"\n", "s.toml").compat.normal_force_on_centre_lines);
  EXPECT_TRUE(
      parse_scene("[compat]\nnormal_force_stretch = \"centre_line\"\n", "s.toml").compat.normal_force_on_centre_lines);
}

TEST(CompatKeys, BadValuesNameLineKeyAndWhatWasExpected) {
  SceneError e = scene_error("[compat]\n\nnormal_force_stretch = \"centreline\"\n");
  EXPECT_EQ(e.key, "compat.normal_force_stretch");
  EXPECT_EQ(e.line, 3);
  EXPECT_NE(e.expected.find("centre_line"), std::string::npos) << e.what();
  e = scene_error("[compat]\nnormal_force_stretch = true\n");
  EXPECT_EQ(e.key, "compat.normal_force_stretch");
  e = scene_error("[compat]\npublished_code = true\n");  // no such key
  EXPECT_EQ(e.key, "compat.published_code");
  EXPECT_EQ(e.line, 2);
  // The exact derivatives of F_n (docs/models.md §3.6.1) exist for the crimped stretch only.
  e = scene_error("[time]\nexact_contact_jacobian = true\n[compat]\nnormal_force_stretch = \"centre_line\"\n");
  EXPECT_EQ(e.key, "compat.normal_force_stretch");
  EXPECT_EQ(e.line, 4);
  EXPECT_NE(e.expected.find("exact_contact_jacobian"), std::string::npos) << e.what();
}

Scene plain_scene(int nu, int nv) {
  Scene s;
  s.wefts = nu;
  s.warps = nv;
  s.spacing_m = kL;
  s.radius_m = kR;
  s.sliding = true;
  s.pattern.kind = Pattern::Kind::plain;
  return s;
}

ContactNormals make(const WovenGrid& g, NormalForceStretch stretch) {
  return ContactNormals(g, std::vector<double>(g.nv(), kKsU), std::vector<double>(g.nv(), kKbU),
                        std::vector<double>(g.nu(), kKsV), std::vector<double>(g.nu(), kKbV), kR, stretch);
}

// Node (i, j) at pos(i, j), the sliding coordinates at rest.
Vec state(const WovenGrid& g, const std::function<Vec3(int, int)>& pos) {
  Vec q = Vec::Zero(g.num_dofs());
  for (int j = 0; j < g.nv(); ++j)
    for (int i = 0; i < g.nu(); ++i) {
      const NodeDofs& d = g.dofs(g.node(i, j));
      q.segment<3>(d.x) = pos(i, j);
      if (is_dof(d.u)) q[d.u] = i * kL;
      if (is_dof(d.v)) q[d.v] = j * kL;
    }
  return q;
}

// Bending part of ½nᵀ(F^u − F^v) from one yarn of a flat plain weave, neighbours a distance h
// apart, at a node whose bending stencils all lie on interior (crimped) nodes: the crimped copy
// zig-zags 2R over h, l = √(h² + 4R²), bending angle θ = 2·atan(2R/h); the stencil centred at the
// node pushes it with 2k_bθh/(L l²) along its normal, each of the two centred at its in-yarn
// neighbours with k_bθh/(L l²) (the bending part of the closed form in contact_normals_test.cpp).
double bending_push(double kb, double h) {
  const double l2 = h * h + 4 * kR * kR;
  return 4.0 * kb * 2.0 * std::atan(2 * kR / h) * h / (kL * l2);
}

TEST(CompatNormalForce, FlatSheetAtRestCarriesOnlyTheCrimpedBending) {
  // On the centre lines a resting sheet has no stretch, so deep in the sheet (two nodes from the
  // ring) F_n is the bending of the crimped copies alone; with the crimped stretch (the lab's
  // model) the stretch of the zig-zag adds (k_s^u + k_s^v)(2 − √2)/2 at R = L/2.
  const WovenGrid g(plain_scene(9, 9));
  ContactNormals published = make(g, NormalForceStretch::centre_lines);
  ContactNormals lab = make(g, NormalForceStretch::crimped_copies);
  const Vec q = state(g, [](int i, int j) { return Vec3(i * kL, j * kL, 0.0); });
  published.compute(q);
  lab.compute(q);
  const double expected = 0.5 * (bending_push(kKbU, kL) + bending_push(kKbV, kL));
  const double stretch_part = 0.5 * (kKsU + kKsV) * (2.0 - std::sqrt(2.0));
  for (int j = 3; j <= 5; ++j)
    for (int i = 3; i <= 5; ++i) {
      const int id = g.node(i, j);
      EXPECT_NEAR(published.normal_force()[id], expected, 1e-12 * expected) << i << "," << j;
      EXPECT_NEAR(lab.normal_force()[id], expected + stretch_part, 1e-12 * stretch_part) << i << "," << j;
    }
}

TEST(CompatNormalForce, StretchingTheSheetInItsPlaneLeavesItUnchanged) {
  // Warps pulled 5 % along u: on the centre lines the stretch forces lie in the sheet and have no
  // normal part; only the flatter crimped zig-zag of the warps changes the bending part.
  const WovenGrid g(plain_scene(9, 9));
  ContactNormals published = make(g, NormalForceStretch::centre_lines);
  published.compute(state(g, [](int i, int j) { return Vec3(i * kL * 1.05, j * kL, 0.0); }));
  const double expected = 0.5 * (bending_push(kKbU, 1.05 * kL) + bending_push(kKbV, kL));
  for (int j = 3; j <= 5; ++j)
    for (int i = 3; i <= 5; ++i)
      EXPECT_NEAR(published.normal_force()[g.node(i, j)], expected, 1e-12 * expected) << i << "," << j;
}

TEST(CompatNormalForce, NodesNextToTheRingSeeItUncrimped) {
  // Node (1, j): its warp's bending stencils reach the ring node (0, j), which the published code
  // leaves on the centre line. Assembled here from the bending term on hand-made crimped copies.
  const WovenGrid g(plain_scene(9, 9));
  ContactNormals published = make(g, NormalForceStretch::centre_lines);
  const auto flat = [](int i, int j) { return Vec3(i * kL, j * kL, 0.0); };
  published.compute(state(g, flat));
  const int j = 4;
  const auto warp_copy = [&](int i) {
    const double offset = g.interior(i, j) ? kR * g.sign(i, j) : 0.0;
    return Vec3(flat(i, j) - offset * Vec3::UnitZ());
  };
  Vec3 warp_force = Vec3::Zero();  // stencils centred at i = 1 (node as centre) and i = 2 (as previous)
  warp_force += BendingTerm::local_force(warp_copy(1), warp_copy(2), warp_copy(0), 2 * kL, 0.0, kKbU).segment<3>(0);
  warp_force += BendingTerm::local_force(warp_copy(2), warp_copy(3), warp_copy(1), 3 * kL, kL, kKbU).segment<3>(6);
  const Vec3 n = g.sign(1, j) * Vec3::UnitZ();
  const double expected = 0.5 * (n.dot(warp_force) + bending_push(kKbV, kL));  // the weft is deep
  EXPECT_GT(expected, 0.0);
  EXPECT_NEAR(published.normal_force()[g.node(1, j)], expected, 1e-12 * expected);
  ContactNormals lab = make(g, NormalForceStretch::crimped_copies);
  lab.compute(state(g, flat));
  EXPECT_GT(lab.normal_force()[g.node(1, j)], 2.0 * expected);  // the crimped stretch dominates
}

TEST(CompatNormalForce, BendingAtRestIgnoresTheSlidingCoordinates) {
  // A flat sheet: on the centre lines the stretch has no normal part, so F_n is the bending of the
  // crimped copies alone. Sliding some crossings changes the lab's bending (U = u1 − u2) but not the
  // published one, which keeps U = 2L (docs/published_code.md row 24): it equals F_n at rest.
  const WovenGrid g(plain_scene(9, 9));
  const auto flat = [](int i, int j) { return Vec3(i * kL, j * kL, 0.0); };
  Vec slid = state(g, flat);
  for (int j = 2; j <= 6; ++j)
    for (int i = 2; i <= 6; ++i) {
      const NodeDofs& d = g.dofs(g.node(i, j));
      slid[d.u] += 0.1 * kL * ((i * 3 + j) % 5 - 2);
      slid[d.v] -= 0.07 * kL * ((i + 2 * j) % 3 - 1);
    }
  ContactNormals at_rest(g, std::vector<double>(g.nv(), kKsU), std::vector<double>(g.nv(), kKbU),
                         std::vector<double>(g.nu(), kKsV), std::vector<double>(g.nu(), kKbV), kR,
                         NormalForceStretch::centre_lines, true);
  ContactNormals current = make(g, NormalForceStretch::centre_lines),
                 reference = make(g, NormalForceStretch::centre_lines);
  at_rest.compute(slid);
  current.compute(slid);
  reference.compute(state(g, flat));
  int changed = 0;
  for (int j = 1; j < 8; ++j)
    for (int i = 1; i < 8; ++i) {
      const int id = g.node(i, j);
      EXPECT_NEAR(at_rest.normal_force()[id], reference.normal_force()[id], 1e-12 * reference.normal_force()[id]);
      changed +=
          std::abs(current.normal_force()[id] - reference.normal_force()[id]) > 1e-3 * reference.normal_force()[id];
    }
  EXPECT_GT(changed, 10);
  EXPECT_THROW(at_rest.compute_gradient(slid), std::invalid_argument);
}

TEST(CompatNormalForce, ExactGradientIsRefused) {
  const WovenGrid g(plain_scene(5, 5));
  ContactNormals published = make(g, NormalForceStretch::centre_lines);
  const Vec q = state(g, [](int i, int j) { return Vec3(i * kL, j * kL, 0.0); });
  published.compute(q);
  EXPECT_THROW(published.compute_gradient(q), std::invalid_argument);
}

// The shipped scene with every switch on, after 10 steps of its integrator (sheared, sliding,
// F_n > 0): the assembled Jacobians are the exact derivatives of the force with F_n and F_u frozen,
// as for the lab's model (yarn_model_jacobian_test.cpp), block by block; and F_n is not the lab's.
TEST(CompatModel, JacobiansMatchDifferencesOfTheFrozenForce) {
  Scene scene = load_scene(WEAVELAB_SOURCE_DIR "/experiments/scenes/hanging_wind.toml");
  scene.compat.normal_force_on_centre_lines = true;
  scene.compat.wind_alternating_diagonals = true;
  scene.compat.bending_sliding_theta = true;
  scene.compat.parallel_contact_attractive = true;
  scene.compat.ring_unsigned = true;
  scene.compat.shear_lock_actual_angle = true;
  scene.compat.shear_lock_published_derivative = true;
  scene.compat.shear_interior_only = true;
  scene.compat.normal_force_bending_at_rest = true;
  YarnModel m(scene);
  BackwardEuler be(BackwardEuler::Variant::linear);
  IntegratorOptions opt;
  opt.dt = 1e-3;
  be.initialize(m, 0.0, m.initial_q(), m.initial_v(), opt);
  ASSERT_EQ(be.advance_to(0.01).outcome, Outcome::ok);
  const Vec q = be.q(), v = be.v();
  Evaluation ev;
  allocate_evaluation(m, ev);
  m.evaluate(0.01, q, v, kForce | kDfdq | kDfdv, ev);
  ASSERT_LT((test::frozen_force(m, q, v) - ev.force).norm(), 1e-12 * ev.force.norm());

  const std::vector<int> kind = test::dof_kinds(m);
  std::vector<int> cols;
  std::mt19937 rng(23);
  std::uniform_int_distribution<int> pick(0, m.num_dofs() - 1);
  std::vector<char> fixed(m.num_dofs(), 0);
  for (int f : m.fixed_dofs()) fixed[f] = 1;
  while (cols.size() < 90) {
    const int c = pick(rng);
    if (!fixed[c]) cols.push_back(c);
  }
  const double hq = 1e-6 * (q.maxCoeff() - q.minCoeff()), hv = 1e-2 * (v.maxCoeff() - v.minCoeff());
  test::Blocks dq, dv;
  for (int c : cols) {
    Vec qp = q, qm = q, vp = v, vm = v;
    qp[c] += hq;
    qm[c] -= hq;
    vp[c] += hv;
    vm[c] -= hv;
    dq.add(kind, c, (test::frozen_force(m, qp, v) - test::frozen_force(m, qm, v)) / (2 * hq), Vec(ev.dfdq.col(c)));
    dv.add(kind, c, (test::frozen_force(m, q, vp) - test::frozen_force(m, q, vm)) / (2 * hv), Vec(ev.dfdv.col(c)));
  }
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) {
      const std::string block = std::string(test::kDofKind[r]) + "-" + test::kDofKind[c];
      if (dq.ref[r][c] > 0.0) {
        EXPECT_LT(dq.relative(r, c), 1e-6) << "df/dq " << block;
      }
      if (dv.ref[r][c] > 0.0) {
        EXPECT_LT(dv.relative(r, c), 1e-6) << "df/dv " << block;
      }
    }
  EXPECT_GT(dq.ref[0][0], 0.0);
  EXPECT_GT(dq.ref[1][0], 0.0);

  // At this state the published F_n is positive but far below the lab's (docs/published_code.md row 1).
  YarnModel lab(load_scene(WEAVELAB_SOURCE_DIR "/experiments/scenes/hanging_wind.toml"));
  const auto normal_force = [&](const YarnModel& model) {
    for (const DataArray& a : model.frame(0.01, q, v).point_data)
      if (a.name == "F_n") return a.values;
    ADD_FAILURE() << "no point data F_n";
    return std::vector<double>{};
  };
  const std::vector<double> fn_pub = normal_force(m), fn_lab = normal_force(lab);
  ASSERT_EQ(fn_pub.size(), fn_lab.size());
  double max_pub = 0.0, min_lab = 1e300;
  for (int j = 1; j + 1 < m.grid().nv(); ++j)
    for (int i = 1; i + 1 < m.grid().nu(); ++i) {
      const int id = m.grid().node(i, j);
      max_pub = std::max(max_pub, fn_pub[id]);
      min_lab = std::min(min_lab, fn_lab[id]);
    }
  EXPECT_GT(max_pub, 0.0);
  EXPECT_LT(max_pub, 1e-2 * min_lab);
}

TEST(CompatKeys, WindDiagonalsAreReadAndRefuseOtherValues) {
  EXPECT_FALSE(parse_scene("", "s.toml").compat.wind_alternating_diagonals);
  EXPECT_TRUE(parse_scene("[compat]\nwind_diagonals = \"alternating\"\n", "s.toml").compat.wind_alternating_diagonals);
  EXPECT_FALSE(parse_scene("[compat]\nwind_diagonals = \"one\"\n", "s.toml").compat.wind_alternating_diagonals);
  const SceneError e = scene_error("[compat]\nnormal_force_stretch = \"crimped\"\nwind_diagonals = \"both\"\n");
  EXPECT_EQ(e.key, "compat.wind_diagonals");
  EXPECT_EQ(e.line, 3);
  EXPECT_NE(e.expected.find("alternating"), std::string::npos) << e.what();
}

// A resting upright cloth in a wind along its normal: every triangle of area a = L²/2 takes the
// pressure ρ_w a v_w² along the wind, a third on each of its nodes (docs/models.md §3.9), so each
// node carries (its number of triangles)·ρ_w a v_w²/3. The triangles are counted here from the
// published split: cell (i, j) along (i, j)–(i+1, j+1) when i + j is even, else along the other diagonal.
TEST(CompatWind, AlternatingDiagonalsShareThePressureByTriangleCount) {
  const int n = 5;
  const double vw = 5.0, rho_w = 2.0;
  std::string text =
      "[cloth]\nwarps = 5\nwefts = 5\nspacing_m = 0.001\nradius_m = 0.0005\n"
      "[wind]\nvelocity_m_per_s = [0.0, 5.0, 0.0]\nair_density_kg_per_m3 = 2.0\n"
      "drag_Ns_per_m3 = 0.5\n[terms]\n";
  for (const char* term :
       {"stretch", "bending", "shear", "parallel_contact", "friction", "gravity", "handles", "inertia"})
    text += std::string(term) + " = false\n";
  const auto node_forces = [&](const std::string& compat) {
    YarnModel m(parse_scene(text + compat, "s.toml"));
    Evaluation ev;
    allocate_evaluation(m, ev);
    m.evaluate(0.0, m.initial_q(), m.initial_v(), kForce, ev);
    std::vector<Vec3> f;
    for (int id = 0; id < n * n; ++id) f.push_back(ev.force.segment<3>(m.grid().dofs(id).x));
    return f;
  };
  std::vector<int> triangles(n * n, 0), triangles_one(n * n, 0);
  const auto count = [&](std::vector<int>& c, int a, int b, int d) { ++c[a], ++c[b], ++c[d]; };
  for (int j = 0; j + 1 < n; ++j)
    for (int i = 0; i + 1 < n; ++i) {
      const int n00 = i + n * j, n10 = n00 + 1, n01 = n00 + n, n11 = n01 + 1;
      count(triangles_one, n00, n10, n11), count(triangles_one, n00, n11, n01);
      if ((i + j) % 2 == 0) count(triangles, n00, n10, n11), count(triangles, n00, n11, n01);
      else count(triangles, n00, n10, n01), count(triangles, n10, n11, n01);
    }
  const double per_triangle = rho_w * 0.5 * 1e-6 * vw * vw / 3.0;
  const std::vector<Vec3> alternating = node_forces("[compat]\nwind_diagonals = \"alternating\"\n");
  const std::vector<Vec3> one = node_forces("");
  int differing = 0;
  for (int id = 0; id < n * n; ++id) {
    EXPECT_LT((alternating[id] - Vec3(0, triangles[id] * per_triangle, 0)).norm(), 1e-12 * per_triangle) << id;
    EXPECT_LT((one[id] - Vec3(0, triangles_one[id] * per_triangle, 0)).norm(), 1e-12 * per_triangle) << id;
    differing += triangles[id] != triangles_one[id];
  }
  EXPECT_GT(differing, 0);
}

}  // namespace
}  // namespace wl
