#include "models/yarn/yarn_region.h"

#include <stdexcept>
#include <string>

namespace wl {

YarnRegion::YarnRegion(int nu, int nv)
    : nu_(nu), nv_(nv), node_(static_cast<size_t>(nu) * nv, 0), cell_(static_cast<size_t>(nu - 1) * (nv - 1), 0) {}

YarnRegion YarnRegion::everything(int nu, int nv) { return YarnRegion(nu, nv, {{0, 0, nu - 1, nv - 1}}); }

YarnRegion::YarnRegion(int nu, int nv, const std::vector<std::array<int, 4>>& rectangles) : YarnRegion(nu, nv) {
  for (const auto& r : rectangles) {
    if (!(0 <= r[0] && r[0] <= r[2] && r[2] < nu && 0 <= r[1] && r[1] <= r[3] && r[3] < nv))
      throw std::invalid_argument("yarn region: rectangle [" + std::to_string(r[0]) + ", " + std::to_string(r[1]) +
                                  ", " + std::to_string(r[2]) + ", " + std::to_string(r[3]) +
                                  "] is not inside the grid of " + std::to_string(nu) + " x " + std::to_string(nv) +
                                  " crossings with i0 <= i1, j0 <= j1");
    for (int j = r[1]; j <= r[3]; ++j)
      for (int i = r[0]; i <= r[2]; ++i) node_[i + nu_ * j] = 1;
  }
  mark_cells();
}

void YarnRegion::mark_cells() {
  for (int b = 0; b + 1 < nv_; ++b)
    for (int a = 0; a + 1 < nu_; ++a) {
      const bool yarn = holds(a, b) && holds(a + 1, b) && holds(a, b + 1) && holds(a + 1, b + 1);
      cell_[a + (nu_ - 1) * b] = yarn ? 1 : 0;
      yarn_cells_ += yarn ? 1 : 0;
    }
}

bool YarnRegion::yarn_interior(int i, int j) const {
  return yarn_cell(i - 1, j - 1) && yarn_cell(i, j - 1) && yarn_cell(i - 1, j) && yarn_cell(i, j);
}

double YarnRegion::yarn_part(std::initializer_list<std::array<int, 2>> cells) const {
  int existing = 0, yarn = 0;
  for (const auto& c : cells) {
    existing += exists(c[0], c[1]) ? 1 : 0;
    yarn += yarn_cell(c[0], c[1]) ? 1 : 0;
  }
  return existing > 0 ? static_cast<double>(yarn) / existing : 0.0;
}

double YarnRegion::segment_share(int i, int j, bool warp) const {
  // A warp segment lies between the cells below and above it, a weft segment between those left and right.
  if (warp) return yarn_part({{i, j - 1}, {i, j}});
  return yarn_part({{i - 1, j}, {i, j}});
}

double YarnRegion::crossing_share(int i, int j) const {
  return yarn_part({{i - 1, j - 1}, {i, j - 1}, {i - 1, j}, {i, j}});
}

}  // namespace wl
