#include "models/yarn/yarn_model.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>
#include <set>
#include <sstream>

#include "models/common/handle_spring.h"
#include "models/common/self_contact.h"
#include "models/common/wind.h"
#include "models/common/yarn_damper.h"
#include "models/scene/parameter_keys.h"
#include "models/yarn/frozen_input_reader.h"
#include "models/yarn/terms/bending.h"
#include "models/yarn/terms/friction_cirio.h"
#include "models/yarn/terms/friction_gong.h"
#include "models/yarn/terms/gravity.h"
#include "models/yarn/terms/parallel_contact.h"
#include "models/yarn/terms/segment_inertia.h"
#include "models/yarn/terms/shear_cirio.h"
#include "models/yarn/terms/shear_gong.h"
#include "models/yarn/terms/stretch.h"

namespace wl {
namespace {

const char* pattern_name(Pattern::Kind k) {
  switch (k) {
    case Pattern::Kind::plain: return "plain";
    case Pattern::Kind::twill: return "twill";
    case Pattern::Kind::satin: return "satin";
  }
  return "?";
}

}  // namespace

YarnModel::YarnModel(const Scene& scene)
    : YarnModel(scene, YarnRegion::everything(scene.nodes_u(), scene.nodes_v()), ContinuumPart{}) {}

YarnModel::YarnModel(const Scene& scene, const YarnRegion& region, ContinuumPart continuum)
    : scene_(scene), region_(region), grid_(scene, region) {
  num_dofs_ = grid_.num_dofs();
  constants_ = grid_.constants();
  set_rest_state();
  set_yarn_constants();
  build_segments();
  const TermSwitches& on = scene.terms;
  const ContactParams& c = scene.contact;
  const bool gong_shear = on.shear && c.shear_model == ContactParams::ShearModel::gong;
  const bool friction = on.friction && scene.sliding;
  const NormalForceStretch normal_force_stretch =
      scene.compat.normal_force_on_centre_lines ? NormalForceStretch::centre_lines : NormalForceStretch::crimped_copies;
  if ((gong_shear || friction) && region_.yarn_cells() > 0) {
    normals_.emplace(grid_, warp_.ks, warp_.kb, weft_.ks, weft_.kb, scene.radius_m, normal_force_stretch,
                     scene.compat.normal_force_bending_at_rest);
    if (!region_.everywhere()) {  // F_n where Gong's shear and friction read it: the region's crossings
      std::vector<char> active(grid_.num_nodes());
      for (int j = 0; j < grid_.nv(); ++j)
        for (int i = 0; i < grid_.nu(); ++i) active[grid_.node(i, j)] = region_.holds(i, j);
      normals_->set_active(std::move(active));
    }
  }
  if (on.inertia) add_inertia();
  if (on.stretch) add_stretch();
  if (on.gravity) add_gravity();
  if (on.bending) add_bending();
  if (on.shear) add_shear();
  if (on.parallel_contact && scene.sliding) add_parallel_contact();
  if (friction) add_friction();
  if (on.wind) add_wind();
  if (on.handles) add_handles();
  if (scene_.yarn_viscosity_Pa_s > 0.0) add_damping();
  add_pins();
  for (auto& term : continuum.terms) terms_.push_back(std::move(term));
  add_obstacles(continuum);
  add_self_contact();
  if (normals_ && scene.exact_contact_jacobian) {
    normals_->compute(q0_);
    normals_->compute_gradient(q0_);  // the structure of ∂F_n/∂q, the same at every state
    chain_.emplace(terms_, *normals_);
    extra_pattern_ = chain_->pattern_entries();
  }
  finalize();
  if (chain_) chain_->bind(pattern());
}

// Rest state: upright x = (iL, 0, h − jL) (cloth in the xz plane, wind along
// +y, docs/models.md §2.5), flat x = (iL, jL, h); u = iL, v = jL; at rest.
void YarnModel::set_rest_state() {
  const double L = scene_.spacing_m;
  q0_ = Vec::Zero(num_dofs_);
  v0_ = Vec::Zero(num_dofs_);
  for (int j = 0; j < grid_.nv(); ++j)
    for (int i = 0; i < grid_.nu(); ++i) {
      const NodeDofs& d = grid_.dofs(grid_.node(i, j));
      q0_.segment<3>(d.x) = scene_.pose == Scene::Pose::upright ? Vec3(i * L, 0.0, scene_.height_m - j * L)
                                                                : Vec3(i * L, j * L, scene_.height_m);
      if (is_dof(d.u)) q0_[d.u] = i * L;
      if (is_dof(d.v)) q0_[d.v] = j * L;
    }
}

// Per-yarn constants: warp j, weft i (k_s = Y·πR², k_b = B·πR², docs/models.md §3.2, §3.3).
void YarnModel::set_yarn_constants() {
  const double area = cross_section();
  auto fill = [&](YarnConstants& yarns, int count, auto type_of) {
    for (int k = 0; k < count; ++k) {
      const YarnType& y = type_of(k);
      yarns.ks.push_back(y.stretch_modulus_Pa * area);
      yarns.kb.push_back(y.bending_modulus_Pa * area);
      yarns.rho.push_back(y.density_kg_per_m);
    }
  };
  fill(warp_, grid_.nv(), [&](int j) -> const YarnType& { return scene_.warp_type(j); });
  fill(weft_, grid_.nu(), [&](int i) -> const YarnType& { return scene_.weft_type(i); });
}

void YarnModel::build_segments() {
  const int nu = grid_.nu(), nv = grid_.nv();
  auto name = [](const std::vector<std::string>& cycle, int k) { return cycle[k % cycle.size()]; };
  for (int j = 0; j < nv; ++j)
    for (int i = 0; i + 1 < nu; ++i)
      segments_.push_back({grid_.node(i, j), grid_.node(i + 1, j), true, region_.segment_share(i, j, true), warp_.ks[j],
                           warp_.rho[j], name(scene_.warp_yarn_types, j)});
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j + 1 < nv; ++j)
      segments_.push_back({grid_.node(i, j), grid_.node(i, j + 1), false, region_.segment_share(i, j, false),
                           weft_.ks[i], weft_.rho[i], name(scene_.weft_yarn_types, i)});
}

