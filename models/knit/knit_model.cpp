#include "models/knit/knit_model.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <numbers>
#include <sstream>
#include <stdexcept>

#include "models/common/yarn_damper.h"
#include "models/knit/compression_pairs.h"
#include "models/knit/image_term.h"
#include "models/knit/knit_boundary.h"
#include "models/knit/knit_rest_shape.h"
#include "models/knit/knit_scene_error.h"
#include "models/knit/stack_pairs.h"
#include "models/knit/terms/stitch_compression.h"
#include "models/knit/terms/stitch_length.h"
#include "models/knit/terms/stitch_roll.h"
#include "models/knit/terms/yarn_compression.h"
#include "models/knit/yarn_contact.h"
#include "models/scene/parameter_keys.h"
#include "models/yarn/terms/bending.h"
#include "models/yarn/terms/gravity.h"
#include "models/yarn/terms/segment_inertia.h"
#include "models/yarn/terms/stretch.h"

namespace wl {
namespace {

constexpr const char* kKnitKindNames[] = {"stockinette", "garter", "rib2x2"};  // KnitPattern::Kind order

// A term under construction with the image shift of every element's entries;
// it is wrapped in an ImageTerm when any shift is non-zero (the periodic tile).
template <class T>
struct Building {
  std::unique_ptr<T> term = std::make_unique<T>();
  std::vector<double> shift;
  bool shifted = false;
  void add_shift(std::initializer_list<double> s) {
    for (double x : s) {
      shift.push_back(x);
      shifted = shifted || x != 0.0;
    }
  }
  void add_shift(const Vec3& a) { add_shift({a[0], a[1], a[2]}); }
  void finish(std::vector<std::unique_ptr<Term>>& terms) {
    if (term->num_elements() == 0) return;
    if (shifted) terms.push_back(std::make_unique<ImageTerm>(std::move(term), std::move(shift)));
    else terms.push_back(std::move(term));
  }
};

}  // namespace

// The stitch of loop (course, wale) per pattern (docs/models.md §11.2):
// stockinette all knit; garter knit and purl courses alternating; 2×2 rib two
// knit and two purl wales. The tile is the smallest repeating block.
KnitLayout knit_layout(const Scene& scene, bool tile) {
  const KnitPattern& k = *scene.knit;
  KnitLayout L;
  L.wale_spacing = scene.spacing_m;
  L.course_spacing = k.course_spacing_m;
  L.thickness = scene.radius_m;
  L.periodic = tile;
  L.courses = k.courses;
  L.wales = k.wales;
  switch (k.kind) {
    case KnitPattern::Kind::stockinette:
      L.purl = [](int, int) { return false; };
      if (tile) L.courses = L.wales = 1;
      break;
    case KnitPattern::Kind::garter:
      L.purl = [](int r, int) { return ((r % 2) + 2) % 2 == 1; };
      if (tile) L.courses = 2, L.wales = 1;
      break;
    case KnitPattern::Kind::rib2x2:
      L.purl = [](int, int c) { return ((c % 4) + 4) % 4 >= 2; };
      if (tile) L.courses = 1, L.wales = 4;
      break;
  }
  return L;
}

std::unique_ptr<KnitModel> KnitModel::tile(const Scene& scene, const std::array<double, 2>& period_scale) {
  return std::unique_ptr<KnitModel>(new KnitModel(scene, true, period_scale));
}

KnitModel::KnitModel(const Scene& scene) : KnitModel(scene, false) {}

namespace {
KnitLayout with_period_scale(KnitLayout layout, const std::array<double, 2>& period_scale) {
  layout.period_scale = period_scale;
  return layout;
}
}  // namespace

KnitModel::KnitModel(const Scene& scene, bool tile, const std::array<double, 2>& period_scale)
    : scene_(scene), tile_(tile), graph_(with_period_scale(knit_layout(scene, tile), period_scale)) {
  // Frozen coordinates of the open cloth: the one-yarn nodes (below the first
  // and above the last course) and the contacts of the first and last wale, as
  // the woven model freezes its outer ring (docs/models.md §11.1).
  const int wales = graph_.layout().wales;
  auto frozen = [&](int n) {
    if (tile_) return false;
    const int contact = n / 2, c = (contact / 2) % wales;
    return graph_.node(n).u.size() < 2 || c == 0 || c == wales - 1;
  };
  constants_ = graph_.assign_dofs(scene.sliding, frozen, num_dofs_);
  visit_of_.resize(graph_.num_nodes());
  for (int n = 0; n < graph_.num_nodes(); ++n) visit_of_[n].assign(graph_.node(n).u.size(), {-1, -1});
  for (int y = 0; y < static_cast<int>(graph_.yarns().size()); ++y) {
    const auto& visits = graph_.yarns()[y].visits;
    for (int k = 0; k < static_cast<int>(visits.size()); ++k) {
      visit_of_[visits[k].node][visits[k].slot] = {y, k};
      const KnitGraph::Step s = graph_.next(y, k);
      if (s.k >= 0) segments_.push_back({y, k, s.k, visits[k].dx, visits[s.k].dx + s.dx, s.du});
    }
  }
  set_generated_state();
  if (!tile_) apply_rest_shape();
  add_segment_terms();
  if (scene.terms.bending) add_bending();
  add_stitch_terms();
  add_compression();
  if (!tile_) {
    apply_pose();
    add_yarn_contact();
    if (auto handles = knit_handles(graph_, scene_, q0_)) terms_.push_back(std::move(handles));
    fixed_ = knit_pinned_dofs(graph_, scene_);
  }
  finalize();
}

void KnitModel::set_generated_state() {
  q0_ = Vec::Zero(num_dofs_);
  v0_ = Vec::Zero(num_dofs_);
  for (const KnitNode& n : graph_.nodes()) {
    q0_.segment<3>(n.x_dof) = n.x;
    for (size_t s = 0; s < n.coord.size(); ++s)
      if (is_dof(n.coord[s])) q0_[n.coord[s]] = n.u[s];
  }
}

// Every node and coordinate takes the relaxed tile's displacement from the
// generated geometry at its place in the tile (docs/models.md §11.3).
void KnitModel::apply_rest_shape() {
  const KnitRestShape& rest = relaxed_tile(scene_);
  const KnitLayout& L = graph_.layout();
  const int tile_courses = rest.courses, tile_wales = rest.wales;
  for (int n = 0; n < graph_.num_nodes(); ++n) {
    const int contact = n / 2, end = n % 2, s = contact % 2, c = (contact / 2) % L.wales, r = contact / 2 / L.wales - 1;
    const int tr = ((r % tile_courses) + tile_courses) % tile_courses, tc = c % tile_wales;
    const int tn = ((tr * tile_wales + tc) * 2 + s) * 2 + end;
    const KnitNode& node = graph_.node(n);
    // The copy (Δr, Δc) of the tile lies (Δc·W·s₀, Δr·C·s₁) from the first, its relaxed period (§11.3.1).
    const int copy_r = (r - tr) / tile_courses, copy_c = (c - tc) / tile_wales;
    const Vec3 period_offset(copy_c * tile_wales * L.wale_spacing * (rest.period_scale[0] - 1.0),
                             copy_r * tile_courses * L.course_spacing * (rest.period_scale[1] - 1.0), 0.0);
    q0_.segment<3>(node.x_dof) += rest.dx[tn] + period_offset;
    // The slots of a one-yarn node are the head (below the last course's) or the leg (above the first).
    const bool leg_only = r < 0;
    for (size_t k = 0; k < node.coord.size(); ++k) {
      const int index = node.coord[k];
      (is_dof(index) ? q0_[index] : constants_[constant_slot(index)]) += rest.du[tn][leg_only ? 1 : k];
    }
  }
}

// Flat: the cloth in the plane z = height (courses along +y); upright: in the
// xz plane hanging down from z = height, its face towards −y (docs/models.md §11.2).
void KnitModel::apply_pose() {
  for (const KnitNode& n : graph_.nodes()) {
    const Vec3 x = q0_.segment<3>(n.x_dof);
    q0_.segment<3>(n.x_dof) = scene_.pose == Scene::Pose::upright ? Vec3(x[0], x[2], scene_.height_m - x[1])
                                                                  : Vec3(x[0], x[1], scene_.height_m + x[2]);
  }
}

// Stretch, inertia, gravity and damping on every yarn segment (docs/models.md
// §3.1, §3.2, §3.8, §3.12), with the course's yarn type.
void KnitModel::add_segment_terms() {
  const double area = std::numbers::pi * scene_.radius_m * scene_.radius_m;
  const Vec3 g(scene_.gravity_m_per_s2[0], scene_.gravity_m_per_s2[1], scene_.gravity_m_per_s2[2]);
  const TermSwitches& on = scene_.terms;
  Building<StretchTerm> stretch;
  Building<SegmentInertiaTerm> inertia;
  Building<YarnDamperTerm> damping;
  auto gravity = std::make_unique<GravityTerm>(g);
  const auto& types = scene_.warp_yarn_types;
  for (const Segment& s : segments_) {
    const std::string& type_name = types[s.yarn % types.size()];
    const YarnType& type = scene_.yarn_types.at(type_name);
    const KnitVisit &v0 = graph_.yarns()[s.yarn].visits[s.k0], &v1 = graph_.yarns()[s.yarn].visits[s.k1];
    const KnitNode &n0 = graph_.node(v0.node), &n1 = graph_.node(v1.node);
    const std::array<int, 8> st{n0.x_dof,     n0.x_dof + 1, n0.x_dof + 2,      n1.x_dof,
                                n1.x_dof + 1, n1.x_dof + 2, n0.coord[v0.slot], n1.coord[v1.slot]};
    const std::initializer_list<double> shift{s.dx0[0], s.dx0[1], s.dx0[2], s.dx1[0], s.dx1[1], s.dx1[2], 0.0, s.du1};
    if (on.stretch) {
      stretch.term->add(st, type.stretch_modulus_Pa * area);
      stretch.term->tag_last(yarn_type_key(type_name, kStretchModulusField), type.stretch_modulus_Pa);
      stretch.add_shift(shift);
    }
    if (tile_) continue;
    if (on.inertia) {
      inertia.term->add(st, type.density_kg_per_m);
      inertia.term->tag_last(yarn_type_key(type_name, kDensityField), type.density_kg_per_m);
    }
    if (on.gravity && g.norm() > 0.0) {
      gravity->add(st, type.density_kg_per_m);
      gravity->tag_last(yarn_type_key(type_name, kDensityField), type.density_kg_per_m);
    }
    if (scene_.yarn_viscosity_Pa_s > 0.0) {
      const double rest = n1.u[v1.slot] + s.du1 - n0.u[v0.slot];
      damping.term->add({st[0], st[1], st[2], st[3], st[4], st[5]},
                        yarn_damper_coefficient(scene_.yarn_viscosity_Pa_s, scene_.radius_m, rest));
    }
  }
  inertia.finish(terms_);
  stretch.finish(terms_);
  if (gravity->num_elements() > 0) terms_.push_back(std::move(gravity));
  damping.finish(terms_);
}

// Bending over every three consecutive visits of a yarn, with a straight rest
// shape (docs/models.md §3.3, §11.4: the loops' curvature is held by the stitches).
void KnitModel::add_bending() {
  const double area = std::numbers::pi * scene_.radius_m * scene_.radius_m;
  Building<BendingTerm> bending;
  const auto& types = scene_.warp_yarn_types;
  for (int y = 0; y < static_cast<int>(graph_.yarns().size()); ++y) {
    const auto& visits = graph_.yarns()[y].visits;
    const std::string& type_name = types[y % types.size()];
    const YarnType& type = scene_.yarn_types.at(type_name);
    for (int k = 0; k < static_cast<int>(visits.size()); ++k) {
      const KnitGraph::Step nx = graph_.next(y, k), pv = graph_.previous(y, k);
      if (nx.k < 0 || pv.k < 0) continue;
      const KnitVisit &v0 = visits[k], &v1 = visits[nx.k], &v2 = visits[pv.k];
      const KnitNode &n0 = graph_.node(v0.node), &n1 = graph_.node(v1.node), &n2 = graph_.node(v2.node);
      bending.term->add({n0.x_dof, n0.x_dof + 1, n0.x_dof + 2, n1.x_dof, n1.x_dof + 1, n1.x_dof + 2, n2.x_dof,
                         n2.x_dof + 1, n2.x_dof + 2, n1.coord[v1.slot], n2.coord[v2.slot]},
                        type.bending_modulus_Pa * area);
      bending.term->tag_last(yarn_type_key(type_name, kBendingModulusField), type.bending_modulus_Pa);
      bending.add_shift(v0.dx);
      bending.add_shift(v1.dx + nx.dx);
      bending.add_shift(v2.dx + pv.dx);
      bending.add_shift({nx.du, pv.du});
    }
  }
  bending.finish(terms_);
}

// At every stitch contact: each yarn's stitch-length penalty and the roll of
// every pair of its yarns about the stitch segment (docs/models.md §11.4;
// stack_pairs.h: n yarns, n(n−1)/2 pairs). L is the stitch segment's generated
// length; the roll's rest angle ψ̄ is that of the relaxed rest shape, which the
// tile relaxes without the roll (§11.3).
void KnitModel::add_stitch_terms() {
  const KnitPattern& k = *scene_.knit;
  Building<StitchRollTerm> roll;
  Building<StitchLengthTerm> length;
  // Built only where they act (the tile relaxes without the roll, §11.3).
  const bool with_roll = k.roll_stiffness_N > 0.0 && !tile_;
  const bool with_length = k.stitch_length_stiffness_N > 0.0 && scene_.sliding;
  for (const StitchContact& c : graph_.stitches()) {
    // A term that refuses its rest state refuses the scene, located (knit_scene_error.h).
    auto located = [&](const std::function<void()>& add) {
      try {
        add();
      } catch (const std::invalid_argument& e) {
        refuse_knit_scene(scene_, "a knit whose stitches have a non-degenerate rest state (docs/models.md §11.4)",
                          std::string(e.what()) + " at the stitch contact of courses " + std::to_string(c.course) +
                              " and " + std::to_string(c.course + 1) + ", wale " + std::to_string(c.wale) + ", " +
                              (c.side == 0 ? "left" : "right") + (tile_ ? " of the periodic tile" : ""));
      }
    };
    const auto [yh, ka] = visit_of_[c.a][0];
    const bool a_first = graph_.next(yh, ka).k == visit_of_[c.b][0].second;
    const int first = a_first ? c.a : c.b, second = a_first ? c.b : c.a;
    const KnitNode &n0 = graph_.node(first), &n1 = graph_.node(second);
    const int yarns = static_cast<int>(n0.u.size());
    const double rest_length = (n1.x - n0.x).norm();
    for (int slot = 0; slot < yarns && with_length; ++slot) {
      const auto [y, kf] = visit_of_[first][slot];
      const KnitGraph::Step s = graph_.next(y, kf);
      located([&] {
        length.term->add({n0.coord[slot], n1.coord[slot]}, k.stitch_length_stiffness_N, n1.u[slot] + s.du - n0.u[slot]);
      });
      length.add_shift({0.0, s.du});
    }
    // The node after the segment along a yarn of the pair: the first yarn's
    // (x3) and the second's (x5), as seen from the contact (their image shift
    // less the contact's own). A yarn that ends at the contact (the cloth's last
    // wale) leaves no roll there.
    auto after = [&](int slot, Vec3& shift) {
      const auto [y, ks] = visit_of_[second][slot];
      const KnitGraph::Step s = graph_.next(y, ks);
      if (s.k < 0) return -1;
      const auto& visits = graph_.yarns()[y].visits;
      shift = visits[s.k].dx + s.dx - visits[ks].dx;
      return visits[s.k].node;
    };
    for (const StackPair& p : with_roll ? stack_pairs(yarns) : std::vector<StackPair>{}) {
      Vec3 shift3 = Vec3::Zero(), shift5 = Vec3::Zero();
      const int n3 = after(p.i, shift3), n5 = after(p.j, shift5);
      if (n3 < 0 || n5 < 0) continue;
      const int x0 = n0.x_dof, x1 = n1.x_dof, x3 = graph_.node(n3).x_dof, x5 = graph_.node(n5).x_dof;
      Eigen::Matrix<double, 12, 1> rest;  // at the initial state: the relaxed rest shape
      rest << q0_.segment<3>(x0), q0_.segment<3>(x1), q0_.segment<3>(x3) + shift3, q0_.segment<3>(x5) + shift5;
      located([&] {
        roll.term->add({x0, x0 + 1, x0 + 2, x1, x1 + 1, x1 + 2, x3, x3 + 1, x3 + 2, x5, x5 + 1, x5 + 2},
                       k.roll_stiffness_N, rest_length, StitchRollTerm::angle(rest.data()),
                       StitchRollTerm::opening(rest.data()));
      });
      roll.term->tag_last(kRollStiffnessKey, k.roll_stiffness_N);
      roll.add_shift(Vec3::Zero());
      roll.add_shift(Vec3::Zero());
      roll.add_shift(shift3);
      roll.add_shift(shift5);
    }
  }
  if (with_roll) roll.finish(terms_);
  if (with_length) length.finish(terms_);
}

// Contact compression (docs/models.md §11.6), in the tile too, so that the rest
// shape is an equilibrium with it: at every stitch contact (every pair of its
// yarns), and between every
// two yarn pieces that share no node and pass closer than the cutoff in the
// generated geometry.
void KnitModel::add_compression() {
  const double kappa = scene_.knit->compression_stiffness_N_per_m;
  if (!(kappa > 0.0)) return;
  const KnitLayout& L = graph_.layout();
  const double D = 2.0 * scene_.radius_m;
  Building<StitchCompressionTerm> stitch;
  for (const StitchContact& c : graph_.stitches()) {
    // The contacts below and above in the same wale and side; in the tile
    // across its course border as images one period down or up.
    auto row = [&](int r, Vec3& shift) {
      shift.setZero();
      if (!tile_) return r;
      const double period = L.courses * L.course_spacing * L.period_scale[1];
      if (r < 0) shift.y() = -period;
      if (r >= L.courses) shift.y() = period;
      return (r + L.courses) % L.courses;
    };
    Vec3 down, up;
    const int rd = row(c.course - 1, down), ru = row(c.course + 1, up);
    const int nodes[8] = {c.a,
                          c.b,
                          graph_.contact_node(c.course, c.wale, 1 - c.side, 0),
                          graph_.contact_node(c.course, c.wale, 1 - c.side, 1),
                          graph_.contact_node(rd, c.wale, c.side, 0),
                          graph_.contact_node(rd, c.wale, c.side, 1),
                          graph_.contact_node(ru, c.wale, c.side, 0),
                          graph_.contact_node(ru, c.wale, c.side, 1)};
    std::array<int, 24> st{};
    for (int e = 0; e < 8; ++e)
      for (int d = 0; d < 3; ++d) st[3 * e + d] = graph_.node(nodes[e]).x_dof + d;
    // One element per pair of the contact's yarns, at its share of the stack (stack_pairs.h).
    for (const StackPair& p : stack_pairs(static_cast<int>(graph_.node(c.a).u.size()))) {
      stitch.term->add(st, kappa, D, c.side == 0 ? 1 : -1, c.purl ? -1 : 1, p.share);
      stitch.term->tag_last(kCompressionStiffnessKey, kappa);
      for (int e = 0; e < 8; ++e) stitch.add_shift(e >= 6 ? up : e >= 4 ? down : Vec3::Zero());
    }
  }
  stitch.finish(terms_);

  // The pairs are found at the generated period (so that a tile has the same
  // pairs at every period scale, §11.3.1) and act at the tile's period.
  const std::vector<YarnPiece> pieces = yarn_pieces();
  std::vector<YarnPiece> generated = pieces;
  const Vec3 scale(L.period_scale[0], L.period_scale[1], 1.0);
  for (YarnPiece& piece : generated) {
    piece.dx0 = piece.dx0.cwiseQuotient(scale);
    piece.dx1 = piece.dx1.cwiseQuotient(scale);
  }
  std::vector<Vec3> x;
  for (const KnitNode& n : graph_.nodes()) x.push_back(n.x);
  std::vector<Vec3> images{Vec3::Zero()};
  if (tile_) {
    images.clear();
    for (int i = -1; i <= 1; ++i)
      for (int j = -1; j <= 1; ++j)
        images.push_back(Vec3(i * L.wales * L.wale_spacing, j * L.courses * L.course_spacing, 0.0));
  }
  Building<YarnCompressionTerm> pairs;
  for (const PiecePair& p : compression_pairs(x, generated, images, knit_compression_cutoff(L, scene_.radius_m))) {
    const YarnPiece &a = pieces[p.a], &b = pieces[p.b];
    std::array<int, 12> st{};
    const int nodes[4] = {a.n0, a.n1, b.n0, b.n1};
    for (int e = 0; e < 4; ++e)
      for (int d = 0; d < 3; ++d) st[3 * e + d] = graph_.node(nodes[e]).x_dof + d;
    pairs.term->add(st, kappa, D);
    pairs.term->tag_last(kCompressionStiffnessKey, kappa);
    pairs.add_shift(a.dx0);
    pairs.add_shift(a.dx1);
    const Vec3 shift = p.shift.cwiseProduct(scale);
    pairs.add_shift(b.dx0 + shift);
    pairs.add_shift(b.dx1 + shift);
  }
  pairs.finish(terms_);
}

// The yarn pieces: every segment once (compression_pairs.h), with its image shifts in the tile.
std::vector<YarnPiece> KnitModel::yarn_pieces() const {
  std::vector<YarnPiece> all;
  for (const Segment& s : segments_) {
    const auto& visits = graph_.yarns()[s.yarn].visits;
    all.push_back({visits[s.k0].node, visits[s.k1].node, s.dx0, s.dx1});
  }
  return unique_pieces(all);
}

// Yarn–yarn contact (docs/models.md §11.10) between the open cloth's pieces,
// the compression's pairs left out (yarn_contact.h); built whether [self_contact] is on or not,
// for the intersection count, and added to the terms when it is.
void KnitModel::add_yarn_contact() {
  const std::vector<YarnPiece> pieces = yarn_pieces();
  std::vector<Vec3> x;
  for (const KnitNode& n : graph_.nodes()) x.push_back(n.x);
  const double radius = scene_.radius_m;
  const std::vector<PiecePair> compressed =
      compression_pairs(x, pieces, {Vec3::Zero()}, knit_compression_cutoff(graph_.layout(), radius));
  const ObstacleContactRule rule = knit_contact_rule(scene_, graph_, pieces);
  const KnitContactSet set = knit_contact_set(graph_, pieces, compressed, radius);
  capsules_ = std::make_shared<const SelfContactTerm>(set.surface, rule.activation_distance_m, rule.stiffness_N_per_m,
                                                      set.capsules);
  add_self_contact(scene_, rule, radius, set.surface, q0_, terms_, set.capsules);
}

std::vector<int> KnitModel::gauge_dofs() const {
  std::vector<int> held{0, 1, 2};
  for (const KnitYarn& y : graph_.yarns()) {
    const int c = graph_.node(y.visits[0].node).coord[y.visits[0].slot];
    if (is_dof(c)) held.push_back(c);
  }
  return held;
}

double KnitModel::max_node_speed(const Vec& v) const {
  double m = 0.0;
  for (const KnitNode& n : graph_.nodes()) m = std::max(m, v.segment<3>(n.x_dof).norm());
  return m;
}

std::string KnitModel::invalid_state(const Vec& q) const {
  if (!scene_.sliding) return {};
  for (const Segment& s : segments_) {
    const auto& visits = graph_.yarns()[s.yarn].visits;
    const KnitVisit &v0 = visits[s.k0], &v1 = visits[s.k1];
    const double u0 = coordinate(q, graph_.node(v0.node).coord[v0.slot]);
    const double u1 = coordinate(q, graph_.node(v1.node).coord[v1.slot]) + s.du1;
    if (!(std::isfinite(u0) && std::isfinite(u1)) || u1 - u0 > 0.0) continue;
    std::ostringstream why;
    why.precision(17);
    why << "sliding coordinates meet or cross on course " << s.yarn << " between contact nodes " << v0.node << " and "
        << v1.node << ": u = " << u0 << " and " << u1 << " (a segment needs increasing coordinates)";
    return why.str();
  }
  return {};
}

// Points: the contact nodes; cells: every yarn segment as a line (the loops in
// ParaView), with its course and tension k_s(‖w‖ − 1).
Frame KnitModel::frame(double t, const Vec& q, const Vec& v) const {
  Frame f;
  f.time = t;
  const int n = graph_.num_nodes();
  f.points.resize(n, 3);
  DataArray vel{"velocity", 3, {}}, slots{"yarns_through", 1, {}};
  for (int k = 0; k < n; ++k) {
    const KnitNode& node = graph_.node(k);
    f.points.row(k) = q.segment<3>(node.x_dof).transpose();
    for (int c = 0; c < 3; ++c) vel.values.push_back(v[node.x_dof + c]);
    slots.values.push_back(static_cast<double>(node.u.size()));
  }
  CellBlock lines{CellType::line, {}};
  DataArray course{"course", 1, {}}, tension{"segment_tension_N", 1, {}};
  const double area = std::numbers::pi * scene_.radius_m * scene_.radius_m;
  for (const Segment& s : segments_) {
    const auto& visits = graph_.yarns()[s.yarn].visits;
    const KnitVisit &v0 = visits[s.k0], &v1 = visits[s.k1];
    const KnitNode &n0 = graph_.node(v0.node), &n1 = graph_.node(v1.node);
    lines.connectivity.insert(lines.connectivity.end(), {v0.node, v1.node});
    course.values.push_back(s.yarn);
    const double du = coordinate(q, n1.coord[v1.slot]) + s.du1 - coordinate(q, n0.coord[v0.slot]);
    const double stretch = (q.segment<3>(n1.x_dof) + s.dx1 - q.segment<3>(n0.x_dof) - s.dx0).norm() / du;
    const YarnType& type = scene_.yarn_types.at(scene_.warp_yarn_types[s.yarn % scene_.warp_yarn_types.size()]);
    tension.values.push_back(type.stretch_modulus_Pa * area * (stretch - 1.0));
  }
  f.cells = {lines};
  f.point_data = {vel, slots};
  f.cell_data = {course, tension};
  return f;
}

std::map<std::string, std::string> KnitModel::describe() const {
  std::map<std::string, std::string> m;
  const KnitLayout& L = graph_.layout();
  int sliding = 0;
  for (const KnitNode& n : graph_.nodes())
    for (int c : n.coord) sliding += is_dof(c) ? 1 : 0;
  m["model"] = "yarn (knit)";
  m["pattern"] = kKnitKindNames[static_cast<int>(scene_.knit->kind)];
  m["loops"] = std::to_string(L.courses) + " courses x " + std::to_string(L.wales) + " wales";
  m["nodes"] = std::to_string(graph_.num_nodes());
  m["stitch_contacts"] = std::to_string(graph_.stitches().size());
  m["sliding_coordinates"] = std::to_string(sliding);
  m["dofs"] = std::to_string(num_dofs_);
  m["fixed_dofs"] = std::to_string(fixed_.size());
  m["segments"] = std::to_string(segments_.size());
  m["terms"] = term_counts();
  m["matrix_nonzeros"] = std::to_string(pattern().nonZeros());
  if (!tile_) {
    const KnitRestShape& rest = relaxed_tile(scene_);
    std::ostringstream r;
    r << rest.courses << " x " << rest.wales << " tile, residual " << rest.residual_N << " N after " << rest.iterations
      << " Newton steps, period scale " << rest.period_scale[0] << ", " << rest.period_scale[1]
      << (rest.period_relaxed ? " (relaxed)" : " (" + rest.period_note + ")") << ", net force on its period "
      << rest.period_force_N[0] << ", " << rest.period_force_N[1] << " N";
    m["rest_shape"] = r.str();
  }
  return m;
}

}  // namespace wl
