// Yarn–yarn contact of a knit (docs/models.md §11.10): the filter leaves the
// tiled rest shape untouched (no pair it keeps starts within d̂, so the
// contact adds nothing to the rest force, while without the filter the rib's
// touching wales would start in contact); [self_contact] on a knit scene
// is accepted, and a d̂ not below the yarn radius is refused naming the key.
#include <gtest/gtest.h>

#include <stdexcept>

#include "models/knit/knit_model.h"
#include "models/knit/yarn_contact.h"
#include "models/model_factory.h"

namespace wl {
namespace {

std::string knit_text(const std::string& kind, const std::string& self_contact) {
  return "[cloth]\nspacing_m = 2e-3\nradius_m = 2e-4\nsliding = true\n[cloth.pattern]\nkind = \"" + kind +
         "\"\ncourses = 4\nwales = 8\n[knit]\nroll_stiffness_N = 1e-5\nstitch_length_stiffness_N = 0.1\n"
         "[gravity]\nacceleration_m_per_s2 = [0, 0, 0]\n[pose]\nkind = \"flat\"\n" +
         self_contact;
}

// The knit's pieces and the compression's pairs among them, as the model builds them.
struct Pieces {
  std::vector<YarnPiece> pieces;
  std::vector<PiecePair> modelled;
};
Pieces knit_pieces(const KnitModel& m, double radius) {
  const KnitGraph& g = m.graph();
  std::vector<YarnPiece> all;
  for (int y = 0; y < static_cast<int>(g.yarns().size()); ++y)
    for (int k = 0; k < static_cast<int>(g.yarns()[y].visits.size()); ++k) {
      const KnitGraph::Step s = g.next(y, k);
      if (s.k >= 0) all.push_back({g.yarns()[y].visits[k].node, g.yarns()[y].visits[s.k].node});
    }
  Pieces p{unique_pieces(all), {}};
  std::vector<Vec3> x;
  for (const KnitNode& n : g.nodes()) x.push_back(n.x);
  p.modelled = compression_pairs(x, p.pieces, {Vec3::Zero()}, knit_compression_cutoff(g.layout(), radius));
  return p;
}

TEST(KnitYarnContact, TheFilterLeavesTheRestShapeUntouched) {
  for (const char* kind : {"stockinette", "garter", "rib2x2"}) {
    const Scene on = parse_scene(knit_text(kind, "[self_contact]\nenabled = true\n"), "knit.toml");
    const Scene off = parse_scene(knit_text(kind, ""), "knit.toml");
    KnitModel with(on), without(off);
    ASSERT_NE(with.describe().at("terms").find("self_contact"), std::string::npos) << kind;
    const Vec& q0 = with.initial_q();
    ASSERT_EQ(q0, without.initial_q()) << kind;
    EXPECT_EQ(with.intersecting_pairs(q0), 0) << kind;
    const Vec v = Vec::Zero(with.num_dofs());
    Evaluation a, b;
    allocate_evaluation(with, a);
    allocate_evaluation(without, b);
    with.evaluate(0.0, q0, v, kForce, a);
    without.evaluate(0.0, q0, v, kForce, b);
    EXPECT_EQ((a.force - b.force).cwiseAbs().maxCoeff(), 0.0) << kind << ": the contact pushes at rest";

    // Without the filter capsules of neighbouring loops start within d̂: at
    // the relaxed period (docs/models.md §11.3.1) the loops of every pattern
    // pack until they touch (the rib's knit and purl wales too), so every
    // pattern needs it.
    const Pieces p = knit_pieces(with, on.radius_m);
    ASSERT_GT(p.modelled.size(), 0u) << kind;
    const ObstacleContactRule rule = knit_contact_rule(on, with.graph(), p.pieces);
    KnitContactSet set = knit_contact_set(with.graph(), p.pieces, p.modelled, on.radius_m);
    const SelfContactTerm filtered(set.surface, rule.activation_distance_m, rule.stiffness_N_per_m, set.capsules);
    set.capsules.modelled.clear();
    const SelfContactTerm unfiltered(set.surface, rule.activation_distance_m, rule.stiffness_N_per_m, set.capsules);
    auto within_dhat = [&](const SelfContactTerm& t) {
      int n = 0;
      for (const auto& pair : t.candidates(q0, q0, rule.activation_distance_m))
        n += t.distance(pair, q0) < rule.activation_distance_m;
      return n;
    };
    EXPECT_EQ(within_dhat(filtered), 0) << kind;
    EXPECT_GT(within_dhat(unfiltered), 0) << kind;
  }
}

// d̂ defaults to R/2; d̂ = R is refused naming the scene's [self_contact] line and the key.
TEST(KnitYarnContact, AnActivationDistanceNotBelowTheYarnRadiusIsRefused) {
  const Scene fine = parse_scene(knit_text("stockinette", "[self_contact]\nenabled = true\n"), "knit.toml");
  const KnitModel m(fine);
  const Pieces p = knit_pieces(m, fine.radius_m);
  EXPECT_DOUBLE_EQ(knit_contact_rule(fine, m.graph(), p.pieces).activation_distance_m, 0.5 * fine.radius_m);
  const Scene coarse = parse_scene(
      knit_text("stockinette", "[self_contact]\nenabled = true\nactivation_distance_m = 0.0002\n"), "knit.toml");
  try {
    make_model(coarse, "knit");
    ADD_FAILURE() << "accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("knit.toml:16: self_contact.activation_distance_m: d̂ = 0.0002 m; expected "
                                         "d̂ below 0.0002 m, the yarn radius"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace wl