// The builders below tag each element with the scene parameter it is
// proportional to (docs/models.md §9.1), and scale it by its yarn share (1 on
// the yarn model; docs/models.md §12.3: f ∝ share·p keeps ∂f/∂p = f/p).

void YarnModel::push_term(std::unique_ptr<Term> term) {
  if (term->num_elements() > 0) terms_.push_back(std::move(term));
}

// Segment inertia, docs/models.md §3.1.
void YarnModel::add_inertia() {
  auto t = std::make_unique<SegmentInertiaTerm>();
  for (const Segment& s : segments_) {
    if (s.share == 0.0) continue;
    t->add(segment_stencil(s), s.share * s.rho);
    t->tag_last(yarn_type_key(s.type, kDensityField), yarn_type(s.type).density_kg_per_m);
  }
  push_term(std::move(t));
}

// Stretch, docs/models.md §3.2.
void YarnModel::add_stretch() {
  auto t = std::make_unique<StretchTerm>();
  t->set_projected_step_stiffness(scene_.terms.stretch_projected_step_hessian);
  for (const Segment& s : segments_) {
    if (s.share == 0.0) continue;
    t->add(segment_stencil(s), s.share * s.ks);
    t->tag_last(yarn_type_key(s.type, kStretchModulusField), yarn_type(s.type).stretch_modulus_Pa);
  }
  push_term(std::move(t));
}

// Gravity on the segment mass, docs/models.md §3.8.
void YarnModel::add_gravity() {
  const Vec3 g(scene_.gravity_m_per_s2[0], scene_.gravity_m_per_s2[1], scene_.gravity_m_per_s2[2]);
  if (g.norm() == 0.0) return;
  auto t = std::make_unique<GravityTerm>(g);
  for (const Segment& s : segments_) {
    if (s.share == 0.0) continue;
    t->add(segment_stencil(s), s.share * s.rho);
    t->tag_last(yarn_type_key(s.type, kDensityField), yarn_type(s.type).density_kg_per_m);
  }
  push_term(std::move(t));
}

