#include "models/mixed/mixed_model.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "models/fem/fem_model.h"
#include "models/fem/terms/nodal_gravity.h"
#include "models/mixed/interface_mass.h"
#include "models/mixed/region_term.h"

namespace wl {
namespace {

// The scene as the mixed model takes it; SceneError naming what stands in the way.
const Scene& checked(const Scene& s) {
  if (!s.mixed.present)
    throw std::invalid_argument(s.source +
                                ": model 'mixed' needs a [mixed] table with yarn_region (docs/models.md §12.1)");
  const int at = s.mixed.line;
  auto line_of = [&](const std::string& key) {
    const auto it = s.key_lines.find(key);
    return it != s.key_lines.end() ? it->second : at;
  };
  const std::string why = " with model 'mixed' (docs/models.md §12.1)";
  if (s.fem.stride != 1)
    throw SceneError(s.source, line_of("fem"), "fem.stride", std::to_string(s.fem.stride),
                     "1" + why + ": the continuum's vertices are the crossings");
  if (!s.fem.mesh_file.empty())
    throw SceneError(s.source, line_of("fem"), "fem.mesh_file", s.fem.mesh_file, "no mesh file" + why);
  if (s.self_contact.enabled)
    throw SceneError(s.source, s.self_contact.line, "self_contact.enabled", "true",
                     "false" + why + ", not carried over yet");
  if (s.exact_contact_jacobian)
    throw SceneError(s.source, line_of("time.exact_contact_jacobian"), "time.exact_contact_jacobian", "true",
                     "false" + why + ", not carried over yet");
  return s;
}

YarnRegion region_of(const Scene& s) { return YarnRegion(s.nodes_u(), s.nodes_v(), s.mixed.yarn_region); }

// The continuum's share of each element of the continuum's terms (docs/models.md §12.3), from the
// crossings its stencil touches: vertex v is crossing (v mod nu, v div nu) on the stride-1 grid mesh.
class ContinuumShares {
 public:
  ContinuumShares(const FemModel& fem, const YarnRegion& region) : region_(region) { set_vertex_mass_shares(fem); }

  double of(const Term& term, int e) const {
    const auto s = term.stencil(e);
    auto vertex = [&](int k) { return s[3 * k] / 3; };
    const std::string name = term.name();
    if (name == "fem-mass" || name == "fem-stretch" || name == "fem-shear" || name == "wind")
      return triangle(vertex(0), vertex(1), vertex(2));
    if (name == "fem-bending")  // a hinge: half of each of its two triangles
      return 0.5 * triangle(vertex(0), vertex(1), vertex(2)) + 0.5 * triangle(vertex(0), vertex(1), vertex(3));
    if (name == "fem-line-bending") return 1.0 - region_.crossing_share(i(vertex(0)), j(vertex(0)));
    if (name == "yarn_damping" || name == "fem-border-stretch") return edge(vertex(0), vertex(1));
    if (name == "fem-gravity") return mass_share_[vertex(0)];
    if (name == "handles") return region_.holds(i(vertex(0)), j(vertex(0))) ? 0.0 : 1.0;
    throw std::logic_error("mixed model: no continuum share for term '" + name + "' (docs/models.md §12.3)");
  }

  // Per vertex: the mass an interface crossing lacks against a quarter of each continuum cell
  // around it (docs/models.md §12.4); 0 off the interface.
  const std::vector<double>& interface_mass() const { return interface_mass_; }
  // Per vertex: the continuum triangles' part of its lumped mass `lumped` (the FEM's), the interface
  // mass added: exactly `lumped` off the region (docs/models.md §12.7).
  std::vector<double> node_mass(const std::vector<double>& lumped) const {
    std::vector<double> m(lumped.size());
    for (size_t k = 0; k < m.size(); ++k) m[k] = mass_share_[k] * lumped[k] + interface_mass_[k];
    return m;
  }
  // A triangle lies in the cell of its smallest i and j.
  double triangle(int a, int b, int c) const {
    return region_.yarn_cell(std::min({i(a), i(b), i(c)}), std::min({j(a), j(b), j(c)})) ? 0.0 : 1.0;
  }

