#include "models/knit/knit_graph.h"

#include <stdexcept>

namespace wl {

KnitGraph::KnitGraph(const KnitLayout& layout) : layout_(layout) {
  if (layout_.courses < 1 || layout_.wales < 1 || !layout_.purl)
    throw std::invalid_argument("KnitGraph: a layout needs courses, wales ≥ 1 and a stitch rule");
  build_contacts();
  build_yarns();
  set_coordinates();
  // The period's images move; the coordinates stay those of the generated loops.
  const Vec3 scale(layout_.period_scale[0], layout_.period_scale[1], 1.0);
  for (KnitYarn& y : yarns_) {
    for (KnitVisit& v : y.visits) v.dx = v.dx.cwiseProduct(scale);
    y.period_dx = y.period_dx.cwiseProduct(scale);
  }
}

int KnitGraph::contact_index(int r, int c, int s) const {
  const int rmin = layout_.periodic ? 0 : -1;
  return ((r - rmin) * layout_.wales + c) * 2 + s;
}

int KnitGraph::contact_node(int r, int c, int s, int e) const { return 2 * contact_index(r, c, s) + e; }

int KnitGraph::add_node(const Vec3& x) {
  nodes_.push_back(KnitNode{x, {}, {}, {}, -1});
  return static_cast<int>(nodes_.size()) - 1;
}

// Contact (r, c, s) sits between course r's loop head and course r+1's leg:
// x = cW ∓ W/4, y = (r + ½)C, its segment from a (y − C/6) to b (y + C/6) and
// through the cloth from −t to +t for a knit stitch of loop (r+1, c), from +t
// to −t for a purl one (docs/models.md §11.2).
void KnitGraph::build_contacts() {
  const KnitLayout& L = layout_;
  const int rmin = L.periodic ? 0 : -1;
  for (int r = rmin; r < L.courses; ++r)
    for (int c = 0; c < L.wales; ++c)
      for (int s = 0; s < 2; ++s) {
        const bool purl = L.purl(r + 1, c);
        const double x = c * L.wale_spacing + (s == 0 ? -0.25 : 0.25) * L.wale_spacing;
        const double y = (r + 0.5) * L.course_spacing, dy = L.course_spacing / 6.0;
        const double z = purl ? L.thickness : -L.thickness;
        const int a = add_node(Vec3(x, y - dy, z));
        const int b = add_node(Vec3(x, y + dy, -z));
        const bool head = L.periodic || r >= 0, leg = L.periodic || r + 1 < L.courses;
        for (int n : {a, b}) {
          if (head) nodes_[n].yarn.push_back(r < 0 ? 0 : r % L.courses);
          if (leg) nodes_[n].yarn.push_back((r + 1) % L.courses);
        }
        if (head && leg) stitches_.push_back({a, b, r, c, s, purl});
      }
}

// Course r at wale c: the left foot (contact (r−1, c, left), a→b, leg slot),
// the left of the head (r, c, left, a→b, head slot), the right of the head
// (b→a) and the right foot (b→a); then the sinker to wale c+1.
void KnitGraph::build_yarns() {
  const KnitLayout& L = layout_;
  for (int r = 0; r < L.courses; ++r) {
    KnitYarn y;
    for (int c = 0; c < L.wales; ++c) {
      auto contact = [&](int row, int s, bool head, bool up) {
        Vec3 dx = Vec3::Zero();
        if (row < 0 && L.periodic) {
          row += L.courses;
          dx = Vec3(0.0, -L.courses * L.course_spacing, 0.0);
        }
        const int a = contact_node(row, c, s, 0);
        const int slot = head ? 0 : static_cast<int>(nodes_[a].yarn.size()) - 1;
        for (int e : {up ? 0 : 1, up ? 1 : 0}) y.visits.push_back({a + e, slot, dx});
      };
      contact(r - 1, 0, false, true);
      contact(r, 0, true, true);
      contact(r, 1, true, false);
      contact(r - 1, 1, false, false);
    }
    if (L.periodic) {
      y.closed = true;
      y.period_dx = Vec3(L.wales * L.wale_spacing, 0.0, 0.0);
    }
    yarns_.push_back(std::move(y));
  }
}

// Arc length along the generated path: u of a visit = distance travelled from
// the yarn's first visit (docs/models.md §11.2).
void KnitGraph::set_coordinates() {
  for (KnitNode& n : nodes_) n.u.assign(n.yarn.size(), 0.0);
  for (KnitYarn& y : yarns_) {
    double u = 0.0;
    Vec3 prev = Vec3::Zero();
    for (size_t k = 0; k < y.visits.size(); ++k) {
      const KnitVisit& v = y.visits[k];
      const Vec3 x = nodes_[v.node].x + v.dx;
      if (k > 0) u += (x - prev).norm();
      nodes_[v.node].u[v.slot] = u;
      prev = x;
    }
    if (y.closed) {
      const KnitVisit& first = y.visits.front();
      y.period_du = u + (nodes_[first.node].x + first.dx + y.period_dx - prev).norm();
    }
  }
}

Vec KnitGraph::assign_dofs(bool sliding, const std::function<bool(int)>& frozen, int& num_dofs) {
  std::vector<double> constants;
  num_dofs = 0;
  for (int k = 0; k < num_nodes(); ++k) {
    KnitNode& n = nodes_[k];
    n.x_dof = num_dofs;
    num_dofs += 3;
    n.coord.clear();
    const bool fixed = !sliding || frozen(k);
    for (double u : n.u) {
      if (fixed) {
        n.coord.push_back(encode_constant(static_cast<int>(constants.size())));
        constants.push_back(u);
      } else n.coord.push_back(num_dofs++);
    }
  }
  return Eigen::Map<Vec>(constants.data(), static_cast<Eigen::Index>(constants.size()));
}

KnitGraph::Step KnitGraph::next(int y, int k) const {
  const KnitYarn& yarn = yarns_[y];
  const int n = static_cast<int>(yarn.visits.size());
  if (k + 1 < n) return {k + 1, Vec3::Zero(), 0.0};
  if (!yarn.closed) return {};
  return {0, yarn.period_dx, yarn.period_du};
}

KnitGraph::Step KnitGraph::previous(int y, int k) const {
  const KnitYarn& yarn = yarns_[y];
  const int n = static_cast<int>(yarn.visits.size());
  if (k > 0) return {k - 1, Vec3::Zero(), 0.0};
  if (!yarn.closed) return {};
  return {n - 1, -yarn.period_dx, -yarn.period_du};
}

}  // namespace wl