// Bending over three consecutive crossings of a yarn, docs/models.md §3.3.
void YarnModel::add_bending() {
  const int nu = grid_.nu(), nv = grid_.nv();
  auto t = std::make_unique<BendingTerm>(scene_.compat.bending_sliding_theta);
  auto add = [&](int n0, int n1, int n2, bool warp, double kb, const std::string& type) {
    const double share = region_.crossing_share(n0 % nu, n0 / nu);
    if (share == 0.0) return;
    const NodeDofs &d0 = grid_.dofs(n0), &d1 = grid_.dofs(n1), &d2 = grid_.dofs(n2);
    const int c1 = warp ? d1.u : d1.v, c2 = warp ? d2.u : d2.v;
    t->add({d0.x, d0.x + 1, d0.x + 2, d1.x, d1.x + 1, d1.x + 2, d2.x, d2.x + 1, d2.x + 2, c1, c2}, share * kb);
    t->tag_last(yarn_type_key(type, kBendingModulusField), yarn_type(type).bending_modulus_Pa);
  };
  auto name = [](const std::vector<std::string>& cycle, int k) { return cycle[k % cycle.size()]; };
  for (int j = 0; j < nv; ++j)
    for (int i = 1; i + 1 < nu; ++i)
      add(grid_.node(i, j), grid_.node(i + 1, j), grid_.node(i - 1, j), true, warp_.kb[j],
          name(scene_.warp_yarn_types, j));
  for (int i = 0; i < nu; ++i)
    for (int j = 1; j + 1 < nv; ++j)
      add(grid_.node(i, j), grid_.node(i, j + 1), grid_.node(i, j - 1), false, weft_.kb[i],
          name(scene_.weft_yarn_types, i));
  push_term(std::move(t));
}

// Shear: four quadrants (warp ±, weft ±) at every node that has them,
// Cirio's law or Gong's with lock (docs/models.md §3.4.4).
void YarnModel::add_shear() {
  const int nu = grid_.nu(), nv = grid_.nv();
  const ContactParams& c = scene_.contact;
  const double L = scene_.spacing_m, area = cross_section();
  std::unique_ptr<CirioShearTerm> cirio;
  std::unique_ptr<GongShearTerm> gong;
  if (c.shear_model == ContactParams::ShearModel::gong)
    gong = std::make_unique<GongShearTerm>(
        L, scene_.radius_m, c.lock_exponent, c.lock_sigma,
        GongShearTerm::Published{scene_.compat.shear_lock_actual_angle, scene_.compat.shear_lock_published_derivative});
  else cirio = std::make_unique<CirioShearTerm>();
  for (int j = 0; j < nv; ++j)
    for (int i = 0; i < nu; ++i)
      for (int di : {1, -1})
        for (int dj : {1, -1}) {
          const int i1 = i + di, j3 = j + dj;
          if (i1 < 0 || i1 >= nu || j3 < 0 || j3 >= nv) continue;
          const bool ring = i == 0 || j == 0 || i == nu - 1 || j == nv - 1;
          if (ring && scene_.compat.shear_interior_only) continue;             // docs/published_code.md row 23
          if (!region_.yarn_cell(std::min(i, i1), std::min(j, j3))) continue;  // the quadrant's cell
          const int n0 = grid_.node(i, j);
          const int x0 = grid_.dofs(n0).x, x1 = grid_.dofs(grid_.node(i1, j)).x, x3 = grid_.dofs(grid_.node(i, j3)).x;
          const std::array<int, 9> st{x0, x0 + 1, x0 + 2, x1, x1 + 1, x1 + 2, x3, x3 + 1, x3 + 2};
          if (gong) {
            // Lock only where the warp and the weft interlace (docs/models.md §3.4.4).
            const bool lock = grid_.sign(i, j) != grid_.sign(i1, j) && grid_.sign(i, j) != grid_.sign(i, j3);
            gong->add(st, n0, c.shear_modulus_Pa * area, lock);
            gong->tag_last(kShearModulusKey, c.shear_modulus_Pa);
          } else {
            cirio->add(st, c.shear_modulus_Pa * area * L);
            cirio->tag_last(kShearModulusKey, c.shear_modulus_Pa);
          }
        }
  if (gong) push_term(std::move(gong));
  else push_term(std::move(cirio));
}

