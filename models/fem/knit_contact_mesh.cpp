#include "models/fem/knit_contact_mesh.h"

#include "models/knit/knit_model.h"

namespace wl {

KnitContactGrid knit_contact_grid(const KnitLayout& l) {
  return {l.courses, l.wales, l.wale_spacing, l.course_spacing};
}

KnitContactGrid knit_contact_grid(const Scene& s) { return knit_contact_grid(knit_layout(s, false)); }

std::vector<KnitGridContact> knit_grid_contacts(const KnitGraph& graph) {
  const KnitContactGrid g = knit_contact_grid(graph.layout());
  std::vector<KnitGridContact> out;
  for (int row = 0; row < g.rows(); ++row)
    for (int column = 0; column < g.columns(); ++column)
      out.push_back({graph.contact_node(row - 1, column / 2, column % 2, 0),
                     graph.contact_node(row - 1, column / 2, column % 2, 1), g.material(column, row)});
  return out;
}

std::vector<KnitGridContact> knit_grid_contacts(const Scene& s) {
  return knit_grid_contacts(KnitGraph(knit_layout(s, false)));
}

namespace {

bool divides_grid(const KnitContactGrid& g, int k) {
  return k >= 1 && (g.columns() - 1) % k == 0 && g.courses % k == 0;
}

}  // namespace

bool knit_stride_fits(const Scene& s, int k) {
  return divides_grid(knit_contact_grid(s), k) && boundary_on_lattice(s, k);
}

FemMesh knit_contact_mesh(const Scene& s) {
  const KnitContactGrid g = knit_contact_grid(s);
  const int k = s.fem.stride;
  if (!divides_grid(g, k))
    throw std::invalid_argument("fem.stride " + std::to_string(k) + " does not divide the knit's contact grid (" +
                                std::to_string(g.columns() - 1) + " column and " + std::to_string(g.courses) +
                                " row spacings)");
  FemMesh m;
  m.source = "knit contact grid";
  for (int column = 0; column < g.columns(); column += k) m.grid_i.push_back(column);
  for (int row = 0; row < g.rows(); row += k) m.grid_j.push_back(row);
  for (int row : m.grid_j)
    for (int column : m.grid_i) {
      const Vec3 x = g.generated(column, row);  // posed as KnitModel::apply_pose
      m.uv.push_back(g.material(column, row));
      m.x.push_back(pose_position(s, x.x(), x.y()));
    }
  add_grid_triangles(m);
  return m;
}

double knit_yarn_mass(const Scene& s) {
  const KnitModel model(s);
  const Vec& q = model.initial_q();
  const auto& types = s.warp_yarn_types;
  double mass = 0.0;
  for (int y = 0; y < static_cast<int>(model.graph().yarns().size()); ++y)
    mass += s.yarn_types.at(types[y % types.size()]).density_kg_per_m * model.yarn_length(q, y);
  return mass;
}

double knit_areal_density(const Scene& s) { return knit_yarn_mass(s) / knit_contact_grid(s).area(); }

}  // namespace wl
