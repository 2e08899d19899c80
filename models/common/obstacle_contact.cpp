#include "models/common/obstacle_contact.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>
#include <stdexcept>

#include "models/common/obstacle_barrier.h"
#include "models/common/obstacle_edge.h"
#include "models/common/obstacle_friction.h"

namespace wl {

ObstacleContactRule obstacle_contact_rule(const Scene& scene, double node_spacing_m, double max_node_mass_kg) {
  const ObstacleContactParams& p = scene.obstacle_contact;
  ObstacleContactRule r;
  r.activation_distance_m = p.activation_distance_m.value_or(0.5 * node_spacing_m);
  const auto& gv = scene.gravity_m_per_s2;
  const double g = std::max(std::sqrt(gv[0] * gv[0] + gv[1] * gv[1] + gv[2] * gv[2]), 9.81);
  const double hold = (0.5 + std::numbers::ln2) * r.activation_distance_m;  // −b'(d̂/2)
  r.stiffness_N_per_m = p.stiffness_N_per_m.value_or(1000.0 * max_node_mass_kg * g / hold);
  r.friction_speed_m_per_s = p.friction_speed_m_per_s;
  return r;
}

ObstacleContact::ObstacleContact(const Scene& scene, const ObstacleContactRule& rule, const std::vector<int>& node_x,
                                 const std::vector<std::array<int, 2>>& segments, const Vec& q0,
                                 std::vector<std::unique_ptr<Term>>& terms) {
  if (scene.obstacles.empty()) return;
  auto obstacles = std::make_shared<std::vector<Obstacle>>();
  for (const ObstacleSpec& s : scene.obstacles) obstacles->emplace_back(s);
  obstacles_ = obstacles;
  const double dhat = rule.activation_distance_m, kappa = rule.stiffness_N_per_m;
  auto barrier = std::make_unique<ObstacleBarrierTerm>(obstacles_, dhat, kappa);
  auto friction = std::make_unique<ObstacleFrictionTerm>(obstacles_, dhat, kappa, rule.friction_speed_m_per_s);
  auto edge = std::make_unique<ObstacleEdgeTerm>(obstacles_, dhat, kappa);
  barrier->set_projected_step_stiffness(scene.obstacle_contact.projected_step_hessian);
  for (int k = 0; k < static_cast<int>(obstacles->size()); ++k) {
    const Obstacle& o = (*obstacles)[k];
    for (int n = 0; n < static_cast<int>(node_x.size()); ++n) {
      const int x = node_x[n];
      const double d = o.signed_distance(q0.segment<3>(x), 0.0);
      if (!(d > 0.0)) {
        std::ostringstream msg;
        msg << scene.source << ":" << o.spec().line << ": obstacles[" << k << "]: node " << n << " at ("
            << q0.segment<3>(x).transpose() << ") m starts " << (d < 0.0 ? "inside" : "on")
            << " the obstacle (signed distance " << d << " m); expected every node outside it";
        throw std::invalid_argument(msg.str());
      }
      barrier->add({x, x + 1, x + 2}, n, k);
      if (o.friction_coefficient() > 0.0) friction->add({x, x + 1, x + 2}, n, k);
    }
    if (!scene.obstacle_contact.segment_edges || sharp_edges(o, 0.0).empty()) continue;
    for (const auto& [a, b] : segments) {
      const int xa = node_x[a], xb = node_x[b];
      edge->add({xa, xa + 1, xa + 2, xb, xb + 1, xb + 2}, k);
      edge_nodes_.push_back({a, b});
    }
  }
  barrier_ = static_cast<int>(terms.size());
  terms.push_back(std::move(barrier));
  if (edge->num_elements() > 0) {
    edge_ = static_cast<int>(terms.size());
    terms.push_back(std::move(edge));
  }
  if (friction->num_elements() > 0) {
    friction_ = static_cast<int>(terms.size());
    terms.push_back(std::move(friction));
  }
}

DataArray ObstacleContact::force_data(const std::vector<std::unique_ptr<Term>>& terms, int num_nodes, double t,
                                      const Vec& q, const Vec& v) const {
  DataArray out{"contact_force", 3, std::vector<double>(3 * static_cast<size_t>(num_nodes), 0.0)};
  if (empty()) return out;
  const auto& barrier = static_cast<const ObstacleBarrierTerm&>(*terms[barrier_]);
  for (int e = 0; e < barrier.num_elements(); ++e) {
    const auto s = barrier.stencil(e);
    const Vec3 f = barrier.force(e, t, q.segment<3>(s[0]));
    for (int c = 0; c < 3; ++c) out.values[3 * barrier.node(e) + c] += f[c];
  }
  if (edge_ >= 0) {
    const auto& edge = static_cast<const ObstacleEdgeTerm&>(*terms[edge_]);
    for (int e = 0; e < edge.num_elements(); ++e) {
      const auto s = edge.stencil(e);
      Eigen::Matrix<double, 6, 1> lq;
      for (int a = 0; a < 6; ++a) lq[a] = q[s[a]];
      const Eigen::Matrix<double, 6, 1> f = edge.force(e, t, lq.data());
      for (int i = 0; i < 2; ++i)
        for (int c = 0; c < 3; ++c) out.values[3 * edge_nodes_[e][i] + c] += f[3 * i + c];
    }
  }
  if (friction_ >= 0) {
    const auto& friction = static_cast<const ObstacleFrictionTerm&>(*terms[friction_]);
    for (int e = 0; e < friction.num_elements(); ++e) {
      const Vec3 f = friction.force(e, v.segment<3>(friction.stencil(e)[0]));
      for (int c = 0; c < 3; ++c) out.values[3 * friction.node(e) + c] += f[c];
    }
  }
  return out;
}

Frame ObstacleContact::frame(double t, double plane_extent_m) const {
  Frame f;
  f.time = t;
  if (empty()) return f;
  std::vector<Vec3> points;
  std::vector<std::array<int, 3>> tris;
  DataArray index{"obstacle", 1, {}};
  for (size_t k = 0; k < obstacles_->size(); ++k) {
    (*obstacles_)[k].surface(t, plane_extent_m, points, tris);
    index.values.resize(points.size(), static_cast<double>(k));
  }
  f.points.resize(static_cast<Eigen::Index>(points.size()), 3);
  for (size_t i = 0; i < points.size(); ++i) f.points.row(static_cast<Eigen::Index>(i)) = points[i].transpose();
  CellBlock cells{CellType::triangle, {}};
  for (const auto& tri : tris) cells.connectivity.insert(cells.connectivity.end(), tri.begin(), tri.end());
  f.cells = {cells};
  f.point_data = {index};
  return f;
}

}  // namespace wl