// Contact of parallel yarns on the sliding coordinates, docs/models.md §3.5.
void YarnModel::add_parallel_contact() {
  const int nu = grid_.nu();
  const double k = scene_.contact.parallel_stiffness_N_per_m2 * scene_.spacing_m;
  // The published code's force is the negative of the penalty's gradient (docs/published_code.md row 12).
  auto t = std::make_unique<ParallelContactTerm>(scene_.compat.parallel_contact_attractive ? -1.0 : 1.0);
  for (const Segment& s : segments_) {
    const NodeDofs &da = grid_.dofs(s.a), &db = grid_.dofs(s.b);
    const int ca = s.warp ? da.u : da.v, cb = s.warp ? db.u : db.v;
    if (!is_dof(ca) && !is_dof(cb)) continue;
    const int sa = grid_.sign(s.a % nu, s.a / nu), sb = grid_.sign(s.b % nu, s.b / nu);
    t->add({ca, cb}, k, parallel_contact_distance(sa, sb, scene_.radius_m));
  }
  push_term(std::move(t));
}

// Sliding friction on u and v of every inner crossing, Gong's or Cirio's law
// (docs/models.md §3.7).
void YarnModel::add_friction() {
  const ContactParams& c = scene_.contact;
  const double L = scene_.spacing_m, mu = c.friction_coefficient, kf = c.friction_stiffness_N_per_m,
               df = c.friction_damping_Ns_per_m;
  std::unique_ptr<FrictionTerm> t;
  if (c.friction_model == ContactParams::FrictionModel::gong)
    t = std::make_unique<GongFrictionTerm>(mu, kf, df, c.tanh_sharpness_per_m);
  else t = std::make_unique<CirioFrictionTerm>(mu, kf, df, c.tanh_sharpness_per_m);
  for (int j = 1; j + 1 < grid_.nv(); ++j)
    for (int i = 1; i + 1 < grid_.nu(); ++i) {
      const int n = grid_.node(i, j);
      const NodeDofs& d = grid_.dofs(n);
      if (!is_dof(d.u)) continue;  // a mixed cloth's crossing outside the region's interior
      t->add(d.u, n, i * L);
      t->add(d.v, n, j * L);
      friction_node_.insert(friction_node_.end(), {n, n});
      friction_axis_.insert(friction_axis_.end(), {0, 1});
    }
  if (t->num_elements() == 0) return;
  friction_term_ = static_cast<int>(terms_.size());
  terms_.push_back(std::move(t));
}

// Wind drag on the cloth surface: each grid cell split into two triangles along
// (i,j)–(i+1,j+1) (docs/models.md §3.9).
void YarnModel::add_wind() {
  if (!(scene_.air_density_kg_per_m3 > 0 || scene_.wind_drag_Ns_per_m3 > 0)) return;
  const Vec3 wind(scene_.wind_velocity_m_per_s[0], scene_.wind_velocity_m_per_s[1], scene_.wind_velocity_m_per_s[2]);
  auto t = std::make_unique<WindTerm>(wind, scene_.air_density_kg_per_m3, scene_.wind_drag_Ns_per_m3);
  auto tri = [&](int a, int b, int cc) {
    const int xa = grid_.dofs(a).x, xb = grid_.dofs(b).x, xc = grid_.dofs(cc).x;
    t->add({xa, xa + 1, xa + 2, xb, xb + 1, xb + 2, xc, xc + 1, xc + 2});
  };
  for (int j = 0; j + 1 < grid_.nv(); ++j)
    for (int i = 0; i + 1 < grid_.nu(); ++i) {
      if (!region_.yarn_cell(i, j)) continue;
      const int n00 = grid_.node(i, j), n10 = grid_.node(i + 1, j), n11 = grid_.node(i + 1, j + 1),
                n01 = grid_.node(i, j + 1);
      // docs/models.md §3.9; the published code alternates the diagonal (docs/published_code.md row 13).
      if (scene_.compat.wind_alternating_diagonals && (i + j) % 2 == 1) {
        tri(n00, n10, n01);
        tri(n10, n11, n01);
      } else {
        tri(n00, n10, n11);
        tri(n00, n11, n01);
      }
    }
  push_term(std::move(t));
}

