// Yarn–yarn contact of a knit (docs/models.md §11.10): the filter leaves the
// tiled rest shape untouched (no pair it keeps starts within d̂, so the
// contact adds nothing to the rest force, while without the filter the rib's
// touching wales would start in contact); [self_contact] on a knit scene
// is accepted, and a d̂ not below the yarn radius is refused naming the key;
// a stockinette patch folded and its flap thrown onto the rest passes
// through it without the contact and never with it.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "integrators/integrator.h"
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

// The flat patch (courses along +y, face +z) folded over its face about the
// line y = y_f: a piece s = y − y_f > 0 past the line is bent round a
// cylinder of radius r (axis at z = r), and beyond the half turn it lies
// upside down above the rest, its mid-plane 2r above it. The flap moves
// towards the rest at `speed` (the bend's nodes in proportion to their turn).
struct Fold {
  Vec q, v;
  std::vector<bool> flap;  // the nodes past the half turn
};
Fold folded(const KnitModel& m, double y_fold, double r, double speed) {
  Fold f{m.initial_q(), Vec::Zero(m.num_dofs()), {}};
  for (const KnitNode& n : m.graph().nodes()) {
    const Vec3 x = f.q.segment<3>(n.x_dof);
    const double s = x.y() - y_fold, turn = std::clamp(s / r, 0.0, M_PI);
    f.flap.push_back(s > M_PI * r);
    if (s <= 0.0) continue;
    const double along = s - r * turn;  // past the half turn
    f.q.segment<3>(n.x_dof) =
        Vec3(x.x(), y_fold + (r - x.z()) * std::sin(turn) - along, r - (r - x.z()) * std::cos(turn));
    f.v[n.x_dof + 2] = -speed * turn / M_PI;
  }
  return f;
}

// A stockinette of 8 courses × 6 wales folded over its face at its middle
// (r = 1 mm, the flap's mid-plane 2 mm above the rest) and its flap thrown
// onto the rest at 2 m/s, 4 ms of be-newton at 0.25 ms: without yarn–yarn
// contact it passes through the rest (intersecting pairs, the flap's nodes
// below the rest's mean height), with it no step ever leaves an intersecting
// pair and the flap stays above.
TEST(KnitYarnContact, AFoldedPatchThrownOntoItselfDoesNotPassThrough) {
  for (bool contact : {false, true}) {
    SCOPED_TRACE(contact ? "with contact" : "without contact");
    const std::string text =
        "[cloth]\nspacing_m = 2e-3\nradius_m = 2e-4\nsliding = true\n[cloth.pattern]\nkind = \"stockinette\"\n"
        "courses = 8\nwales = 6\ncourse_spacing_m = 1.6e-3\n[knit]\nroll_stiffness_N = 1e-5\n"
        "stitch_length_stiffness_N = 0.1\n[gravity]\nacceleration_m_per_s2 = [0, 0, 0]\n[pose]\nkind = \"flat\"\n"
        "[damping]\nyarn_viscosity_Pa_s = 10.0\n" +
        std::string(contact ? "[self_contact]\nenabled = true\n" : "");
    const KnitModel m(parse_scene(text, "fold.toml"));
    double y_min = INFINITY, y_max = -INFINITY;
    for (const KnitNode& n : m.graph().nodes()) {
      y_min = std::min(y_min, m.initial_q()[n.x_dof + 1]);
      y_max = std::max(y_max, m.initial_q()[n.x_dof + 1]);
    }
    const Fold f = folded(m, 0.5 * (y_min + y_max), 1e-3, 2.0);
    ASSERT_EQ(m.intersecting_pairs(f.q), 0);
    auto integ = make_integrator("be-newton");
    IntegratorOptions opt;
    opt.dt = 2.5e-4;
    integ->initialize(m, 0.0, f.q, f.v, opt);
    long most = 0;
    integ->on_step = [&](const StepRecord&) { most = std::max(most, m.intersecting_pairs(integ->q())); };
    const StepResult r = integ->advance_to(4e-3);
    ASSERT_EQ(r.outcome, Outcome::ok) << r.message;
    // The flap's lowest node against the mean height of the rest (y < y_f).
    double lowest_flap = INFINITY, rest_z = 0.0;
    int rest = 0;
    for (int k = 0; k < m.graph().num_nodes(); ++k) {
      const Vec3 x = m.position(integ->q(), k);
      if (f.flap[k]) lowest_flap = std::min(lowest_flap, x.z());
      if (f.q[m.graph().node(k).x_dof + 1] < 0.5 * (y_min + y_max)) rest_z += x.z(), ++rest;
    }
    rest_z /= rest;
    std::printf("%s: most intersecting pairs %ld, at the end %ld, lowest flap node %.3g m above the rest's mean\n",
                contact ? "with" : "without", most, m.intersecting_pairs(integ->q()), lowest_flap - rest_z);
    if (contact) {
      EXPECT_EQ(most, 0);
      EXPECT_GT(lowest_flap, rest_z);
    } else {
      EXPECT_GT(m.intersecting_pairs(integ->q()), 0);
      EXPECT_LT(lowest_flap, rest_z);
    }
  }
}

}  // namespace
}  // namespace wl