 private:
  int i(int v) const { return v % region_.nu(); }
  int j(int v) const { return v / region_.nu(); }
  double edge(int a, int b) const {
    if (std::abs(i(a) - i(b)) + std::abs(j(a) - j(b)) != 1)
      throw std::logic_error("mixed model: a continuum edge element is not a grid segment");
    if (j(a) == j(b)) return 1.0 - region_.segment_share(std::min(i(a), i(b)), j(a), true);
    return 1.0 - region_.segment_share(i(a), std::min(j(a), j(b)), false);
  }
  // Per vertex: the part of its lumped mass that continuum triangles give it (exactly 1 when all do),
  // and what a quarter of each continuum cell around an interface crossing adds to it.
  void set_vertex_mass_shares(const FemModel& fem) {
    const int nu = region_.nu(), nv = nu * region_.nv();
    std::vector<double> continuum(nv, 0.0), total(nv, 0.0), cell_mass((nu - 1) * (region_.nv() - 1), 0.0);
    for (const auto& term : fem.terms()) {
      if (term->name() != "fem-mass") continue;
      double q[9], v[9], f[9], m[81];
      for (int e = 0; e < term->num_elements(); ++e) {
        fem.gather_local(*term, e, fem.initial_q(), fem.initial_v(), q, v);
        std::fill(f, f + 9, 0.0);
        std::fill(m, m + 81, 0.0);
        term->evaluate(e, q, v, ElementOutput{f, nullptr, nullptr, m});
        const auto s = term->stencil(e);
        const double share = triangle(s[0] / 3, s[3] / 3, s[6] / 3);
        const int cell = std::min({i(s[0] / 3), i(s[3] / 3), i(s[6] / 3)}) +
                         (nu - 1) * std::min({j(s[0] / 3), j(s[3] / 3), j(s[6] / 3)});
        for (int k = 0; k < 3; ++k) {
          total[s[3 * k] / 3] += m[30 * k];  // the diagonal entry (3k, 3k) of the 9×9 block
          continuum[s[3 * k] / 3] += share * m[30 * k];
          cell_mass[cell] += share * m[30 * k];
        }
      }
    }
    mass_share_.resize(nv);
    for (int k = 0; k < nv; ++k) mass_share_[k] = continuum[k] == total[k] ? 1.0 : continuum[k] / total[k];
    interface_mass_.assign(nv, 0.0);
    for (int k = 0; k < nv; ++k) {
      const double yarn = region_.crossing_share(i(k), j(k));
      if (yarn == 0.0 || yarn == 1.0) continue;
      double quarters = 0.0;
      for (int a = i(k) - 1; a <= i(k); ++a)
        for (int b = j(k) - 1; b <= j(k); ++b)
          if (a >= 0 && b >= 0 && a < nu - 1 && b < region_.nv() - 1) quarters += cell_mass[a + (nu - 1) * b] / 4;
      interface_mass_[k] = quarters - continuum[k];
    }
  }