// Yarn-internal stretch damping on every warp and weft segment (docs/models.md §3.12).
void YarnModel::add_damping() {
  const double c = yarn_damper_coefficient(scene_.yarn_viscosity_Pa_s, scene_.radius_m, scene_.spacing_m);
  auto t = std::make_unique<YarnDamperTerm>();
  auto segment = [&](int a, int b, double share) {
    if (share == 0.0) return;
    const int xa = grid_.dofs(a).x, xb = grid_.dofs(b).x;
    t->add({xa, xa + 1, xa + 2, xb, xb + 1, xb + 2}, share * c);
  };
  for (int j = 0; j < grid_.nv(); ++j)
    for (int i = 0; i < grid_.nu(); ++i) {
      if (i + 1 < grid_.nu()) segment(grid_.node(i, j), grid_.node(i + 1, j), region_.segment_share(i, j, true));
      if (j + 1 < grid_.nv()) segment(grid_.node(i, j), grid_.node(i, j + 1), region_.segment_share(i, j, false));
    }
  push_term(std::move(t));
}

// Handles: a spring from the node to its target, which starts at the rest position (docs/models.md §3.10).
void YarnModel::add_handles() {
  if (scene_.handles.empty()) return;
  auto t = std::make_unique<HandleSpringTerm>();
  for (const Handle& h : scene_.handles) {
    if (!region_.holds(h.node.i, h.node.j)) continue;  // the continuum's (docs/models.md §12.3)
    const int x = grid_.dofs(grid_.node(h.node.i, h.node.j)).x;
    t->add({x, x + 1, x + 2}, q0_.segment<3>(x), h);
  }
  push_term(std::move(t));
}

// Pins hold every DoF of their node, sliding coordinates included.
void YarnModel::add_pins() {
  for (const NodeRef& p : scene_.pins) {
    const NodeDofs& d = grid_.dofs(grid_.node(p.i, p.j));
    for (int k = 0; k < 3; ++k) fixed_.push_back(d.x + k);
    if (is_dof(d.u)) fixed_.push_back(d.u);
    if (is_dof(d.v)) fixed_.push_back(d.v);
  }
}

// Node–obstacle contact and friction at every crossing, segment–edge contact on
// every yarn segment of the yarn level and every edge of the continuum's triangles
// (docs/models.md §3.11, §12.7): node spacing L; κ from the heaviest crossing, a
// crossing weighing at most its yarn share of (2 max ρ)·L plus what the continuum lumps on it.
void YarnModel::add_obstacles(const ContinuumPart& continuum) {
  if (scene_.obstacles.empty()) return;
  double rho = 0.0;
  for (const auto& [name, y] : scene_.yarn_types) rho = std::max(rho, y.density_kg_per_m);
  const double L = scene_.spacing_m, crossing_mass = 2.0 * rho * L;
  std::vector<int> node_x(grid_.num_nodes());
  double heaviest = 0.0;
  std::set<std::array<int, 2>> segments(continuum.edges.begin(), continuum.edges.end());  // each once, ordered
  for (int j = 0; j < grid_.nv(); ++j)
    for (int i = 0; i < grid_.nu(); ++i) {
      const int k = grid_.node(i, j);
      node_x[k] = grid_.dofs(k).x;
      const double lumped = continuum.node_mass.empty() ? 0.0 : continuum.node_mass[k];
      heaviest = std::max(heaviest, region_.crossing_share(i, j) * crossing_mass + lumped);
      if (i + 1 < grid_.nu() && region_.segment_share(i, j, true) > 0.0) segments.insert({k, grid_.node(i + 1, j)});
      if (j + 1 < grid_.nv() && region_.segment_share(i, j, false) > 0.0) segments.insert({k, grid_.node(i, j + 1)});
    }
  obstacles_ = ObstacleContact(scene_, obstacle_contact_rule(scene_, L, heaviest), node_x,
                               {segments.begin(), segments.end()}, q0_, terms_);
}

// Cloth–cloth contact over the crossing grid, each cell split along
// (i,j)–(i+1,j+1) as the intersection count splits it (docs/models.md §3.11.7).
void YarnModel::add_self_contact() {
  if (!scene_.self_contact.enabled) return;
  ContactSurface surface;
  for (int k = 0; k < grid_.num_nodes(); ++k) surface.node_x.push_back(grid_.dofs(k).x);
  for (int j = 0; j + 1 < grid_.nv(); ++j)
    for (int i = 0; i + 1 < grid_.nu(); ++i) {
      const int n00 = grid_.node(i, j), n10 = grid_.node(i + 1, j), n11 = grid_.node(i + 1, j + 1),
                n01 = grid_.node(i, j + 1);
      surface.triangles.push_back({n00, n10, n11});
      surface.triangles.push_back({n00, n11, n01});
    }
  double rho = 0.0;
  for (const auto& [name, y] : scene_.yarn_types) rho = std::max(rho, y.density_kg_per_m);
  const double L = scene_.spacing_m;
  wl::add_self_contact(scene_, self_contact_rule(scene_, L, 2.0 * rho * L), L, surface, q0_, terms_);
}

