// The knit graph (docs/models.md §11.1): contact nodes carrying a position x
// and one sliding coordinate per yarn through them (a "slot"), and yarns as
// ordered paths of (node, slot) visits. Built from a knit layout: course r's
// yarn runs through the loops (r, 0..wales−1); the loop of course r+1 at wale c
// is pulled through the loop of course r at wale c, meeting it at two stitch
// contacts (left and right). A stitch contact is a segment between two nodes
// a (lower) and b (upper) that both yarns traverse in the same direction:
// slot 0 is course r's yarn (the loop head), slot 1 course r+1's (the leg).
// Where one of the two courses does not exist (below the first course, above
// the last) the nodes carry one slot only.
//
// A periodic graph is one tile of a pattern with its yarns closed: each visit
// may refer to an image of its node shifted by `dx`, and a yarn continues after
// its last visit at its first, shifted by (period_dx, period_du).
#pragma once
#include <array>
#include <functional>
#include <vector>

#include "models/core/types.h"

namespace wl {

struct KnitLayout {
  int courses = 2, wales = 2;
  double wale_spacing = 1e-3;    // W: loop width [m]
  double course_spacing = 8e-4;  // C: loop height [m]
  double thickness = 5e-4;       // t: the stitch segment goes from −t to +t through the cloth [m]
  bool periodic = false;         // one tile, yarns closed in both directions
  // periodic: the tile's period is (wales·W·period_scale[0], courses·C·period_scale[1])
  // while its loops (coordinates, rest lengths) keep the generated W and C (docs/models.md §11.3.1).
  std::array<double, 2> period_scale{1.0, 1.0};
  // Whether the loop (course, wale) is a purl stitch (its yarn passes behind the
  // loop below), else a knit stitch (courses ≥ 1; course 0 is cast on).
  std::function<bool(int course, int wale)> purl;
};

struct KnitNode {
  Vec3 x;                  // generated position
  std::vector<int> yarn;   // per slot: the yarn through it
  std::vector<double> u;   // per slot: generated arc-length coordinate of that yarn
  std::vector<int> coord;  // per slot: DoF index or encoded constant (types.h), set by assign_dofs
  int x_dof = -1;
};

struct KnitVisit {
  int node = 0, slot = 0;
  Vec3 dx = Vec3::Zero();  // the yarn passes the image of the node shifted by dx
};

struct KnitYarn {
  std::vector<KnitVisit> visits;
  bool closed = false;
  Vec3 period_dx = Vec3::Zero();  // closed: the next period's image shift
  double period_du = 0.0;         // closed: arc length per period
};

struct StitchContact {
  int a = 0, b = 0;                    // nodes: the stitch segment a→b, both yarns go from a to b or both from b to a
  int course = 0, wale = 0, side = 0;  // between courses `course` and course+1; side 0 left, 1 right
  bool purl = false;
};

class KnitGraph {
 public:
  explicit KnitGraph(const KnitLayout& layout);

  const KnitLayout& layout() const { return layout_; }
  int num_nodes() const { return static_cast<int>(nodes_.size()); }
  const KnitNode& node(int k) const { return nodes_[k]; }
  const std::vector<KnitNode>& nodes() const { return nodes_; }
  const std::vector<KnitYarn>& yarns() const { return yarns_; }
  // Contacts with n ≥ 2 slots (yarns): where the stitch terms act.
  const std::vector<StitchContact>& stitches() const { return stitches_; }
  // Node id of contact (course r ∈ [−1, courses−1] non-periodic / [0, courses−1]
  // periodic, wale c, side s) end e (0: a, 1: b).
  int contact_node(int r, int c, int s, int e) const;

  // Numbers the DoFs: x (3) per node, then one coordinate per slot, a DoF when
  // `sliding` and frozen(node) is false, else a constant. Returns the constants.
  Vec assign_dofs(bool sliding, const std::function<bool(int node)>& frozen, int& num_dofs);
  // The visit after / before visit k of yarn y (wrapping when closed; −1 at an
  // open end), with the extra shift the wrap adds.
  struct Step {
    int k = -1;
    Vec3 dx = Vec3::Zero();
    double du = 0.0;
  };
  Step next(int y, int k) const;
  Step previous(int y, int k) const;

 private:
  int add_node(const Vec3& x);
  void build_contacts();
  void build_yarns();
  void set_coordinates();

  KnitLayout layout_;
  std::vector<KnitNode> nodes_;
  std::vector<KnitYarn> yarns_;
  std::vector<StitchContact> stitches_;
  std::vector<int> contact_first_;  // node id of end a of each contact, indexed by contact_index
  int contact_index(int r, int c, int s) const;
};

}  // namespace wl