  const YarnRegion& region_;
  std::vector<double> mass_share_, interface_mass_;
};

std::string rectangles_text(const std::vector<std::array<int, 4>>& rectangles) {
  std::string text = "[";
  for (size_t k = 0; k < rectangles.size(); ++k) {
    const auto& r = rectangles[k];
    text += (k ? ", [" : "[") + std::to_string(r[0]) + ", " + std::to_string(r[1]) + ", " + std::to_string(r[2]) +
            ", " + std::to_string(r[3]) + "]";
  }
  return text + "]";
}

// The interface crossings' mass corrections (docs/models.md §12.4) and gravity on them, where the
// continuum's lumping leaves one (round-off differences of a cell's mass on straight sides are not).
void add_interface_mass(const Scene& scene, const FemModel& fem, const WovenGrid& grid,
                        const std::vector<double>& delta, std::vector<std::unique_ptr<Term>>& out) {
  const double rho = fem.material().areal_density_kg_per_m2;
  const double negligible = 1e-12 * rho * scene.spacing_m * scene.spacing_m;
  auto mass = std::make_unique<InterfaceMassTerm>();
  const Vec3 g(scene.gravity_m_per_s2[0], scene.gravity_m_per_s2[1], scene.gravity_m_per_s2[2]);
  bool gravity = false;
  for (const auto& term : fem.terms()) gravity = gravity || term->name() == "fem-gravity";
  auto weight = std::make_unique<NodalGravityTerm>(g);
  for (int v = 0; v < static_cast<int>(delta.size()); ++v) {
    if (std::abs(delta[v]) <= negligible) continue;
    const int x = grid.dofs(v).x;
    mass->add({x, x + 1, x + 2}, delta[v]);
    mass->tag_last(kFemArealDensity, rho);
    weight->add({x, x + 1, x + 2}, delta[v]);
    weight->tag_last(kFemArealDensity, rho);
  }
  if (mass->num_elements() == 0) return;
  out.push_back(std::move(mass));
  if (gravity) out.push_back(std::move(weight));
}

}  // namespace

ContinuumPart continuum_part(const Scene& scene, const YarnRegion& region) {
  Scene without_obstacles = scene;  // the mixed cloth's obstacle contact is over the crossings (§12.7)
  without_obstacles.obstacles.clear();
  const FemModel fem(without_obstacles);
  const WovenGrid grid(scene, region);
  const ContinuumShares shares(fem, region);
  ContinuumPart part;
  part.node_mass = shares.node_mass(fem.vertex_mass());
  for (const auto& t : fem.mesh().triangles) {
    if (shares.triangle(t[0], t[1], t[2]) == 0.0) continue;
    for (int k = 0; k < 3; ++k) part.edges.push_back({std::min(t[k], t[(k + 1) % 3]), std::max(t[k], t[(k + 1) % 3])});
  }
  std::vector<std::unique_ptr<Term>>& out = part.terms;
  for (const auto& term : fem.terms()) {
    std::vector<RegionTerm::Element> elements;
    for (int e = 0; e < term->num_elements(); ++e) {
      const double share = shares.of(*term, e);
      if (share == 0.0) continue;
      std::vector<int> stencil;
      for (int dof : term->stencil(e)) {
        if (!is_dof(dof)) throw std::logic_error("mixed model: a continuum stencil holds a constant");
        stencil.push_back(grid.dofs(dof / 3).x + dof % 3);  // vertex v is crossing v
      }
      elements.push_back({e, share, std::move(stencil)});
    }
    if (!elements.empty()) out.push_back(std::make_unique<RegionTerm>(term->clone(), std::move(elements)));
  }
  add_interface_mass(scene, fem, grid, shares.interface_mass(), out);
  return part;
}

MixedModel::MixedModel(const Scene& scene) : MixedModel(checked(scene), region_of(scene)) {}

MixedModel::MixedModel(const Scene& scene, const YarnRegion& region)
    : YarnModel(scene, region, continuum_part(scene, region)), rectangles_(rectangles_text(scene.mixed.yarn_region)) {
  for (int k = 0; k < grid().num_nodes(); ++k) sliding_ = sliding_ || is_dof(grid().dofs(k).u);
}

Frame MixedModel::frame(double t, const Vec& q, const Vec& v) const {
  Frame f = YarnModel::frame(t, q, v);
  DataArray level{"yarn_level", 1, {}};
  for (int j = 0; j < grid().nv(); ++j)
    for (int i = 0; i < grid().nu(); ++i) level.values.push_back(region().holds(i, j) ? 1.0 : 0.0);
  f.point_data.push_back(std::move(level));
  return f;
}

std::map<std::string, std::string> MixedModel::describe() const {
  std::map<std::string, std::string> m = YarnModel::describe();
  m["model"] = "mixed";
  m["yarn_region"] = rectangles_;
  m["yarn_cells"] = std::to_string(region().yarn_cells()) + " of " +
                    std::to_string((grid().nu() - 1) * (grid().nv() - 1)) + " (the others continuum)";
  return m;
}

}  // namespace wl
