// Which crossings of the woven grid a cloth simulates at yarn level, and the
// share of the cloth each yarn-level element stands for there (docs/models.md
// §12.1–§12.3). Cell (a, b) is the square of crossings (a … a+1, b … b+1); a
// yarn cell has its four corners in the region. The yarn model's region is the
// whole grid: every share is then 1 and the yarn-interior crossings are the
// grid's interior.
#pragma once
#include <array>
#include <initializer_list>
#include <vector>

namespace wl {

class YarnRegion {
 public:
  // The whole grid of nu × nv crossings (the yarn model).
  static YarnRegion everything(int nu, int nv);
  // The crossings held by the rectangles [i0, j0, i1, j1] (inclusive, inside the grid).
  YarnRegion(int nu, int nv, const std::vector<std::array<int, 4>>& rectangles);

  // Crossing (i, j) is in the region.
  bool holds(int i, int j) const { return node_[i + nu_ * j] != 0; }
  // Cell (a, b) exists and its four corners are in the region.
  bool yarn_cell(int a, int b) const { return exists(a, b) && cell_[a + (nu_ - 1) * b] != 0; }
  // The four cells around crossing (i, j) exist and are yarn cells: where it slides.
  bool yarn_interior(int i, int j) const;
  // Yarn share of the segment from (i, j) to (i+1, j) (warp) or (i, j+1) (weft):
  // the yarn cells' part of the cells beside it (one on the cloth's border, else two).
  double segment_share(int i, int j, bool warp) const;
  // Yarn share of an element standing for the cells around crossing (i, j).
  double crossing_share(int i, int j) const;
  // Every cell is a yarn cell.
  bool everywhere() const { return yarn_cells_ == (nu_ - 1) * (nv_ - 1); }
  int yarn_cells() const { return yarn_cells_; }
  int nu() const { return nu_; }
  int nv() const { return nv_; }

 private:
  YarnRegion(int nu, int nv);
  bool exists(int a, int b) const { return a >= 0 && b >= 0 && a < nu_ - 1 && b < nv_ - 1; }
  void mark_cells();
  // The yarn cells' part of those of `cells` that exist.
  double yarn_part(std::initializer_list<std::array<int, 2>> cells) const;

  int nu_, nv_, yarn_cells_ = 0;
  std::vector<char> node_, cell_;  // per crossing i + nu·j, per cell a + (nu−1)·b
};

}  // namespace wl
