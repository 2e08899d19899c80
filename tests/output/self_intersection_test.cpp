// count_self_intersections (docs/models.md §3.11.7): crossing triangles are
// counted, neighbours sharing a vertex or an edge are not, and a quad grid
// folded through itself is caught.
#include "output/self_intersection.h"

#include <gtest/gtest.h>

#include "tests/output/output_test_util.h"

namespace wl {
namespace {

Frame grid(int n, double fold_z) {  // n×n quads in the plane z = 0; the half x > 0.5 raised to fold_z and flipped back
  Frame f;
  f.points.resize(n * n, 3);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const double x = double(i) / (n - 1), y = double(j) / (n - 1);
      f.points.row(i + n * j) << (x > 0.5 ? 1.0 - x : x), y, (x > 0.5 ? fold_z * (x - 0.5) : 0.0);
    }
  f.cells = {test::quad_grid_cells(n)};
  return f;
}

TEST(SelfIntersection, CountsCrossingPairsOnly) {
  Frame f;
  f.points.resize(6, 3);
  f.points << 0, 0, 0, 1, 0, 0, 0, 1, 0,             // in z = 0
      0.2, 0.2, -0.5, 0.2, 0.2, 0.5, 0.6, 0.1, 0.0;  // through it
  f.cells = {CellBlock{CellType::triangle, {0, 1, 2, 3, 4, 5}}};
  EXPECT_EQ(count_self_intersections(f), 1);
  f.points.row(3) << 2, 2, -0.5;  // moved away: no contact
  f.points.row(4) << 2, 2, 0.5;
  f.points.row(5) << 2.5, 2, 0.0;
  EXPECT_EQ(count_self_intersections(f), 0);
}

TEST(SelfIntersection, FlatGridIsCleanAndAFoldThroughItselfIsNot) {
  EXPECT_EQ(count_self_intersections(grid(9, 1e-3)), 0);  // folded back above itself, no crossing
  Frame through = grid(9, 1e-3);
  for (Eigen::Index k = 0; k < through.points.rows(); ++k)  // the folded half dips below the plane near the fold
    if (through.points(k, 2) > 0.0 && through.points(k, 1) > 0.45 && through.points(k, 1) < 0.8)
      through.points(k, 2) = -0.01;
  EXPECT_GT(count_self_intersections(through), 0);
}

TEST(SelfIntersection, ANonManifoldSurfaceIsReported) {
  Frame f;
  f.points.resize(5, 3);
  f.points << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, -1, 0, 0, 0, 1;
  f.cells = {CellBlock{CellType::triangle, {0, 1, 2, 0, 1, 3, 0, 1, 4}}};  // three faces on edge 0–1
  EXPECT_EQ(count_self_intersections(f), -1);
}

}  // namespace
}  // namespace wl