Frame YarnModel::obstacle_frame(double t) const {
  return obstacles_.frame(t, std::max(grid_.nu(), grid_.nv()) * scene_.spacing_m);
}

double YarnModel::cross_section() const { return std::numbers::pi * scene_.radius_m * scene_.radius_m; }

std::array<int, 8> YarnModel::segment_stencil(const Segment& s) const {
  const NodeDofs &a = grid_.dofs(s.a), &b = grid_.dofs(s.b);
  return {a.x, a.x + 1, a.x + 2, b.x, b.x + 1, b.x + 2, s.warp ? a.u : a.v, s.warp ? b.u : b.v};
}

void YarnModel::prepare_auxiliary(double, const Vec& q, const Vec&, EvalContext& ctx) {
  if (!normals_) return;
  normals_->compute(q);
  if (chain_) normals_->compute_gradient(q);
  ctx.normal_force = normals_->normal_force();
}

void YarnModel::after_stage(int stage, const Vec& q, const Vec& v, const AssemblyRequest& req, Evaluation& out) {
  if (!chain_) return;
  if (stage == 0) chain_->keep_stage0_rows(req, out);
  else chain_->add_jacobians(*this, q, v, *normals_, req, out);
}

// ∂F_n/∂p from the parts of F_n proportional to each yarn's k_s (∝ Y) and k_b
// (∝ B), docs/models.md §3.6.1.
std::vector<double> YarnModel::normal_force_parameter_derivative(const std::string& key) const {
  auto per_unit = [&](const std::string& type, const char* field, double value) {
    return value > 0.0 && yarn_type_key(type, field) == key ? 1.0 / value : 0.0;
  };
  auto cycled = [](const std::vector<std::string>& cycle, int k) { return cycle[k % cycle.size()]; };
  const auto& parts = normals_->stiffness_parts();
  std::vector<double> dfn_dp(grid_.num_nodes(), 0.0);
  for (int j = 0; j < grid_.nv(); ++j)
    for (int i = 0; i < grid_.nu(); ++i) {
      const int id = grid_.node(i, j);
      const std::string warp = cycled(scene_.warp_yarn_types, j), weft = cycled(scene_.weft_yarn_types, i);
      const YarnType &yw = yarn_type(warp), &yf = yarn_type(weft);
      dfn_dp[id] = parts[id].warp_stretch * per_unit(warp, kStretchModulusField, yw.stretch_modulus_Pa) +
                   parts[id].warp_bending * per_unit(warp, kBendingModulusField, yw.bending_modulus_Pa) +
                   parts[id].weft_stretch * per_unit(weft, kStretchModulusField, yf.stretch_modulus_Pa) +
                   parts[id].weft_bending * per_unit(weft, kBendingModulusField, yf.bending_modulus_Pa);
    }
  return dfn_dp;
}

// The terms' ∂f/∂p, with exact_contact_jacobian what passes through F_n and
// F_u (docs/models.md §3.6.1), and what passes through the anchors' dū/dp
// (∂F/∂ū = −∂F/∂u, docs/models.md §9.2).
bool YarnModel::force_parameter_derivative(const std::string& key, double t, const Vec& q, const Vec& v,
                                           Vec& dfdp) const {
  bool any = TermModel::force_parameter_derivative(key, t, q, v, dfdp);
  if (chain_)
    any = chain_->add_parameter_derivative(*this, key, q, v, normal_force_parameter_derivative(key), dfdp) || any;
  const auto k = std::find(anchor_keys_.begin(), anchor_keys_.end(), key);
  if (friction_term_ < 0 || k == anchor_keys_.end()) return any;
  const Term& friction = *terms_[friction_term_];
  for (int e = 0; e < friction.num_elements(); ++e) {
    const double du_dp = anchor_dp_(e, k - anchor_keys_.begin());
    const int dof = friction.stencil(e)[0];
    if (du_dp == 0.0 || !is_dof(dof)) continue;
    double lq = 0.0, lv = 0.0, f = 0.0, dfdu = 0.0;
    gather_local(friction, e, q, v, &lq, &lv);
    friction.evaluate(e, &lq, &lv, ElementOutput{&f, &dfdu});
    dfdp[dof] -= dfdu * du_dp;
    any = true;
  }
  return any;
}

