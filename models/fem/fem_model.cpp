#include "models/fem/fem_model.h"

#include <algorithm>
#include <cmath>
#include <set>
#include <sstream>

#include "models/common/handle_spring.h"
#include "models/common/self_contact.h"
#include "models/common/wind.h"
#include "models/common/yarn_damper.h"
#include "models/fem/deformation_gradient.h"
#include "models/fem/knit_contact_mesh.h"
#include "models/fem/terms/border_stretch.h"
#include "models/fem/terms/grid_line_bending.h"
#include "models/fem/terms/hinge_bending.h"
#include "models/fem/terms/in_plane_shear.h"
#include "models/fem/terms/lumped_mass.h"
#include "models/fem/terms/nodal_gravity.h"
#include "models/fem/terms/tile_bending.h"
#include "models/fem/terms/tile_membrane.h"
#include "models/fem/terms/warp_weft_stretch.h"
#include "models/fem/tile_law_file.h"

namespace wl {
namespace {

std::array<int, 9> triangle_stencil(const std::array<int, 3>& t) {
  std::array<int, 9> s;
  for (int k = 0; k < 3; ++k)
    for (int c = 0; c < 3; ++c) s[3 * k + c] = 3 * t[k] + c;
  return s;
}

// The tile law's membrane on every triangle, instead of stretch and shear (docs/models.md §6.9).
void add_tile_membrane(std::vector<std::unique_ptr<Term>>& terms, TileMembraneLaw law, const FemMesh& mesh,
                       const std::vector<TriangleRest>& rest) {
  auto t = std::make_unique<TileMembraneTerm>(std::make_shared<const TileMembraneLaw>(std::move(law)));
  for (int e = 0; e < mesh.num_triangles(); ++e) t->add(triangle_stencil(mesh.triangles[e]), rest[e]);
  terms.push_back(std::move(t));
}

// The tile law's curvature part on every triangle, instead of the hinges or grid lines
// (docs/models.md §6.9.1): each triangle with the apexes across its three edges.
void add_tile_bending(std::vector<std::unique_ptr<Term>>& terms, TileBendingLaw law, const FemMesh& mesh,
                      const std::vector<Hinge>& hinges) {
  std::vector<std::array<int, 3>> apex(mesh.num_triangles(), {-1, -1, -1});
  auto edge_of = [&](int t, int from) {  // edge k of triangle t runs from its vertex k
    for (int k = 0; k < 3; ++k)
      if (mesh.triangles[t][k] == from) return k;
    return -1;
  };
  for (const Hinge& h : hinges) {
    apex[h.tri0][edge_of(h.tri0, h.v[0])] = h.v[3];  // tri0 holds v0→v1, the other apex across
    apex[h.tri1][edge_of(h.tri1, h.v[1])] = h.v[2];  // tri1 holds v1→v0
  }
  auto t = std::make_unique<TileBendingTerm>(std::make_shared<const TileBendingLaw>(std::move(law)));
  for (int e = 0; e < mesh.num_triangles(); ++e) {
    const auto& tri = mesh.triangles[e];
    t->add({tri[0], tri[1], tri[2], apex[e][0], apex[e][1], apex[e][2]},
           {mesh.uv[tri[0]], mesh.uv[tri[1]], mesh.uv[tri[2]]});
  }
  terms.push_back(std::move(t));
}

std::string format(double x) {
  std::ostringstream s;
  s.precision(6);
  s << x;
  return s.str();
}

}  // namespace

// m(i, j) = L/2 · (ρ_warp(j)·n_i + ρ_weft(i)·n_j), n_i, n_j the yarn segments at the crossing along
// its warp and its weft (1 on the border, 2 inside): half of each segment's mass, as the yarn
// level's segments lump (docs/models.md §6.6). Index i + wefts·j, the grid mesh's at stride 1.
std::vector<double> yarn_node_masses(const Scene& s) {
  const int nu = s.nodes_u(), nv = s.nodes_v();
  std::vector<double> m(static_cast<size_t>(nu) * nv);
  for (int j = 0; j < nv; ++j)
    for (int i = 0; i < nu; ++i) {
      const int ni = (i > 0) + (i + 1 < nu), nj = (j > 0) + (j + 1 < nv);
      m[i + nu * j] = 0.5 * s.spacing_m * (s.warp_type(j).density_kg_per_m * ni + s.weft_type(i).density_kg_per_m * nj);
    }
  return m;
}

// A knit scene's continuum takes no yarn damper: its coefficient per edge counts the yarns along a
// crossing grid's edges (docs/models.md §3.12); a knit's yarns follow its loops, not the contact
// grid's edges (§11.9). The calibration's static patches (the other constructor) feel no damping.
static const Scene& without_knit_damping(const Scene& s) {
  if (!s.knit || !(s.yarn_viscosity_Pa_s > 0)) return s;
  const auto line = s.key_lines.find("damping.yarn_viscosity_Pa_s");
  throw SceneError(s.source, line != s.key_lines.end() ? line->second : 1, "damping.yarn_viscosity_Pa_s",
                   format(s.yarn_viscosity_Pa_s),
                   "0 for the continuum of a knit (no yarn runs along the contact grid's edges to damp; "
                   "docs/models.md §11.9)");
}

FemModel::FemModel(const Scene& scene)
    // Each argument checks the damping first: its refusal does not depend on the order of evaluation.
    : FemModel(without_knit_damping(scene), make_fem_mesh(without_knit_damping(scene)),
               fem_material(without_knit_damping(scene))) {}

FemModel::FemModel(const Scene& scene, FemMesh mesh, const FemMaterial& material)
    : scene_(scene), mesh_(std::move(mesh)), material_(material) {
  build();
}

void FemModel::build() {
  const int nv = mesh_.num_vertices(), nt = mesh_.num_triangles();
  num_dofs_ = 3 * nv;
  q0_.resize(num_dofs_);
  v0_ = Vec::Zero(num_dofs_);
  for (int i = 0; i < nv; ++i) q0_.segment<3>(3 * i) = mesh_.x[i];
  constants_ = Vec();

  rest_.resize(nt);
  for (int t = 0; t < nt; ++t) {
    const auto& tri = mesh_.triangles[t];
    rest_[t] = triangle_rest(mesh_.uv[tri[0]], mesh_.uv[tri[1]], mesh_.uv[tri[2]]);
    for (int k = 0; k < 3; ++k)
      max_uv_edge_ = std::max(max_uv_edge_, (mesh_.uv[tri[(k + 1) % 3]] - mesh_.uv[tri[k]]).norm());
  }
  hinges_ = interior_hinges(mesh_);

  add_terms(terms_);
  for (const NodeRef& p : scene_.pins) {
    const int v = vertex_of_node(p);
    for (int c = 0; c < 3; ++c) fixed_.push_back(3 * v + c);
  }
  rest_lu_.resize(nt);
  rest_lv_.resize(nt);
  for (int e = 0; e < nt; ++e) {
    const auto s = triangle_stencil(mesh_.triangles[e]);
    double q[9];
    for (int k = 0; k < 9; ++k) q[k] = q0_[s[k]];
    rest_lu_[e] = warp_vector(rest_[e], q).norm();
    rest_lv_[e] = weft_vector(rest_[e], q).norm();
  }
  finalize();
}

// The terms from material_ (docs/models.md §6), in the order the assembly keeps;
// each add_* builds one term when the scene turns it on.
void FemModel::add_terms(std::vector<std::unique_ptr<Term>>& terms) {
  const TermSwitches& on = scene_.terms;
  add_mass(terms);  // always: the FEM has no other inertia
  // A tile law: its membrane holds stretch and shear in one, its curvature part the bending
  // (docs/models.md §6.9).
  const std::string law_path = tile_law_path(scene_.fem);
  const TileLawFile law = law_path.empty() ? TileLawFile{} : read_tile_law_file(law_path);
  if (!law_path.empty() && (on.stretch || on.shear)) add_tile_membrane(terms, TileMembraneLaw(law), mesh_, rest_);
  else {
    if (on.stretch) add_stretch(terms);
    if (on.shear) add_shear(terms);
  }
  if (on.stretch && scene_.fem.border_strip) add_border_stretch(terms);
  if (on.bending && !law_path.empty()) add_tile_bending(terms, TileBendingLaw(law), mesh_, hinges_);
  else if (on.bending && scene_.fem.grid_line_bending) add_grid_line_bending(terms);
  else if (on.bending && !hinges_.empty()) add_hinge_bending(terms);
  if (on.gravity) add_gravity(terms);
  if (on.wind) add_wind(terms);
  if (scene_.yarn_viscosity_Pa_s > 0.0) add_damping(terms);
  if (on.handles && !scene_.handles.empty()) add_handles(terms);
  if (!scene_.obstacles.empty()) add_obstacles(terms);
  if (scene_.self_contact.enabled) add_self_contact(terms);
}

// Mass, lumped (docs/models.md §6.6): ρ_A·A/3 per vertex and triangle, or with
// [fem] yarn_node_mass the total ρ_A·ΣA shared in the proportions of the yarn
// level's node masses, each vertex's share split evenly over its triangles.
// Sets vertex_mass_.
void FemModel::add_mass(std::vector<std::unique_ptr<Term>>& terms) {
  const int nv = mesh_.num_vertices(), nt = mesh_.num_triangles();
  vertex_mass_.assign(nv, 0.0);
  std::vector<double> share;  // yarn_node_mass: each vertex's mass per incident triangle [kg]
  if (scene_.fem.yarn_node_mass) {
    const std::vector<double> yarn = yarn_node_masses(scene_);
    double area = 0, yarn_total = 0;
    for (const TriangleRest& r : rest_) area += r.area;
    for (double m : yarn) yarn_total += m;
    std::vector<int> incident(nv, 0);
    for (const auto& tri : mesh_.triangles)
      for (int v : tri) ++incident[v];
    share.resize(nv);
    for (int v = 0; v < nv; ++v)
      share[v] = material_.areal_density_kg_per_m2 * area * yarn[v] / yarn_total / incident[v];
  }
  auto t = std::make_unique<LumpedMassTerm>();
  for (int e = 0; e < nt; ++e) {
    const auto& tri = mesh_.triangles[e];
    const double third = material_.areal_density_kg_per_m2 * rest_[e].area / 3.0;
    const std::array<double, 3> m = share.empty() ? std::array<double, 3>{third, third, third}
                                                  : std::array<double, 3>{share[tri[0]], share[tri[1]], share[tri[2]]};
    t->add(triangle_stencil(tri), m);
    t->tag_last(kFemArealDensity, material_.areal_density_kg_per_m2);
    for (int k = 0; k < 3; ++k) vertex_mass_[tri[k]] += m[k];
  }
  terms.push_back(std::move(t));
}

// Warp/weft stretch on every triangle (docs/models.md §6.3).
void FemModel::add_stretch(std::vector<std::unique_ptr<Term>>& terms) const {
  auto t = std::make_unique<WarpWeftStretchTerm>(stretch_law(material_));
  for (int e = 0; e < mesh_.num_triangles(); ++e) t->add(triangle_stencil(mesh_.triangles[e]), rest_[e]);
  terms.push_back(std::move(t));
}

// In-plane shear with its lock, or the spline law (docs/models.md §6.4, §6.4.1).
void FemModel::add_shear(std::vector<std::unique_ptr<Term>>& terms) const {
  std::unique_ptr<InPlaneShearTerm> t;
  if (material_.shear_knots_rad.empty()) {
    t = std::make_unique<InPlaneShearTerm>(material_.shear_N_per_m, material_.shear_lock_angle_rad,
                                           material_.shear_lock_exponent);
  } else {  // an absent knot value is k_sh
    std::vector<double> values;
    for (size_t i = 0; i < material_.shear_knots_rad.size(); ++i)
      values.push_back(material_.shear_knot_N_per_m[i] > 0 ? material_.shear_knot_N_per_m[i] : material_.shear_N_per_m);
    t = std::make_unique<InPlaneShearTerm>(material_.shear_N_per_m, material_.shear_lock_angle_rad,
                                           material_.shear_lock_exponent, material_.shear_knots_rad, values);
  }
  for (int e = 0; e < mesh_.num_triangles(); ++e) t->add(triangle_stencil(mesh_.triangles[e]), rest_[e]);
  terms.push_back(std::move(t));
}

// Border edges (one triangle): the outer half spacing of the border yarns (terms/border_stretch.h).
void FemModel::add_border_stretch(std::vector<std::unique_ptr<Term>>& terms) const {
  std::map<std::pair<int, int>, int> count;
  for (const auto& tri : mesh_.triangles)
    for (int k = 0; k < 3; ++k) ++count[std::minmax(tri[k], tri[(k + 1) % 3])];
  auto t = std::make_unique<BorderStretchTerm>(material_.warp_stretch_N_per_m, material_.weft_stretch_N_per_m,
                                               0.5 * scene_.spacing_m);
  for (const auto& [edge, n] : count) {
    if (n != 1) continue;
    const Vec2 d = mesh_.uv[edge.second] - mesh_.uv[edge.first];
    t->add({3 * edge.first, 3 * edge.first + 1, 3 * edge.first + 2, 3 * edge.second, 3 * edge.second + 1,
            3 * edge.second + 2},
           d.norm(), std::abs(d.x()) >= std::abs(d.y()));
  }
  terms.push_back(std::move(t));
}

// Each interior vertex of a grid line bends like a yarn (terms/grid_line_bending.h); a line
// stands for the cloth halfway to its neighbours, so a border line for half a spacing.
void FemModel::add_grid_line_bending(std::vector<std::unique_ptr<Term>>& terms) const {
  const int na = static_cast<int>(mesh_.grid_i.size()), nb = static_cast<int>(mesh_.grid_j.size());
  auto t = std::make_unique<GridLineBendingTerm>();
  auto width = [&](const std::vector<int>& lines, int k) {
    const double prev = k > 0 ? lines[k] - lines[k - 1] : 0,
                 next = k + 1 < (int)lines.size() ? lines[k + 1] - lines[k] : 0;
    return 0.5 * (prev + next) * scene_.spacing_m;
  };
  auto add_line_element = [&](int mid, int next, int prev, double k, double w, const char* key) {
    std::array<int, 9> s;
    for (int c = 0; c < 3; ++c) {
      s[c] = 3 * mid + c;
      s[3 + c] = 3 * next + c;
      s[6 + c] = 3 * prev + c;
    }
    t->add(s, k * w, (mesh_.uv[next] - mesh_.uv[mid]).norm());
    t->tag_last(key, k);
  };
  for (int b = 0; b < nb; ++b)  // warp lines, along u
    for (int a = 1; a + 1 < na; ++a)
      add_line_element(mesh_.grid_vertex(a, b), mesh_.grid_vertex(a + 1, b), mesh_.grid_vertex(a - 1, b),
                       material_.warp_bending_N_m, width(mesh_.grid_j, b), kFemWarpBending);
  for (int a = 0; a < na; ++a)  // weft lines, along v
    for (int b = 1; b + 1 < nb; ++b)
      add_line_element(mesh_.grid_vertex(a, b), mesh_.grid_vertex(a, b + 1), mesh_.grid_vertex(a, b - 1),
                       material_.weft_bending_N_m, width(mesh_.grid_i, a), kFemWeftBending);
  terms.push_back(std::move(t));
}

// Dihedral-angle bending on every interior edge (docs/models.md §6.5).
void FemModel::add_hinge_bending(std::vector<std::unique_ptr<Term>>& terms) const {
  auto t = std::make_unique<HingeBendingTerm>(material_.warp_bending_N_m, material_.weft_bending_N_m,
                                              material_.diagonal_bending_N_m);
  for (const Hinge& h : hinges_) {
    std::array<int, 12> s;
    for (int k = 0; k < 4; ++k)
      for (int c = 0; c < 3; ++c) s[3 * k + c] = 3 * h.v[k] + c;
    t->add(s, mesh_.uv[h.v[1]] - mesh_.uv[h.v[0]], rest_[h.tri0].area + rest_[h.tri1].area);
  }
  terms.push_back(std::move(t));
}

// Gravity on the lumped vertex masses (after add_mass); none for g = 0.
void FemModel::add_gravity(std::vector<std::unique_ptr<Term>>& terms) const {
  const Vec3 g(scene_.gravity_m_per_s2[0], scene_.gravity_m_per_s2[1], scene_.gravity_m_per_s2[2]);
  if (!(g.norm() > 0)) return;
  auto t = std::make_unique<NodalGravityTerm>(g);
  for (int i = 0; i < mesh_.num_vertices(); ++i) {
    t->add({3 * i, 3 * i + 1, 3 * i + 2}, vertex_mass_[i]);
    t->tag_last(kFemArealDensity, material_.areal_density_kg_per_m2);
  }
  terms.push_back(std::move(t));
}

// Wind: the yarn model's term and parameters, on every triangle (docs/models.md §3.9, §6.6);
// none without air density or drag.
void FemModel::add_wind(std::vector<std::unique_ptr<Term>>& terms) const {
  if (!(scene_.air_density_kg_per_m3 > 0 || scene_.wind_drag_Ns_per_m3 > 0)) return;
  const Vec3 wind(scene_.wind_velocity_m_per_s[0], scene_.wind_velocity_m_per_s[1], scene_.wind_velocity_m_per_s[2]);
  auto t = std::make_unique<WindTerm>(wind, scene_.air_density_kg_per_m3, scene_.wind_drag_Ns_per_m3);
  for (const auto& tri : mesh_.triangles) t->add(triangle_stencil(tri));
  terms.push_back(std::move(t));
}

// Yarn-internal stretch damping on the warp and weft edges (docs/models.md §3.12):
// an edge of length kL along the warp carries k yarns of coefficient ηπR²/(kL).
void FemModel::add_damping(std::vector<std::unique_ptr<Term>>& terms) const {
  const double c = yarn_damper_coefficient(scene_.yarn_viscosity_Pa_s, scene_.radius_m, scene_.spacing_m);
  auto t = std::make_unique<YarnDamperTerm>();
  std::set<std::pair<int, int>> edges;
  for (const auto& tri : mesh_.triangles)
    for (int k = 0; k < 3; ++k) {
      const int a = std::min(tri[k], tri[(k + 1) % 3]), b = std::max(tri[k], tri[(k + 1) % 3]);
      const Vec2 d = mesh_.uv[b] - mesh_.uv[a];
      const bool along_yarn = std::abs(d.x()) <= 1e-9 * d.norm() || std::abs(d.y()) <= 1e-9 * d.norm();
      if (along_yarn && edges.insert({a, b}).second)
        t->add({3 * a, 3 * a + 1, 3 * a + 2, 3 * b, 3 * b + 1, 3 * b + 2}, c);
    }
  terms.push_back(std::move(t));
}

// A handle spring at each handle's vertex (models/common/handle_spring.h).
void FemModel::add_handles(std::vector<std::unique_ptr<Term>>& terms) const {
  auto t = std::make_unique<HandleSpringTerm>();
  for (const Handle& h : scene_.handles) {
    const int v = vertex_of_node(h.node);
    t->add({3 * v, 3 * v + 1, 3 * v + 2}, q0_.segment<3>(3 * v), h);
  }
  terms.push_back(std::move(t));
}

// Node–obstacle contact and friction at every vertex, segment–edge contact on
// every triangle edge (docs/models.md §3.11), node spacing stride·L. Sets obstacles_.
void FemModel::add_obstacles(std::vector<std::unique_ptr<Term>>& terms) {
  const int nv = mesh_.num_vertices();
  std::vector<int> node_x;
  for (int i = 0; i < nv; ++i) node_x.push_back(3 * i);
  const double m = *std::max_element(vertex_mass_.begin(), vertex_mass_.end());
  const ObstacleContactRule rule = obstacle_contact_rule(scene_, scene_.fem.stride * scene_.spacing_m, m);
  std::set<std::array<int, 2>> edges;  // the triangles' edges, each once
  for (const auto& t : mesh_.triangles)
    for (int k = 0; k < 3; ++k) edges.insert({std::min(t[k], t[(k + 1) % 3]), std::max(t[k], t[(k + 1) % 3])});
  obstacles_ = ObstacleContact(scene_, rule, node_x, {edges.begin(), edges.end()}, q0_, terms);
}

// Cloth–cloth contact over the mesh's triangles (docs/models.md §3.11.7).
void FemModel::add_self_contact(std::vector<std::unique_ptr<Term>>& terms) const {
  ContactSurface surface{mesh_.triangles, {}};
  for (int i = 0; i < mesh_.num_vertices(); ++i) surface.node_x.push_back(3 * i);
  const double m = *std::max_element(vertex_mass_.begin(), vertex_mass_.end());
  const double l = scene_.fem.stride * scene_.spacing_m;
  wl::add_self_contact(scene_, self_contact_rule(scene_, l, m), l, surface, q0_, terms);
}

void FemModel::set_material(const FemMaterial& material) {
  material_ = material;
  std::vector<std::unique_ptr<Term>> terms;
  add_terms(terms);
  replace_terms(std::move(terms));
}

int FemModel::vertex_of_node(const NodeRef& node) const {
  const Vec2 uv = scene_.knit ? knit_contact_material(knit_contact_grid(scene_), node)
                              : Vec2(node.i * scene_.spacing_m, node.j * scene_.spacing_m);
  const int v = nearest_vertex(mesh_, uv);
  const double d = (mesh_.uv[v] - uv).norm();
  if (mesh_.is_grid() ? d > 1e-9 * scene_.spacing_m : d > max_uv_edge_) {
    std::ostringstream s;
    s << mesh_.source << ": " << (scene_.knit ? "contact" : "crossing") << " (" << node.i << ", " << node.j
      << ") at material (" << uv.x() << ", " << uv.y() << ") m has no vertex: nearest is vertex " << v
      << " at distance " << d << " m"
      << (mesh_.is_grid() ? " (pins and handles must lie on the fem.stride lattice)" : " (outside the mesh)");
    throw std::invalid_argument(s.str());
  }
  return v;
}

bool FemModel::surface_weights(const Vec2& uv, std::array<int, 3>* vertices, Vec3* weights) const {
  for (const auto& tri : mesh_.triangles) {
    const Vec2 a = mesh_.uv[tri[0]], e1 = mesh_.uv[tri[1]] - a, e2 = mesh_.uv[tri[2]] - a, p = uv - a;
    const double det = e1.x() * e2.y() - e1.y() * e2.x();
    const double b1 = (p.x() * e2.y() - p.y() * e2.x()) / det, b2 = (e1.x() * p.y() - e1.y() * p.x()) / det;
    const double tol = 1e-12;
    if (b1 >= -tol && b2 >= -tol && b1 + b2 <= 1 + tol) {
      *vertices = {tri[0], tri[1], tri[2]};
      *weights = Vec3(1 - b1 - b2, b1, b2);
      return true;
    }
  }
  return false;
}

bool FemModel::surface_point(const Vec& q, const Vec2& uv, Vec3* x) const {
  std::array<int, 3> v;
  Vec3 w;
  if (!surface_weights(uv, &v, &w)) return false;
  *x = w[0] * position(q, v[0]) + w[1] * position(q, v[1]) + w[2] * position(q, v[2]);
  return true;
}

std::vector<FaceTension> FemModel::tension_map(const Vec& q) const {
  std::vector<FaceTension> out(mesh_.num_triangles());
  for (int e = 0; e < mesh_.num_triangles(); ++e) {
    const auto& tri = mesh_.triangles[e];
    const TriangleRest r = triangle_rest(mesh_.uv[tri[0]], mesh_.uv[tri[1]], mesh_.uv[tri[2]]);
    double x[9];
    for (int k = 0; k < 3; ++k)
      for (int c = 0; c < 3; ++c) x[3 * k + c] = q[3 * tri[k] + c];
    out[e] = face_tension(warp_vector(r, x), weft_vector(r, x), rest_lu_[e], rest_lv_[e],
                          material_.warp_stretch_N_per_m, material_.weft_stretch_N_per_m);
  }
  return out;
}

Frame FemModel::frame(double t, const Vec& q, const Vec& v) const {
  const int nv = mesh_.num_vertices(), nt = mesh_.num_triangles();
  Frame f;
  f.time = t;
  f.points.resize(nv, 3);
  DataArray vel{"velocity", 3, {}}, uv{"uv", 2, {}};
  for (int i = 0; i < nv; ++i) {
    f.points.row(i) = q.segment<3>(3 * i).transpose();
    for (int c = 0; c < 3; ++c) vel.values.push_back(v[3 * i + c]);
    uv.values.push_back(mesh_.uv[i].x());
    uv.values.push_back(mesh_.uv[i].y());
  }
  CellBlock tris{CellType::triangle, {}};
  for (const auto& tri : mesh_.triangles) tris.connectivity.insert(tris.connectivity.end(), tri.begin(), tri.end());
  f.cells.push_back(std::move(tris));
  DataArray tension{"tension", 1, {}}, lu{"lu", 1, {}}, lv{"lv", 1, {}};
  for (const FaceTension& ft : tension_map(q)) {
    tension.values.push_back(ft.tension);
    lu.values.push_back(ft.lu);
    lv.values.push_back(ft.lv);
  }
  f.point_data = {std::move(vel), std::move(uv)};
  if (!obstacles_.empty()) f.point_data.push_back(obstacles_.force_data(terms_, nv, t, q, v));
  f.cell_data = {std::move(tension), std::move(lu), std::move(lv)};
  (void)nt;
  return f;
}

Frame FemModel::obstacle_frame(double t) const {
  return obstacles_.frame(t, std::max(scene_.warps, scene_.wefts) * scene_.spacing_m);
}

std::map<std::string, std::string> FemModel::describe() const {
  std::map<std::string, std::string> m;
  m["model"] = "fem";
  m["mesh"] = mesh_.is_grid() ? mesh_.source + " " + std::to_string(mesh_.grid_i.size()) + " x " +
                                    std::to_string(mesh_.grid_j.size()) + " vertices (stride " +
                                    std::to_string(scene_.fem.stride) + ")"
                              : mesh_.source;
  m["vertices"] = std::to_string(mesh_.num_vertices());
  m["triangles"] = std::to_string(mesh_.num_triangles());
  m["hinges"] = std::to_string(hinges_.size());
  m["dofs"] = std::to_string(num_dofs_);
  m["fixed_dofs"] = std::to_string(fixed_.size());
  m["terms"] = term_counts();
  m["matrix_nonzeros"] = std::to_string(pattern().nonZeros());
  m["mass"] = scene_.fem.yarn_node_mass ? "lumped in the proportions of the yarn level's node masses"
              : scene_.knit ? "the knit's yarn mass over its contact grid, a third of each triangle's per vertex"
                            : "lumped, a third of each triangle's per vertex";
  const FemMaterial& p = material_;
  m["fem_parameters"] =
      "areal_density_kg_per_m2=" + format(p.areal_density_kg_per_m2) +
      " warp_stretch_N_per_m=" + format(p.warp_stretch_N_per_m) +
      " weft_stretch_N_per_m=" + format(p.weft_stretch_N_per_m) + " shear_N_per_m=" + format(p.shear_N_per_m) +
      " shear_lock_angle_rad=" + format(p.shear_lock_angle_rad) +
      " shear_lock_exponent=" + format(p.shear_lock_exponent) + " warp_bending_N_m=" + format(p.warp_bending_N_m) +
      " weft_bending_N_m=" + format(p.weft_bending_N_m);
  if (p.diagonal_bending_N_m > 0) m["fem_parameters"] += " diagonal_bending_N_m=" + format(p.diagonal_bending_N_m);
  if (const std::string law = tile_law_path(scene_.fem); !law.empty())
    m["tile_law"] = law +
                    " (its membrane instead of the stretch and shear laws, its curvature part per triangle "
                    "instead of the hinges; docs/models.md §6.9)";
  for (const auto& [key, value] : {std::pair{"stretch_coupling_N_per_m", p.stretch_coupling_N_per_m},
                                   std::pair{"warp_stretch_quartic_N_per_m", p.warp_stretch_quartic_N_per_m},
                                   std::pair{"weft_stretch_quartic_N_per_m", p.weft_stretch_quartic_N_per_m},
                                   std::pair{"areal_stretch_quartic_N_per_m", p.areal_stretch_quartic_N_per_m}})
    if (value > 0) m["fem_parameters"] += std::string(" ") + key + "=" + format(value);
  for (size_t i = 0; i < p.shear_knots_rad.size(); ++i)
    m["fem_parameters"] += " " + shear_knot_key(int(i)) + "=" +
                           format(p.shear_knot_N_per_m[i] > 0 ? p.shear_knot_N_per_m[i] : p.shear_N_per_m) + " (at " +
                           format(p.shear_knots_rad[i]) + " rad)";
  return m;
}

}  // namespace wl
