// The scene's rigid obstacles in a model (docs/models.md §3.11): builds the
// contact barrier and friction terms over the model's nodes, resolves the
// contact rules, and gives the contact force per node and the obstacles'
// surface for output. Shared by the yarn and FEM models.
#pragma once
#include <array>
#include <memory>
#include <vector>

#include "models/common/obstacle.h"
#include "models/core/frame.h"
#include "models/core/term.h"
#include "models/scene/scene.h"

namespace wl {

// The contact parameters a scene resolves to (docs/models.md §3.11.2):
//   d̂ = activation_distance_m, else ½ the node spacing ℓ;
//   κ = stiffness_N_per_m, else the stiffness at which the barrier holds
//       1000 times the heaviest node's weight m g (g = max(‖g‖, 9.81 m/s²)) at
//       d = d̂/2: κ = 1000 m g / (−b'(d̂/2)) with −b'(d̂/2) = (½ + ln 2) d̂;
//   ε = friction_speed_m_per_s.
struct ObstacleContactRule {
  double activation_distance_m = 0.0, stiffness_N_per_m = 0.0, friction_speed_m_per_s = 0.0;
};
ObstacleContactRule obstacle_contact_rule(const Scene& scene, double node_spacing_m, double max_node_mass_kg);

class ObstacleContact {
 public:
  ObstacleContact() = default;
  // Adds to `terms` the barrier on every (node, obstacle), the friction on
  // those with μ > 0 and, with obstacle_contact.segment_edges, the segment–edge
  // barrier on every (segment, obstacle with sharp edges) (§3.11.10); node k has position DoFs node_x[k] … +2, a
  // segment joins two nodes (the cloth's yarn segments or triangle edges). Throws
  // std::invalid_argument naming the node and the obstacle's scene line when a
  // node starts at or inside an obstacle.
  ObstacleContact(const Scene& scene, const ObstacleContactRule& rule, const std::vector<int>& node_x,
                  const std::vector<std::array<int, 2>>& segments, const Vec& q0,
                  std::vector<std::unique_ptr<Term>>& terms);
  bool empty() const { return barrier_ < 0; }
  // "contact_force" point data [N]: barrier, segment–edge and friction force on each node at
  // (t, q, v), friction with its lagged normal force (that of the last accepted state).
  DataArray force_data(const std::vector<std::unique_ptr<Term>>& terms, int num_nodes, double t, const Vec& q,
                       const Vec& v) const;
  // The obstacles at time t as triangles, point data "obstacle" (its index).
  Frame frame(double t, double plane_extent_m) const;

 private:
  std::shared_ptr<const std::vector<Obstacle>> obstacles_;
  int barrier_ = -1, friction_ = -1, edge_ = -1;  // indices into the model's terms
  std::vector<std::array<int, 2>> edge_nodes_;    // the nodes of each segment–edge element
};

}  // namespace wl
