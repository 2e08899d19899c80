#include "models/knit/yarn_contact.h"

#include <algorithm>

namespace wl {

KnitContactSet knit_contact_set(const KnitGraph& graph, const std::vector<YarnPiece>& pieces,
                                const std::vector<PiecePair>& compressed, double radius) {
  KnitContactSet set;
  for (const KnitNode& n : graph.nodes()) set.surface.node_x.push_back(n.x_dof);
  for (const YarnPiece& p : pieces) set.capsules.segments.push_back({p.n0, p.n1});
  set.capsules.radius = radius;
  for (const PiecePair& p : compressed) set.capsules.modelled.push_back({p.a, p.b});
  set.capsules.core_distance = knit_core_distance(radius);
  return set;
}

ObstacleContactRule knit_contact_rule(const Scene& scene, const KnitGraph& graph,
                                      const std::vector<YarnPiece>& pieces) {
  double rho = 0.0, longest = 0.0;
  for (const auto& [name, y] : scene.yarn_types) rho = std::max(rho, y.density_kg_per_m);
  for (const YarnPiece& p : pieces) longest = std::max(longest, (graph.node(p.n1).x - graph.node(p.n0).x).norm());
  return self_contact_rule(scene, scene.radius_m, 2.0 * rho * longest);
}

}  // namespace wl
