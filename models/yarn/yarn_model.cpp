#include "models/yarn/yarn_model.h"

#include <cmath>
#include <numbers>
#include <sstream>

#include "models/common/handle_spring.h"
#include "models/common/wind.h"
#include "models/scene/parameter_keys.h"
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

// Rest position of node (i, j): upright x = (iL, 0, h − jL) (cloth in the xz
// plane, wind along +y, docs/models.md §2.5); flat x = (iL, jL, h).
static Vec3 rest_position(const Scene& s, int i, int j) {
  const double L = s.spacing_m;
  return s.pose == Scene::Pose::upright ? Vec3(i * L, 0.0, s.height_m - j * L) : Vec3(i * L, j * L, s.height_m);
}

YarnModel::YarnModel(const Scene& scene) : scene_(scene), grid_(scene) {
  const int nu = grid_.nu(), nv = grid_.nv();
  const double L = scene.spacing_m, R = scene.radius_m, area = std::numbers::pi * R * R;
  num_dofs_ = grid_.num_dofs();
  constants_ = grid_.constants();
  q0_ = Vec::Zero(num_dofs_);
  v0_ = Vec::Zero(num_dofs_);
  for (int j = 0; j < nv; ++j)
    for (int i = 0; i < nu; ++i) {
      const NodeDofs& d = grid_.dofs(grid_.node(i, j));
      q0_.segment<3>(d.x) = rest_position(scene, i, j);
      if (is_dof(d.u)) q0_[d.u] = i * L;
      if (is_dof(d.v)) q0_[d.v] = j * L;
    }

  // Per-yarn stiffness: warp j, weft i (k_s = Y·πR², k_b = B·πR², docs/models.md §3.2, §3.3).
  std::vector<double> warp_ks(nv), warp_kb(nv), warp_rho(nv), weft_ks(nu), weft_kb(nu), weft_rho(nu);
  auto warp_name = [&](int j) { return scene.warp_yarn_types[j % scene.warp_yarn_types.size()]; };
  auto weft_name = [&](int i) { return scene.weft_yarn_types[i % scene.weft_yarn_types.size()]; };
  for (int j = 0; j < nv; ++j) {
    const YarnType& y = scene.warp_type(j);
    warp_ks[j] = y.stretch_modulus_Pa * area;
    warp_kb[j] = y.bending_modulus_Pa * area;
    warp_rho[j] = y.density_kg_per_m;
  }
  for (int i = 0; i < nu; ++i) {
    const YarnType& y = scene.weft_type(i);
    weft_ks[i] = y.stretch_modulus_Pa * area;
    weft_kb[i] = y.bending_modulus_Pa * area;
    weft_rho[i] = y.density_kg_per_m;
  }

  for (int j = 0; j < nv; ++j)
    for (int i = 0; i + 1 < nu; ++i)
      segments_.push_back({grid_.node(i, j), grid_.node(i + 1, j), true, warp_ks[j], warp_name(j)});
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j + 1 < nv; ++j)
      segments_.push_back({grid_.node(i, j), grid_.node(i, j + 1), false, weft_ks[i], weft_name(i)});
  auto rho_of = [&](const Segment& s) { return s.warp ? warp_rho[s.a / nu] : weft_rho[s.a % nu]; };
  // Each element is tagged with the scene parameter it is proportional to (docs/models.md §9.1).
  auto type_of = [&](const Segment& s) -> const YarnType& { return scene.yarn_types.at(s.type); };

  const TermSwitches& on = scene.terms;
  const ContactParams& c = scene.contact;
  if (on.inertia) {
    auto t = std::make_unique<SegmentInertiaTerm>();
    for (const Segment& s : segments_) {
      t->add(segment_stencil(s), rho_of(s));
      t->tag_last(yarn_type_key(s.type, kDensityField), type_of(s).density_kg_per_m);
    }
    terms_.push_back(std::move(t));
  }
  if (on.stretch) {
    auto t = std::make_unique<StretchTerm>();
    for (const Segment& s : segments_) {
      t->add(segment_stencil(s), s.ks);
      t->tag_last(yarn_type_key(s.type, kStretchModulusField), type_of(s).stretch_modulus_Pa);
    }
    terms_.push_back(std::move(t));
  }
  const Vec3 g(scene.gravity_m_per_s2[0], scene.gravity_m_per_s2[1], scene.gravity_m_per_s2[2]);
  if (on.gravity && g.norm() > 0) {
    auto t = std::make_unique<GravityTerm>(g);
    for (const Segment& s : segments_) {
      t->add(segment_stencil(s), rho_of(s));
      t->tag_last(yarn_type_key(s.type, kDensityField), type_of(s).density_kg_per_m);
    }
    terms_.push_back(std::move(t));
  }
  if (on.bending) {
    auto t = std::make_unique<BendingTerm>();
    auto add = [&](int n0, int n1, int n2, bool warp, double kb, const std::string& type) {
      const NodeDofs &d0 = grid_.dofs(n0), &d1 = grid_.dofs(n1), &d2 = grid_.dofs(n2);
      const int c1 = warp ? d1.u : d1.v, c2 = warp ? d2.u : d2.v;
      t->add({d0.x, d0.x + 1, d0.x + 2, d1.x, d1.x + 1, d1.x + 2, d2.x, d2.x + 1, d2.x + 2, c1, c2}, kb);
      t->tag_last(yarn_type_key(type, kBendingModulusField), scene.yarn_types.at(type).bending_modulus_Pa);
    };
    for (int j = 0; j < nv; ++j)
      for (int i = 1; i + 1 < nu; ++i)
        add(grid_.node(i, j), grid_.node(i + 1, j), grid_.node(i - 1, j), true, warp_kb[j], warp_name(j));
    for (int i = 0; i < nu; ++i)
      for (int j = 1; j + 1 < nv; ++j)
        add(grid_.node(i, j), grid_.node(i, j + 1), grid_.node(i, j - 1), false, weft_kb[i], weft_name(i));
    terms_.push_back(std::move(t));
  }

  const bool gong_shear = on.shear && c.shear_model == ContactParams::ShearModel::gong;
  const bool friction = on.friction && scene.sliding;
  if (gong_shear || friction) normals_ = std::make_unique<ContactNormals>(grid_, warp_ks, warp_kb, weft_ks, weft_kb, R);
  const std::vector<double>* fn = normals_ ? &normals_->normal_force() : nullptr;

  if (on.shear) {
    // Four quadrants (warp ±, weft ±) at every node that has them (docs/models.md §3.4.4).
    std::unique_ptr<CirioShearTerm> cirio;
    std::unique_ptr<GongShearTerm> gong;
    if (gong_shear) gong = std::make_unique<GongShearTerm>(fn, L, R, c.lock_exponent, c.lock_sigma);
    else cirio = std::make_unique<CirioShearTerm>();
    for (int j = 0; j < nv; ++j)
      for (int i = 0; i < nu; ++i)
        for (int di : {1, -1})
          for (int dj : {1, -1}) {
            const int i1 = i + di, j3 = j + dj;
            if (i1 < 0 || i1 >= nu || j3 < 0 || j3 >= nv) continue;
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
    if (gong) terms_.push_back(std::move(gong));
    else terms_.push_back(std::move(cirio));
  }

  if (on.parallel_contact && scene.sliding) {
    auto t = std::make_unique<ParallelContactTerm>();
    for (const Segment& s : segments_) {
      const NodeDofs &da = grid_.dofs(s.a), &db = grid_.dofs(s.b);
      const int ca = s.warp ? da.u : da.v, cb = s.warp ? db.u : db.v;
      if (!is_dof(ca) && !is_dof(cb)) continue;
      const int sa = grid_.sign(s.a % nu, s.a / nu), sb = grid_.sign(s.b % nu, s.b / nu);
      t->add({ca, cb}, c.parallel_stiffness_N_per_m2 * L, parallel_contact_distance(sa, sb, R));
    }
    terms_.push_back(std::move(t));
  }

  if (friction) {
    auto add_all = [&](auto& term) {
      for (int j = 1; j + 1 < nv; ++j)
        for (int i = 1; i + 1 < nu; ++i) {
          const int n = grid_.node(i, j);
          const NodeDofs& d = grid_.dofs(n);
          term->add(d.u, n, i * L);
          term->add(d.v, n, j * L);
          friction_node_.insert(friction_node_.end(), {n, n});
          friction_axis_.insert(friction_axis_.end(), {0, 1});
        }
    };
    const double mu = c.friction_coefficient, kf = c.friction_stiffness_N_per_m, df = c.friction_damping_Ns_per_m;
    std::unique_ptr<FrictionTerm> t;
    if (c.friction_model == ContactParams::FrictionModel::gong)
      t = std::make_unique<GongFrictionTerm>(fn, mu, kf, df, c.tanh_sharpness_per_m);
    else t = std::make_unique<CirioFrictionTerm>(fn, mu, kf, df, c.tanh_sharpness_per_m);
    add_all(t);
    friction_ = t.get();
    terms_.push_back(std::move(t));
  }

  const Vec3 wind(scene.wind_velocity_m_per_s[0], scene.wind_velocity_m_per_s[1], scene.wind_velocity_m_per_s[2]);
  if (on.wind && (scene.air_density_kg_per_m3 > 0 || scene.wind_drag_Ns_per_m3 > 0)) {
    // Each grid cell split into two triangles along (i,j)–(i+1,j+1) (docs/models.md §3.9).
    auto t = std::make_unique<WindTerm>(wind, scene.air_density_kg_per_m3, scene.wind_drag_Ns_per_m3);
    auto tri = [&](int a, int b, int cc) {
      const int xa = grid_.dofs(a).x, xb = grid_.dofs(b).x, xc = grid_.dofs(cc).x;
      t->add({xa, xa + 1, xa + 2, xb, xb + 1, xb + 2, xc, xc + 1, xc + 2});
    };
    for (int j = 0; j + 1 < nv; ++j)
      for (int i = 0; i + 1 < nu; ++i) {
        const int n00 = grid_.node(i, j), n10 = grid_.node(i + 1, j), n11 = grid_.node(i + 1, j + 1),
                  n01 = grid_.node(i, j + 1);
        tri(n00, n10, n11);
        tri(n00, n11, n01);
      }
    terms_.push_back(std::move(t));
  }

  if (on.handles && !scene.handles.empty()) {
    auto t = std::make_unique<HandleSpringTerm>();
    for (const Handle& h : scene.handles) {
      const int x = grid_.dofs(grid_.node(h.node.i, h.node.j)).x;
      t->add({x, x + 1, x + 2}, q0_.segment<3>(x), h.stiffness_N_per_m);
    }
    terms_.push_back(std::move(t));
  }

  for (const NodeRef& p : scene.pins) {
    const NodeDofs& d = grid_.dofs(grid_.node(p.i, p.j));
    for (int k = 0; k < 3; ++k) fixed_.push_back(d.x + k);
    if (is_dof(d.u)) fixed_.push_back(d.u);
    if (is_dof(d.v)) fixed_.push_back(d.v);
  }
  finalize();
}

