#include "models/knit/knit_boundary.h"

#include "models/common/handle_spring.h"

namespace wl {

std::array<int, 2> knit_contact_nodes(const KnitGraph& graph, const NodeRef& ref) {
  const int r = ref.i - 1, c = ref.j / 2, s = ref.j % 2;
  return {graph.contact_node(r, c, s, 0), graph.contact_node(r, c, s, 1)};
}

std::vector<int> knit_pinned_dofs(const KnitGraph& graph, const Scene& scene) {
  std::vector<int> held;
  for (const NodeRef& p : scene.pins)
    for (int n : knit_contact_nodes(graph, p)) {
      const KnitNode& node = graph.node(n);
      for (int k = 0; k < 3; ++k) held.push_back(node.x_dof + k);
      for (int c : node.coord)
        if (is_dof(c)) held.push_back(c);
    }
  return held;
}

// V = ½ (k/2) ‖x − a(t)‖² on each node of the contact (docs/models.md §3.10, §11.7).
std::unique_ptr<Term> knit_handles(const KnitGraph& graph, const Scene& scene, const Vec& q0) {
  if (scene.handles.empty() || !scene.terms.handles) return nullptr;
  auto t = std::make_unique<HandleSpringTerm>();
  for (const Handle& h : scene.handles) {
    const HandleMotion motion{Vec3(h.velocity_m_per_s[0], h.velocity_m_per_s[1], h.velocity_m_per_s[2]), h.start_s,
                              h.stop_s};
    for (int n : knit_contact_nodes(graph, h.node)) {
      const int x = graph.node(n).x_dof;
      t->add({x, x + 1, x + 2}, q0.segment<3>(x), 0.5 * h.stiffness_N_per_m, motion);
    }
  }
  return t;
}

}  // namespace wl
