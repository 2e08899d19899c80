#include "models/common/self_contact.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>
#include <sstream>
#include <stdexcept>

#include <CGAL/Box_intersection_d/Box_with_info_d.h>
#include <CGAL/box_intersection_d.h>
#include <Eigen/Eigenvalues>

#include "models/common/conservative_advance.h"

namespace wl {

namespace {

using Box = CGAL::Box_intersection_d::Box_with_info_d<double, 3, int>;

// Nodes of each primitive of a pair (point–triangle: 1 + 3; edge–edge: 2 + 2).
int first_size(PairKind k) { return k == PairKind::point_triangle ? 1 : 2; }

// Largest fraction of the straight move x0 → x1 over which the pair stays
// farther than `target`, by conservative advancement: with a common
// translation removed, d(α) is Lipschitz with L = max‖Δxᵢ‖ over the first
// primitive + max over the second, so a step of (d − target)/L is safe.
double first_approach(PairKind kind, const std::array<Vec3, 4>& x0, const std::array<Vec3, 4>& x1, double d0,
                      double target) {
  std::array<Vec3, 4> dx;
  for (int i = 0; i < 4; ++i) dx[i] = (x1[i] - x0[i]) - (x1[0] - x0[0]);
  const int n1 = first_size(kind);
  double l1 = 0.0, l2 = 0.0;
  for (int i = 0; i < 4; ++i) (i < n1 ? l1 : l2) = std::max(i < n1 ? l1 : l2, dx[i].norm());
  return conservative_advance(d0, target, l1 + l2, [&](double alpha) {
    std::array<Vec3, 4> x;
    for (int i = 0; i < 4; ++i) x[i] = x0[i] + alpha * (x1[i] - x0[i]);
    return closest_support(kind, x).distance;
  });
}

// The symmetric part of a matrix with its negative eigenvalues set to 0.
template <int N>
Eigen::Matrix<double, N, N> positive_part(const Eigen::Matrix<double, N, N>& a) {
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, N, N>> eig(0.5 * (a + a.transpose()));
  return eig.eigenvectors() * eig.eigenvalues().cwiseMax(0.0).asDiagonal() * eig.eigenvectors().transpose();
}

}  // namespace

ObstacleContactRule self_contact_rule(const Scene& scene, double node_spacing_m, double max_node_mass_kg) {
  Scene s = scene;  // the obstacles' rule with the self-contact's own values
  s.obstacle_contact.activation_distance_m = scene.self_contact.activation_distance_m;
  s.obstacle_contact.stiffness_N_per_m = scene.self_contact.stiffness_N_per_m;
  return obstacle_contact_rule(s, node_spacing_m, max_node_mass_kg);
}

namespace {
std::array<int, 2> sorted_edge(std::array<int, 2> e) {
  if (e[1] < e[0]) std::swap(e[0], e[1]);
  return e;
}
std::array<int, 4> edge_pair_key(std::array<int, 2> a, std::array<int, 2> b) {
  a = sorted_edge(a);
  b = sorted_edge(b);
  if (b < a) std::swap(a, b);
  return {a[0], a[1], b[0], b[1]};
}
}  // namespace

SelfContactTerm::SelfContactTerm(ContactSurface surface, double dhat, double kappa, const ContactCapsules& capsules)
    : surface_(std::move(surface)),
      dhat_(dhat),
      radius_(capsules.radius),
      core_distance_(capsules.core_distance),
      kernels_{SelfContactPairTerm(dhat, kappa, 2.0 * capsules.radius),
               SelfContactPairTerm(dhat, kappa, capsules.core_distance)} {
  const int n = static_cast<int>(surface_.node_x.size());
  std::set<std::array<int, 2>> edges;
  for (const auto& t : surface_.triangles)
    for (int k = 0; k < 3; ++k) edges.insert(sorted_edge({t[k], t[(k + 1) % 3]}));
  for (const auto& e : capsules.segments) edges.insert(sorted_edge(e));
  edges_.assign(edges.begin(), edges.end());
  for (const auto& p : capsules.modelled)
    modelled_.insert(edge_pair_key(capsules.segments[p[0]], capsules.segments[p[1]]));
  for (int k = 0; k < n; ++k) {
    const int x = surface_.node_x[k];
    stencils_.push_back({x, x + 1, x + 2});
  }
  force_.assign(n, Vec3::Zero());
  block_.assign(n, Mat3::Zero());
}

// Pairs that share a node are left out.
bool SelfContactTerm::excluded(const int* a, int na, const int* b, int nb) const {
  for (int i = 0; i < na; ++i)
    for (int j = 0; j < nb; ++j)
      if (a[i] == b[j]) return true;
  return false;
}

std::array<Vec3, 4> SelfContactTerm::nodes(const Pair& p, const Vec& q) const {
  std::array<Vec3, 4> x;
  for (int i = 0; i < 4; ++i) x[i] = q.segment<3>(surface_.node_x[p.node[i]]);
  return x;
}

double SelfContactTerm::contact_distance(const Pair& p) const { return p.core ? core_distance_ : 2.0 * radius_; }

double SelfContactTerm::distance(const Pair& p, const Vec& q) const {
  return closest_support(p.kind, nodes(p, q)).distance - contact_distance(p);
}

long SelfContactTerm::overlapping_pairs(const Vec& q) const {
  long n = 0;
  for (const Pair& p : candidates(q, q, 0.0)) n += distance(p, q) < 0.0;
  return n;
}

std::vector<SelfContactTerm::Pair> SelfContactTerm::candidates(const Vec& q0, const Vec& q1, double margin) const {
  auto box = [&](const int* node, int n, int id) {
    double lo[3], hi[3];
    for (int c = 0; c < 3; ++c) {
      lo[c] = std::numeric_limits<double>::infinity();
      hi[c] = -lo[c];
    }
    for (int i = 0; i < n; ++i)
      for (const Vec* q : {&q0, &q1})
        for (int c = 0; c < 3; ++c) {
          const double v = (*q)[surface_.node_x[node[i]] + c];
          lo[c] = std::min(lo[c], v - radius_ - 0.5 * margin);
          hi[c] = std::max(hi[c], v + radius_ + 0.5 * margin);
        }
    return Box(lo, hi, id);
  };
  std::vector<Box> points, triangles, edges;
  for (int k = 0; k < static_cast<int>(surface_.node_x.size()); ++k) points.push_back(box(&k, 1, k));
  for (int k = 0; k < static_cast<int>(surface_.triangles.size()); ++k)
    triangles.push_back(box(surface_.triangles[k].data(), 3, k));
  for (int k = 0; k < static_cast<int>(edges_.size()); ++k) edges.push_back(box(edges_[k].data(), 2, k));
  std::vector<Pair> out;
  CGAL::box_intersection_d(points.begin(), points.end(), triangles.begin(), triangles.end(),
                           [&](const Box& p, const Box& t) {
                             const int a = p.info();
                             const auto& tri = surface_.triangles[t.info()];
                             if (!excluded(&a, 1, tri.data(), 3))
                               out.push_back({PairKind::point_triangle, {a, tri[0], tri[1], tri[2]}});
                           });
  CGAL::box_self_intersection_d(edges.begin(), edges.end(), [&](const Box& b0, const Box& b1) {
    const auto &e0 = edges_[b0.info()], &e1 = edges_[b1.info()];
    if (!excluded(e0.data(), 2, e1.data(), 2))
      out.push_back({PairKind::edge_edge, {e0[0], e0[1], e1[0], e1[1]}, modelled_.count(edge_pair_key(e0, e1)) > 0});
  });
  // A fixed order, whatever order the box intersection reports them in.
  std::sort(out.begin(), out.end(), [](const Pair& a, const Pair& b) {
    return std::make_pair(a.kind, a.node) < std::make_pair(b.kind, b.node);
  });
  return out;
}

void SelfContactTerm::prepare(const EvalContext& ctx) {
  const Vec& q = *ctx.q;
  std::fill(force_.begin(), force_.end(), Vec3::Zero());
  std::fill(block_.begin(), block_.end(), Mat3::Zero());
  std::array<std::vector<Pair>, 2> active;
  for (SelfContactPairTerm& kernel : kernels_) kernel.clear();
  for (const Pair& p : candidates(q, q, dhat_)) {
    if (!(distance(p, q) < dhat_)) continue;
    std::array<int, 12> s;
    for (int i = 0; i < 4; ++i)
      for (int c = 0; c < 3; ++c) s[3 * i + c] = surface_.node_x[p.node[i]] + c;
    kernels_[p.core].add(s, p.kind);
    active[p.core].push_back(p);
  }
  for (int which = 0; which < 2; ++which) gather(kernels_[which], active[which], q);
}

void SelfContactTerm::gather(const SelfContactPairTerm& kernel, const std::vector<Pair>& active, const Vec& q) {
  for (int e = 0; e < kernel.num_elements(); ++e) {
    Eigen::Matrix<double, 12, 1> lq, f = Eigen::Matrix<double, 12, 1>::Zero();
    Eigen::Matrix<double, 12, 12> k = Eigen::Matrix<double, 12, 12>::Zero();
    const auto s = kernel.stencil(e);
    for (int a = 0; a < 12; ++a) lq[a] = q[s[a]];
    kernel.evaluate(e, lq.data(), nullptr, ElementOutput{f.data(), k.data()});
    // H ⪯ H⁺ ⪯ m·blockdiag(H⁺), H⁺ the positive part of H = −∂F/∂x and m its
    // non-zero node blocks (Cauchy–Schwarz): the step's stiffness bounds the pair's.
    const Eigen::Matrix<double, 12, 12> hp = positive_part<12>(-k);
    int m = 0;
    for (int i = 0; i < 4; ++i) m += hp.block<3, 3>(3 * i, 3 * i).squaredNorm() > 0.0;
    for (int i = 0; i < 4; ++i) {
      const int n = active[e].node[i];
      force_[n] += f.segment<3>(3 * i);
      block_[n] -= m * hp.block<3, 3>(3 * i, 3 * i);
    }
  }
}

void SelfContactTerm::evaluate(int e, const double*, const double*, const ElementOutput& out) const {
  VecMap(out.force) = force_[e];
  if (out.dfdq) MatMap(out.dfdq) = block_[e];
}

double SelfContactTerm::admissible_fraction(const EvalContext& from, const EvalContext& to) const {
  double alpha = 1.0;
  for (const Pair& p : candidates(*from.q, *to.q, kApproachFraction * dhat_)) {
    const std::array<Vec3, 4> x0 = nodes(p, *from.q), x1 = nodes(p, *to.q);
    const double d0 = closest_support(p.kind, x0).distance, g0 = d0 - contact_distance(p);
    if (!(g0 > 0.0)) continue;  // a start in contact constrains nothing (never an accepted state)
    const double target = contact_distance(p) + kApproachFraction * std::min(g0, dhat_);
    alpha = std::min(alpha, first_approach(p.kind, x0, x1, d0, target));
  }
  return alpha;
}

void refuse_self_contact(const Scene& scene, const std::string& what) {
  if (!scene.self_contact.enabled) return;
  throw std::invalid_argument(scene.source + ":" + std::to_string(scene.self_contact.line) +
                              ": self_contact.enabled: " + what +
                              " needs the exact stiffness, of which self-contact assembles a bound "
                              "(docs/models.md §3.11.7); expected a scene without it");
}

void add_self_contact(const Scene& scene, const ObstacleContactRule& rule, double node_spacing_m,
                      ContactSurface surface, const Vec& q0, std::vector<std::unique_ptr<Term>>& terms,
                      const ContactCapsules& capsules) {
  if (!scene.self_contact.enabled) return;
  auto term = std::make_unique<SelfContactTerm>(std::move(surface), rule.activation_distance_m, rule.stiffness_N_per_m,
                                                capsules);
  double closest = std::numeric_limits<double>::infinity();
  for (const auto& p : term->candidates(q0, q0, rule.activation_distance_m))
    closest = std::min(closest, term->distance(p, q0));
  const double dhat = rule.activation_distance_m, bound = std::min(closest, node_spacing_m);
  if (!(dhat < bound)) {
    std::ostringstream msg;
    msg << scene.source << ":" << scene.self_contact.line << ": self_contact.activation_distance_m: d̂ = " << dhat
        << " m; expected d̂ below " << bound << " m, "
        << (closest >= node_spacing_m ? (capsules.radius > 0.0 ? "the yarn radius" : "the node spacing")
            : capsules.radius > 0.0
                ? "the gap at which two yarn segments that share no node start (d − 2R, or d less the core distance "
                  "for the pairs the compression models; the knit must not feel itself at rest)"
                : "the distance at which two surface primitives that share no node start "
                  "(the cloth must not feel itself at rest)");
    throw std::invalid_argument(msg.str());
  }
  terms.push_back(std::move(term));
}

}  // namespace wl