std::array<int, 8> YarnModel::segment_stencil(const Segment& s) const {
  const NodeDofs &a = grid_.dofs(s.a), &b = grid_.dofs(s.b);
  return {a.x, a.x + 1, a.x + 2, b.x, b.x + 1, b.x + 2, s.warp ? a.u : a.v, s.warp ? b.u : b.v};
}

void YarnModel::update_auxiliary(double, const Vec& q, const Vec&) {
  if (normals_) normals_->compute(q);
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

Frame YarnModel::frame(double t, const Vec& q, const Vec& v) {
  const int n = grid_.num_nodes(), nu = grid_.nu(), nv = grid_.nv();
  Frame f;
  f.time = t;
  f.points.resize(n, 3);
  DataArray vel{"velocity", 3, {}}, u{"u", 1, {}}, vv{"v", 1, {}}, fn{"F_n", 1, {}}, slide{"sliding", 2, {}};
  if (normals_) normals_->compute(q);
  for (int k = 0; k < n; ++k) {
    const NodeDofs& d = grid_.dofs(k);
    f.points.row(k) = q.segment<3>(d.x).transpose();
    for (int c = 0; c < 3; ++c) vel.values.push_back(v[d.x + c]);
    u.values.push_back(coordinate(q, d.u));
    vv.values.push_back(coordinate(q, d.v));
    fn.values.push_back(normals_ ? normals_->normal_force()[k] : 0.0);
  }
  slide.values.assign(2 * n, 0.0);
  std::vector<double> state;
  if (friction_) state = friction_->sliding_state();
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
  std::ostringstream terms;
  for (const auto& t : terms_)
    terms << (terms.tellp() > 0 ? ", " : "") << t->name() << " (" << t->num_elements() << ")";
  m["terms"] = terms.str();
  m["matrix_nonzeros"] = std::to_string(pattern().nonZeros());
  return m;
}

}  // namespace wl
