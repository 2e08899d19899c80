#include "models/yarn/woven_grid.h"

#include <numeric>

namespace wl {

int pattern_sign(const Pattern& p, int i, int j) {
  switch (p.kind) {
    case Pattern::Kind::plain: return (i + j) % 2 == 0 ? 1 : -1;
    case Pattern::Kind::twill: {
      const int period = p.twill_over + p.twill_under;
      const int k = ((i + p.twill_shift * j) % period + period) % period;
      return k < p.twill_over ? 1 : -1;
    }
    case Pattern::Kind::satin: return ((p.satin_step * i + j) % p.satin_harness) == 0 ? 1 : -1;
  }
  return 1;
}

WovenGrid::WovenGrid(const Scene& scene) : WovenGrid(scene, YarnRegion::everything(scene.nodes_u(), scene.nodes_v())) {}

WovenGrid::WovenGrid(const Scene& scene, const YarnRegion& region)
    : nu_(scene.nodes_u()), nv_(scene.nodes_v()), L_(scene.spacing_m), dofs_(nu_ * nv_), sign_(nu_ * nv_) {
  std::vector<double> constants;
  for (int j = 0; j < nv_; ++j)
    for (int i = 0; i < nu_; ++i) {
      NodeDofs& d = dofs_[node(i, j)];
      d.x = num_dofs_;
      num_dofs_ += 3;
      const bool slides = scene.sliding && region.yarn_interior(i, j);
      if (slides) {
        d.u = num_dofs_++;
        d.v = num_dofs_++;
      } else {
        d.u = encode_constant(static_cast<int>(constants.size()));
        constants.push_back(i * L_);
        d.v = encode_constant(static_cast<int>(constants.size()));
        constants.push_back(j * L_);
      }
      // docs/models.md §2.3; the published code leaves the ring unsigned (docs/published_code.md row 22).
      const bool ring = i == 0 || j == 0 || i == nu_ - 1 || j == nv_ - 1;
      sign_[node(i, j)] = ring && scene.compat.ring_unsigned ? 1 : pattern_sign(scene.pattern, i, j);
    }
  constants_ = Eigen::Map<Vec>(constants.data(), static_cast<Eigen::Index>(constants.size()));
}

}  // namespace wl
