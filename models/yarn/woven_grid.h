// The woven grid of the yarn-level model (docs/models.md §2): node (i, j) is the
// crossing of weft i and warp j; i runs along the warp (material u = i·L), j
// along the weft (v = j·L). Warp j passes nodes (0..nu−1, j) and slides in u;
// weft i passes nodes (i, 0..nv−1) and slides in v. The outer ring has no
// sliding DoFs (docs/models.md §2.1, §4.2); neither has any node when sliding is off.
// Over a YarnRegion only the region's yarn-interior crossings slide (docs/models.md §12.2).
#pragma once
#include <vector>

#include "models/core/types.h"
#include "models/scene/scene.h"
#include "models/yarn/yarn_region.h"

namespace wl {

struct NodeDofs {
  int x = -1;  // index of x (3 consecutive DoFs)
  int u = -1;  // DoF index, or an encoded constant (types.h) when frozen
  int v = -1;
};

class WovenGrid {
 public:
  explicit WovenGrid(const Scene& scene);
  WovenGrid(const Scene& scene, const YarnRegion& region);
  int nu() const { return nu_; }
  int nv() const { return nv_; }
  int num_nodes() const { return nu_ * nv_; }
  int node(int i, int j) const { return i + nu_ * j; }
  bool interior(int i, int j) const { return i > 0 && j > 0 && i < nu_ - 1 && j < nv_ - 1; }
  const NodeDofs& dofs(int n) const { return dofs_[n]; }
  int num_dofs() const { return num_dofs_; }
  // Constant coordinates referenced by encoded stencil entries.
  const Vec& constants() const { return constants_; }
  // Over/under sign s_ij = ±1: +1 when the weft lies on the +n side of the warp (docs/models.md §2.3).
  int sign(int i, int j) const { return sign_[node(i, j)]; }
  double spacing() const { return L_; }

 private:
  int nu_, nv_, num_dofs_ = 0;
  double L_;
  std::vector<NodeDofs> dofs_;
  std::vector<int> sign_;
  Vec constants_;
};

// Pattern masks (docs/models.md §2.3; scene keys in experiments/scenes/README.md): +1/−1 per crossing.
int pattern_sign(const Pattern& p, int i, int j);

}  // namespace wl
