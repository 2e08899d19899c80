// The drape coefficient and fold count (driver/drape_measure.h, docs/models.md
// §3.11.6) on shapes whose answers are known: a flat square and a flat disk
// (coefficient 1), a cloth hanging straight down from the pedestal's rim
// (coefficient 0), and flat stars r(φ) = R₀ + A cos(Nφ) (N folds when the
// peak-to-trough height 2A exceeds the prominence, none otherwise).
#include "driver/drape_measure.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace wl {
namespace {

constexpr double kPi = std::numbers::pi;

// An n×n grid of quads of side L at height z, its corner at the origin (a woven cloth's frame).
Frame flat_square(int nodes, double L) {
  Frame f;
  f.points.resize(nodes * nodes, 3);
  for (int i = 0; i < nodes; ++i)
    for (int j = 0; j < nodes; ++j) f.points.row(i * nodes + j) << i * L, j * L, 0.001;
  CellBlock quads{CellType::quad, {}};
  for (int i = 0; i + 1 < nodes; ++i)
    for (int j = 0; j + 1 < nodes; ++j)
      quads.connectivity.insert(quads.connectivity.end(),
                                {i * nodes + j, (i + 1) * nodes + j, (i + 1) * nodes + j + 1, i * nodes + j + 1});
  f.cells = {CellBlock{CellType::line, {0, 1}}, quads};  // line cells (yarns) are not surface
  return f;
}

// A fan of triangles about (cx, cy) whose rim is r(φ_k) at `sides` equally spaced angles, at height z.
template <class Radius>
Frame flat_fan(double cx, double cy, int sides, Radius r, double z = 0.0) {
  Frame f;
  f.points.resize(sides + 1, 3);
  f.points.row(0) << cx, cy, z;
  CellBlock tris{CellType::triangle, {}};
  for (int k = 0; k < sides; ++k) {
    const double phi = 2.0 * kPi * k / sides;
    f.points.row(k + 1) << cx + r(phi) * std::cos(phi), cy + r(phi) * std::sin(phi), z;
    tris.connectivity.insert(tris.connectivity.end(), {0, k + 1, (k + 1) % sides + 1});
  }
  f.cells = {tris};
  return f;
}

// Area of the fan's polygon (shoelace).
double polygon_area(const Frame& fan) {
  double twice = 0.0;
  const int n = static_cast<int>(fan.points.rows()) - 1;
  for (int k = 1; k <= n; ++k) {
    const int next = k % n + 1;
    twice += fan.points(k, 0) * fan.points(next, 1) - fan.points(next, 0) * fan.points(k, 1);
  }
  return 0.5 * std::abs(twice);
}

// A pixel is misjudged only when its centre lies within half its diagonal of
// the outline, so the shadow's area is off by at most the outline's length
// times the pixel's diagonal: the tolerance of the coefficient.
double coefficient_bound(double perimeter, const DrapeGeometry& g) {
  return perimeter * g.pixel_m * std::sqrt(2.0) / (g.cloth_area_m2 - kPi * g.pedestal_radius_m * g.pedestal_radius_m);
}

TEST(DrapeMeasure, FlatSquareClothCoversExactlyItsAreaAndShowsFourCorners) {
  const double L = 1e-3;
  const Frame f = flat_square(33, L);  // 32 mm square, as cusick_drape_33.toml
  DrapeGeometry g;
  g.centre_x_m = g.centre_y_m = 0.016;
  g.pedestal_radius_m = 0.008;
  g.cloth_area_m2 = 32 * L * 32 * L;
  // Pixel centres sit half a pixel inside the square's edges: every one of the 320 × 320 is covered, none else.
  const auto shadow = rasterize_shadow(f, g.pixel_m);
  ASSERT_TRUE(shadow);
  EXPECT_EQ(std::count(shadow->covered.begin(), shadow->covered.end(), char(1)), 320 * 320);
  const auto m = measure_drape(f, g);
  ASSERT_TRUE(m);
  EXPECT_NEAR(m->coefficient, 1.0, 1e-12);
  EXPECT_EQ(m->folds, 4);
}

TEST(DrapeMeasure, FlatDiskClothHasCoefficientOne) {
  DrapeGeometry g;
  g.centre_x_m = 0.03;
  g.centre_y_m = 0.02;
  g.pedestal_radius_m = 0.008;
  const double R = 0.02;
  const Frame f = flat_fan(g.centre_x_m, g.centre_y_m, 720, [&](double) { return R; });
  g.cloth_area_m2 = polygon_area(f);
  const auto m = measure_drape(f, g);
  ASSERT_TRUE(m);
  EXPECT_NEAR(m->coefficient, 1.0, coefficient_bound(2 * kPi * R, g));
  EXPECT_EQ(m->folds, 0);  // a circle has no fold
}

TEST(DrapeMeasure, ClothHangingStraightDownFromThePedestalHasCoefficientZero) {
  DrapeGeometry g;
  g.centre_x_m = g.centre_y_m = 0.016;
  g.pedestal_radius_m = 0.008;
  g.cloth_area_m2 = 0.032 * 0.032;
  const int sides = 720;
  // The top on the pedestal (a fan whose polygon has the pedestal's area), then a vertical skirt below its rim.
  const double r = g.pedestal_radius_m * std::sqrt(2 * kPi / (sides * std::sin(2 * kPi / sides)));
  Frame f = flat_fan(g.centre_x_m, g.centre_y_m, sides, [&](double) { return r; });
  const int top = static_cast<int>(f.points.rows());
  f.points.conservativeResize(top + sides, 3);
  CellBlock skirt{CellType::quad, {}};
  for (int k = 0; k < sides; ++k) {
    f.points.row(top + k) = f.points.row(k + 1);
    f.points(top + k, 2) = -0.012;
    const int next = (k + 1) % sides;
    skirt.connectivity.insert(skirt.connectivity.end(), {k + 1, next + 1, top + next, top + k});
  }
  f.cells.push_back(skirt);
  const auto m = measure_drape(f, g);
  ASSERT_TRUE(m);
  EXPECT_NEAR(m->coefficient, 0.0, coefficient_bound(2 * kPi * r, g));
}

// r(φ) = R₀ + A cos(N(φ − φ₀)) about the pedestal's axis. φ₀ = 7.3° keeps the peaks off the pixel
// grid's axes and diagonals: a peak there is rasterized into two equal maxima with a shallow dip
// between them, which the definition (as experiments/drape_measure.py's) counts as two folds.
int star_folds(int N, double amplitude, double prominence = 5e-4) {
  DrapeGeometry g;
  g.centre_x_m = g.centre_y_m = 0.032;
  g.pedestal_radius_m = 0.016;
  g.cloth_area_m2 = 0.064 * 0.064;
  g.fold_prominence_m = prominence;
  const Frame f = flat_fan(g.centre_x_m, g.centre_y_m, 1440,
                           [&](double phi) { return 0.024 + amplitude * std::cos(N * (phi - 7.3 * kPi / 180.0)); });
  const auto m = measure_drape(f, g);
  return m ? m->folds : -1;
}

TEST(DrapeMeasure, StarWithNSymmetricFoldsCountsN) {
  for (int N : {3, 5, 6, 8, 12, 15, 20}) EXPECT_EQ(star_folds(N, 0.002), N) << "N = " << N;
}

TEST(DrapeMeasure, FoldsMustStandTheProminenceAboveTheirTroughs) {
  // Peak to trough 2A, less 2 % for the 5° smoothing at N = 8, give or take a pixel's diagonal (0.14 mm)
  // for the rasterized outline: 0.3 mm stays below the default 0.5 mm, 0.8 mm above it and below 1 mm.
  EXPECT_EQ(star_folds(8, 0.00015), 0);
  EXPECT_EQ(star_folds(8, 0.0004), 8);
  EXPECT_EQ(star_folds(8, 0.0004, 1e-3), 0);
}

TEST(DrapeMeasure, CountFoldsOnAGivenRadius) {
  std::array<double, 360> r{};
  for (int k = 0; k < 360; ++k) r[k] = 0.02;
  EXPECT_EQ(count_folds(r, 5e-4), 0);
  // One bump of 2 mm, 20° wide, across the 0°/360° seam: one fold.
  for (int k = -10; k <= 10; ++k) r[(k + 360) % 360] = 0.02 + 0.002 * std::cos(kPi * k / 20.0);
  EXPECT_EQ(count_folds(r, 5e-4), 1);
  // A second bump, 1 mm high, opposite: two folds at 0.5 mm, one at 1.5 mm.
  for (int k = 170; k <= 190; ++k) r[k] = 0.02 + 0.001 * std::cos(kPi * (k - 180) / 20.0);
  EXPECT_EQ(count_folds(r, 5e-4), 2);
  EXPECT_EQ(count_folds(r, 1.5e-3), 1);
}

TEST(DrapeMeasure, GeometryFromTheScene) {
  const Scene s = parse_scene(
      "[cloth]\nwarps = 9\nwefts = 5\nspacing_m = 0.002\nradius_m = 0.0005\n"
      "[[obstacles]]\nshape = \"box\"\ncenter_m = [0, 0, -1]\nhalf_extents_m = [1, 1, 0.5]\n"
      "[[obstacles]]\nshape = \"disk\"\ncenter_m = [0.004, 0.008, -0.001]\nradius_m = 0.003\nthickness_m = 0.002\n"
      "[measures]\ndrape = true\ndrape_pixel_m = 0.0002\nfold_prominence_m = 0.001\n",
      "drape.toml");
  const DrapeGeometry g = drape_geometry(s);
  EXPECT_EQ(g.centre_x_m, 0.004);
  EXPECT_EQ(g.centre_y_m, 0.008);
  EXPECT_EQ(g.pedestal_radius_m, 0.003);
  EXPECT_DOUBLE_EQ(g.cloth_area_m2, (4 * 0.002) * (8 * 0.002));
  EXPECT_EQ(g.pixel_m, 0.0002);
  EXPECT_EQ(g.fold_prominence_m, 0.001);
}

TEST(DrapeMeasure, ABlownUpFrameIsNotMeasured) {
  Frame f = flat_square(3, 1e-3);
  f.points(8, 0) = 1e6;  // a node far away: more than kMaxShadowPixels pixels
  DrapeGeometry g;
  g.cloth_area_m2 = 4e-6;
  EXPECT_FALSE(measure_drape(f, g));
}

}  // namespace
}  // namespace wl