std::vector<std::string> YarnModel::asymmetric_terms() const {
  std::vector<std::string> names = TermModel::asymmetric_terms();
  if (!chain_) return names;
  for (const auto& term : terms_)
    if (const FrozenInputReader* reader = frozen_input_reader(*term);
        reader && term->num_elements() > 0 && reader->normal_force_node(0) >= 0 &&
        std::find(names.begin(), names.end(), term->name()) == names.end())
      names.push_back(term->name());
  return names;
}

void YarnModel::accept_step_sensitivities(const std::vector<std::string>& keys, const Vec& q, const Vec& v,
                                          const Eigen::MatrixXd& dq_dp, const Eigen::MatrixXd& dv_dp, double h) {
  if (friction_term_ < 0) return;
  const auto* gong = dynamic_cast<const GongFrictionTerm*>(terms_[friction_term_].get());
  if (!gong) return;  // Cirio's return mapping: not carried (docs/models.md §9.2)
  const int ne = gong->num_elements();
  if (anchor_keys_ != keys || anchor_dp_.rows() != ne) {
    anchor_keys_ = keys;
    anchor_dp_ = Eigen::MatrixXd::Zero(ne, static_cast<Eigen::Index>(keys.size()));
  }
  const auto& grad = normals_->gradient();
  Vec dfdp;
  for (size_t k = 0; k < keys.size(); ++k) {
    const Vec sq = dq_dp.col(static_cast<Eigen::Index>(k)), sv = dv_dp.col(static_cast<Eigen::Index>(k));
    std::vector<double> dfn_dp;
    if (chain_) {
      TermModel::force_parameter_derivative(keys[k], 0.0, q, v, dfdp);
      dfn_dp = normal_force_parameter_derivative(keys[k]);
    }
    const bool is_mu = keys[k] == kFrictionCoefficientKey;
    for (int e = 0; e < ne; ++e) {
      const int dof = gong->stencil(e)[0];
      if (!is_dof(dof)) continue;
      const GongFrictionTerm::AnchorRate r = gong->anchor_rate(e);
      double dsigma = is_mu ? r.d_mu : 0.0;
      if (chain_) {
        const int node = friction_node_[e];
        double dfn = dfn_dp[node];
        for (size_t c = 0; c < grad[node].dof.size(); ++c) dfn += grad[node].value[c] * sq[grad[node].dof[c]];
        const double dfu = chain_->tangential_directional(friction_term_, e, sq, sv) +
                           chain_->tangential_parameter_derivative(*this, friction_term_, e, keys[k], q, v, dfdp);
        dsigma += r.d_Fu * dfu + r.d_Fn * dfn;
      }
      anchor_dp_(e, static_cast<Eigen::Index>(k)) += h * (dsigma * v[dof] + r.sigma * sv[dof]);
    }
  }
}

Vec3 YarnModel::position(const Vec& q, int i, int j) const { return q.segment<3>(grid_.dofs(grid_.node(i, j)).x); }

double YarnModel::max_node_speed(const Vec& v) const {
  double m = 0.0;
  for (int k = 0; k < grid_.num_nodes(); ++k) m = std::max(m, v.segment<3>(grid_.dofs(k).x).norm());
  return m;
}

std::string YarnModel::invalid_state(const Vec& q) const {
  if (!scene_.sliding) return {};
  const int nu = grid_.nu();
  for (const Segment& s : segments_) {
    const NodeDofs &a = grid_.dofs(s.a), &b = grid_.dofs(s.b);
    const double ca = coordinate(q, s.warp ? a.u : a.v), cb = coordinate(q, s.warp ? b.u : b.v);
    if (!(std::isfinite(ca) && std::isfinite(cb)) || cb - ca > 0.0) continue;
    std::ostringstream why;
    why.precision(17);
    why << "sliding coordinates meet or cross on " << (s.warp ? "warp " : "weft ") << (s.warp ? s.a / nu : s.a % nu)
        << " between crossings (" << s.a % nu << ", " << s.a / nu << ") and (" << s.b % nu << ", " << s.b / nu
        << "): " << (s.warp ? "u" : "v") << " = " << ca << " and " << cb << " (a segment needs increasing coordinates)";
    return why.str();
  }
  return {};
}

