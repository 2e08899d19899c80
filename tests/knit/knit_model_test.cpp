// The knit model (docs/models.md §11): the graph of a pattern, knit against
// purl, the relaxed tile, the tiled rest state that stays still away from the
// edges, and the assembled Jacobian of the cloth and of the periodic tile.
#include "models/knit/knit_model.h"

#include <gtest/gtest.h>

#include <cmath>

#include "calibration/scene_parameters.h"
#include "models/knit/knit_rest_shape.h"
#include "models/model_factory.h"
#include "tests/support/fd_check.h"

namespace wl {
namespace {

Scene knit_scene(const std::string& kind, int courses, int wales, bool sliding = true) {
  return parse_scene("[cloth]\nspacing_m = 2e-3\nradius_m = 2e-4\nsliding = " +
                         std::string(sliding ? "true" : "false") + "\n[cloth.pattern]\nkind = \"" + kind +
                         "\"\ncourses = " + std::to_string(courses) + "\nwales = " + std::to_string(wales) +
                         "\n[knit]\nroll_stiffness_N = 1e-5\nstitch_length_stiffness_N = 0.1\n"
                         "[gravity]\nacceleration_m_per_s2 = [0, 0, 0]\n[pose]\nkind = \"flat\"\n",
                     "knit.toml");
}

double k_s(const Scene& s) { return 5e5 * M_PI * s.radius_m * s.radius_m; }

TEST(KnitGraph, StockinetteCounts) {
  const KnitModel m(knit_scene("stockinette", 4, 3));
  const KnitGraph& g = m.graph();
  // (courses + 1) contact rows × wales × 2 sides × 2 nodes; two-yarn contacts
  // between consecutive courses only; 8 visits per loop.
  EXPECT_EQ(g.num_nodes(), 5 * 3 * 4);
  EXPECT_EQ(static_cast<int>(g.stitches().size()), 3 * 3 * 2);
  ASSERT_EQ(g.yarns().size(), 4u);
  for (const KnitYarn& y : g.yarns()) EXPECT_EQ(y.visits.size(), 8u * 3u);
  int two = 0;
  for (const KnitNode& n : g.nodes()) two += n.u.size() == 2 ? 1 : 0;
  EXPECT_EQ(two, 2 * static_cast<int>(g.stitches().size()));
}

// Knit and purl differ by which way the stitch segment crosses the cloth
// (docs/models.md §11.2): garter alternates by course, rib by pairs of wales.
TEST(KnitGraph, KnitAndPurlCrossTheClothOppositeWays) {
  for (const std::string kind : {"garter", "rib2x2"}) {
    const KnitModel m(knit_scene(kind, 4, 8));
    int knit = 0, purl = 0;
    for (const StitchContact& c : m.graph().stitches()) {
      const double rise = m.graph().node(c.b).x.z() - m.graph().node(c.a).x.z();
      const bool expect_purl = kind == "garter" ? (c.course + 1) % 2 == 1 : c.wale % 4 >= 2;
      EXPECT_EQ(c.purl, expect_purl);
      EXPECT_EQ(rise < 0.0, c.purl) << kind << " contact at course " << c.course << ", wale " << c.wale;
      (c.purl ? purl : knit) += 1;
    }
    EXPECT_GT(knit, 0);
    EXPECT_GT(purl, 0);
  }
}

TEST(KnitRestShape, TheTileRelaxesToAStaticEquilibrium) {
  for (const std::string kind : {"stockinette", "garter", "rib2x2"}) {
    const Scene s = knit_scene(kind, 4, 4);
    const KnitRestShape r = relax_knit_tile(s);
    EXPECT_LE(r.residual_N, kKnitRestTolerance * k_s(s)) << kind;
    EXPECT_LT(r.energy_relaxed_J, r.energy_generated_J) << kind;
    double moved = 0.0;
    for (const Vec3& d : r.dx) moved = std::max(moved, d.norm());
    EXPECT_GT(moved, 1e-3 * s.radius_m) << kind << ": the relaxation should change the generated loops";
  }
}

// The tiled rest state without gravity: the nodes whose every element lies
// inside the cloth see the relaxed tile and stay still (force below the
// bound), while the generated state and the free edges are not in equilibrium.
TEST(KnitRestShape, TheTiledRestStateStaysStillInside) {
  for (const std::string kind : {"stockinette", "garter"}) {
    const Scene s = knit_scene(kind, 6, 6);
    KnitModel m(s);
    Evaluation eval;
    allocate_evaluation(m, eval);
    const Vec q = m.initial_q(), v = Vec::Zero(m.num_dofs());
    m.evaluate(0.0, q, v, kForce, eval);
    const KnitGraph& g = m.graph();
    const double bound = 1e-9 * k_s(s);
    double inside = 0.0, edge = 0.0;
    for (int n = 0; n < g.num_nodes(); ++n) {
      const int contact = n / 2, c = (contact / 2) % 6, r = contact / 2 / 6 - 1;
      const KnitNode& node = g.node(n);
      double f = eval.force.segment<3>(node.x_dof).cwiseAbs().maxCoeff();
      for (int k : node.coord)
        if (is_dof(k)) f = std::max(f, std::abs(eval.force[k]));
      if (r >= 1 && r <= 3 && c >= 1 && c <= 4) inside = std::max(inside, f);
      else edge = std::max(edge, f);
    }
    EXPECT_LE(inside, bound) << kind;
    EXPECT_GT(edge, 1e3 * bound) << kind << ": the free edges are not in equilibrium";
    // Without the relaxation the inside is not at rest either.
    const auto tile = KnitModel::tile(s);
    Evaluation te;
    allocate_evaluation(*tile, te);
    tile->evaluate(0.0, tile->initial_q(), Vec::Zero(tile->num_dofs()), kForce, te);
    EXPECT_GT(te.force.cwiseAbs().maxCoeff(), 1e3 * bound) << kind;
  }
}

// ∂f/∂q of the assembled cloth (gravity, inertia at v = 0 included) and of the
// periodic tile (elements across its border through ImageTerm) against finite differences.
TEST(KnitModel, AssembledJacobianMatchesFiniteDifferences) {
  Scene s = knit_scene("rib2x2", 3, 4);
  s.gravity_m_per_s2 = {0.0, 0.0, -9.81};
  std::vector<std::unique_ptr<Model>> models;
  models.push_back(make_model(s, "knit"));
  models.push_back(KnitModel::tile(s));
  for (auto& model : models) {
    const int n = model->num_dofs();
    Vec q = model->initial_q();
    for (int k = 0; k < n; ++k) q[k] += 2e-5 * std::sin(1.3 * k);  // off the rest state
    const Vec v = Vec::Zero(n);
    Evaluation eval;
    allocate_evaluation(*model, eval);
    model->evaluate(0.0, q, v, kForce | kDfdq, eval);
    const SparseMatrix K = eval.dfdq;
    auto force = [&](const Vec& x) {
      Evaluation e;
      allocate_evaluation(*model, e);
      model->evaluate(0.0, x, v, kForce, e);
      return Vec(e.force);
    };
    std::vector<int> cols;
    for (int k = 0; k < n; k += std::max(1, n / 40)) cols.push_back(k);
    test::FdOptions opt;
    opt.rel_step = 1e-7;
    opt.rtol = 1e-5;
    const auto r = test::check_jacobian_columns(
        force, q, [&](int j) { return Vec(K.col(j)); }, cols, opt);
    EXPECT_TRUE(r.ok) << model->describe().at("model") << ": " << r.detail;
  }
}

// The deepest overlap (2R − d, 2R − σh) over the elements of the contact
// compression term `name` of a model at state q, from each element's energy
// ½ κ (2R − d)² (docs/models.md §11.6); −1 without such a term.
double deepest_overlap(const KnitModel& m, const Vec& q, double kappa, const std::string& name) {
  double deepest = -1.0;
  const Vec v = Vec::Zero(m.num_dofs());
  for (const auto& term : m.terms()) {
    if (term->name() != name) continue;
    std::vector<double> lq(term->stencil_size()), lv(term->stencil_size());
    for (int e = 0; e < term->num_elements(); ++e) {
      m.gather_local(*term, e, q, v, lq.data(), lv.data());
      deepest = std::max(deepest, std::sqrt(2.0 * term->energy(e, lq.data()) / kappa));
    }
  }
  return deepest;
}

// Without the compression the relaxed stitches collapse: the two yarns of a
// stitch pass into each other and its front and back are lost. With it every
// stitch keeps its two yarns 2R apart through the cloth to within a tenth,
// and no two watched pieces of yarn overlap by more.
TEST(KnitCompression, TheRelaxedStitchesKeepTheirYarnsApart) {
  for (const std::string kind : {"stockinette", "garter"}) {
    Scene s = knit_scene(kind, 4, 4);
    const double D = 2.0 * s.radius_m, kappa = s.knit->compression_stiffness_N_per_m;
    const KnitModel held(s);
    const double stitch = deepest_overlap(held, held.initial_q(), kappa, "stitch_compression");
    const double pieces = deepest_overlap(held, held.initial_q(), kappa, "yarn_compression");
    s.knit->compression_stiffness_N_per_m = 1e-12;  // the terms watch, their force is negligible
    const KnitModel free(s);
    const double collapsed = deepest_overlap(free, free.initial_q(), 1e-12, "stitch_compression");
    EXPECT_GE(stitch, 0.0) << kind << ": no stitch compression term";
    EXPECT_GE(pieces, 0.0) << kind << ": no yarn compression term";
    EXPECT_LE(stitch, 0.1 * D) << kind;
    EXPECT_LE(pieces, 0.1 * D) << kind;
    EXPECT_GT(collapsed, 0.5 * D) << kind << ": without compression the stitches should collapse";
  }
}

// The stiffness κ is read from [knit] (default 100 N/m), 0 builds neither
// compression term, and a negative value is a located error.
TEST(KnitCompression, StiffnessKey) {
  const std::string head = "[cloth.pattern]\nkind = \"stockinette\"\ncourses = 4\nwales = 4\n[knit]\n";
  EXPECT_DOUBLE_EQ(parse_scene(head, "ok.toml").knit->compression_stiffness_N_per_m, 100.0);
  EXPECT_DOUBLE_EQ(
      parse_scene(head + "compression_stiffness_N_per_m = 0\n", "ok.toml").knit->compression_stiffness_N_per_m, 0.0);
  Scene off = knit_scene("stockinette", 4, 4);
  off.knit->compression_stiffness_N_per_m = 0.0;
  const KnitModel m(off);
  for (const auto& t : m.terms()) EXPECT_EQ(t->name().find("compression"), std::string::npos) << t->name();
  try {
    parse_scene(head + "compression_stiffness_N_per_m = -1\n", "bad.toml");
    ADD_FAILURE() << "a negative κ should be rejected";
  } catch (const SceneError& e) {
    EXPECT_EQ(e.line, 6);
    EXPECT_EQ(e.key, "knit.compression_stiffness_N_per_m");
  }
}

// What `fit` refuses on a knit (docs/calibration.md §8.1) is what its initial state, the relaxed
// rest shape, depends on: a 1 % change of each refused key moves q0, of each fitted key not at all.
TEST(KnitModel, TheRestShapeDependsOnTheKeysTheFitRefuses) {
  const Scene s = knit_scene("stockinette", 3, 3);
  const Vec q0 = KnitModel(s).initial_q();
  auto moved = [&](const std::string& key) {
    Scene t = s;
    set_scene_parameter(t, key, 1.01 * scene_parameter(s, key));
    return (KnitModel(t).initial_q() - q0).norm();
  };
  for (const char* key : {"yarn_types.default.stretch_modulus_Pa", "yarn_types.default.bending_modulus_Pa",
                          "knit.stitch_length_stiffness_N", "knit.compression_stiffness_N_per_m"})
    EXPECT_GT(moved(key), 1e-9) << key;
  for (const char* key : {"yarn_types.default.density_kg_per_m", "knit.roll_stiffness_N"})
    EXPECT_EQ(moved(key), 0.0) << key;
}

// A knit's continuum takes its stiffnesses from a calibration, never from the yarn
// (docs/models.md §11.9): without them the fem model is refused, naming the first key.
TEST(KnitModel, TheFemModelOfAKnitNeedsCalibratedStiffnesses) {
  try {
    make_model(knit_scene("stockinette", 3, 3), "fem");
    ADD_FAILURE() << "a knit's continuum without stiffnesses should be refused";
  } catch (const SceneError& e) {
    EXPECT_EQ(e.key, "fem.warp_stretch_N_per_m");
    EXPECT_NE(e.expected.find("calibrate"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace wl