double YarnModel::coordinate(const Vec& q, int index) const {
  return is_dof(index) ? q[index] : constants_[constant_slot(index)];
}

Frame YarnModel::frame(double t, const Vec& q, const Vec& v) const {
  const int n = grid_.num_nodes(), nu = grid_.nu(), nv = grid_.nv();
  Frame f;
  f.time = t;
  f.points.resize(n, 3);
  DataArray vel{"velocity", 3, {}}, u{"u", 1, {}}, vv{"v", 1, {}}, fn{"F_n", 1, {}}, slide{"sliding", 2, {}};
  std::optional<ContactNormals> normals = normals_;  // F_n at q, leaving the evaluation's own untouched
  if (normals) normals->compute(q);
  for (int k = 0; k < n; ++k) {
    const NodeDofs& d = grid_.dofs(k);
    f.points.row(k) = q.segment<3>(d.x).transpose();
    for (int c = 0; c < 3; ++c) vel.values.push_back(v[d.x + c]);
    u.values.push_back(coordinate(q, d.u));
    vv.values.push_back(coordinate(q, d.v));
    fn.values.push_back(normals ? normals->normal_force()[k] : 0.0);
  }
  slide.values.assign(2 * n, 0.0);
  std::vector<double> state;
  if (friction_term_ >= 0) state = static_cast<const FrictionTerm&>(*terms_[friction_term_]).sliding_state();
  for (size_t e = 0; e < state.size(); ++e) slide.values[2 * friction_node_[e] + friction_axis_[e]] = state[e];

  CellBlock lines{CellType::line, {}}, quads{CellType::quad, {}};
  DataArray tension{"segment_tension_N", 1, {}};
  for (const Segment& s : segments_) {
    lines.connectivity.insert(lines.connectivity.end(), {s.a, s.b});
    const NodeDofs &a = grid_.dofs(s.a), &b = grid_.dofs(s.b);
    const double du = std::abs(coordinate(q, s.warp ? b.u : b.v) - coordinate(q, s.warp ? a.u : a.v));
    const double stretch = (q.segment<3>(b.x) - q.segment<3>(a.x)).norm() / du;
    tension.values.push_back(s.ks * (stretch - 1.0));  // k_s(‖w‖−1), docs/models.md §3.2
  }
  for (int j = 0; j + 1 < nv; ++j)
    for (int i = 0; i + 1 < nu; ++i) {
      quads.connectivity.insert(quads.connectivity.end(), {grid_.node(i, j), grid_.node(i + 1, j),
                                                           grid_.node(i + 1, j + 1), grid_.node(i, j + 1)});
      tension.values.push_back(0.0);  // surface cells carry no segment tension
    }
  f.cells = {lines, quads};
  f.point_data = {vel, u, vv, fn, slide};
  if (!obstacles_.empty()) f.point_data.push_back(obstacles_.force_data(terms_, n, t, q, v));
  f.cell_data = {tension};
  return f;
}

std::map<std::string, std::string> YarnModel::describe() const {
  std::map<std::string, std::string> m;
  int sliding = 0;
  for (int k = 0; k < grid_.num_nodes(); ++k) sliding += is_dof(grid_.dofs(k).u) ? 1 : 0;
  m["model"] = "yarn";
  m["grid"] = std::to_string(grid_.nu()) + " x " + std::to_string(grid_.nv()) + " nodes";
  m["nodes"] = std::to_string(grid_.num_nodes());
  m["sliding_nodes"] = std::to_string(sliding);
  m["dofs"] = std::to_string(num_dofs_);
  m["fixed_dofs"] = std::to_string(fixed_.size());
  m["pattern"] = pattern_name(scene_.pattern.kind);
  m["segments"] = std::to_string(segments_.size());
  m["terms"] = term_counts();
  m["matrix_nonzeros"] = std::to_string(pattern().nonZeros());
  return m;
}

}  // namespace wl
