#include "driver/drape_measure.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace wl {
namespace {

using Point2 = std::array<double, 2>;

// The triangles of the cloth's surface cells: triangles, and quads split into (0, 1, 2) and (0, 2, 3).
std::vector<std::array<int, 3>> surface_triangles(const Frame& frame) {
  std::vector<std::array<int, 3>> tris;
  for (const CellBlock& block : frame.cells) {
    const int k = block.nodes_per_cell();
    if (block.type == CellType::line) continue;
    for (int c = 0; c < block.size(); ++c) {
      const int* n = &block.connectivity[static_cast<size_t>(c) * k];
      tris.push_back({n[0], n[1], n[2]});
      if (block.type == CellType::quad) tris.push_back({n[0], n[2], n[3]});
    }
  }
  return tris;
}

// Marks the pixels whose centres lie in triangle (a, b, c) (barycentrics ≥ 0, edges included).
void cover_triangle(Shadow& s, const std::vector<double>& gx, const std::vector<double>& gy, Point2 a, Point2 b,
                    Point2 c) {
  const double x_lo = std::min({a[0], b[0], c[0]}), x_hi = std::max({a[0], b[0], c[0]});
  const double y_lo = std::min({a[1], b[1], c[1]}), y_hi = std::max({a[1], b[1], c[1]});
  const auto i0 = std::lower_bound(gx.begin(), gx.end(), x_lo) - gx.begin();
  const auto i1 = std::upper_bound(gx.begin(), gx.end(), x_hi) - gx.begin();
  const auto j0 = std::lower_bound(gy.begin(), gy.end(), y_lo) - gy.begin();
  const auto j1 = std::upper_bound(gy.begin(), gy.end(), y_hi) - gy.begin();
  if (i0 >= i1 || j0 >= j1) return;
  const double det = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
  if (det == 0.0) return;
  for (auto i = i0; i < i1; ++i)
    for (auto j = j0; j < j1; ++j) {
      const double X = gx[i], Y = gy[j];
      const double l1 = ((X - a[0]) * (c[1] - a[1]) - (Y - a[1]) * (c[0] - a[0])) / det;
      const double l2 = ((b[0] - a[0]) * (Y - a[1]) - (b[1] - a[1]) * (X - a[0])) / det;
      if (l1 >= 0.0 && l2 >= 0.0 && l1 + l2 <= 1.0) s.covered[static_cast<size_t>(i) * s.ny + j] = 1;
    }
}

}  // namespace

double Shadow::area_m2() const {
  return static_cast<double>(std::count(covered.begin(), covered.end(), char(1))) * pixel * pixel;
}

DrapeGeometry drape_geometry(const Scene& scene) {
  DrapeGeometry g;
  for (const ObstacleSpec& o : scene.obstacles) {
    if (o.shape != ObstacleSpec::Shape::disk && o.shape != ObstacleSpec::Shape::cylinder &&
        o.shape != ObstacleSpec::Shape::sphere)
      continue;
    g.centre_x_m = o.center_m[0];
    g.centre_y_m = o.center_m[1];
    g.pedestal_radius_m = o.radius_m;
    break;
  }
  const double side_u = (scene.wefts - 1) * scene.spacing_m, side_v = (scene.warps - 1) * scene.spacing_m;
  g.cloth_area_m2 = side_u * side_v;
  g.pixel_m = scene.measures.drape_pixel_m;
  g.fold_prominence_m = scene.measures.fold_prominence_m;
  return g;
}

std::optional<Shadow> rasterize_shadow(const Frame& frame, double pixel_m) {
  Shadow s;
  s.pixel = pixel_m;
  if (frame.points.rows() == 0) return s;
  const double x_lo = frame.points.col(0).minCoeff(), x_hi = frame.points.col(0).maxCoeff();
  const double y_lo = frame.points.col(1).minCoeff(), y_hi = frame.points.col(1).maxCoeff();
  const double nx = std::ceil((x_hi - x_lo) / pixel_m), ny = std::ceil((y_hi - y_lo) / pixel_m);
  if (!(nx * ny <= kMaxShadowPixels && nx <= kMaxShadowPixels && ny <= kMaxShadowPixels)) return std::nullopt;
  s.x0 = x_lo;
  s.y0 = y_lo;
  s.nx = static_cast<int>(nx);
  s.ny = static_cast<int>(ny);
  s.covered.assign(static_cast<size_t>(s.nx) * s.ny, 0);
  std::vector<double> gx(s.nx), gy(s.ny);
  for (int i = 0; i < s.nx; ++i) gx[i] = x_lo + pixel_m * (0.5 + i);
  for (int j = 0; j < s.ny; ++j) gy[j] = y_lo + pixel_m * (0.5 + j);
  auto xy = [&](int n) { return Point2{frame.points(n, 0), frame.points(n, 1)}; };
  for (const auto& t : surface_triangles(frame)) cover_triangle(s, gx, gy, xy(t[0]), xy(t[1]), xy(t[2]));
  return s;
}

std::array<double, 360> outer_radius_per_degree(const Shadow& s, double centre_x_m, double centre_y_m) {
  std::array<double, 360> radius{};
  for (int i = 0; i < s.nx; ++i)
    for (int j = 0; j < s.ny; ++j) {
      if (!s.covered[static_cast<size_t>(i) * s.ny + j]) continue;
      const double dx = s.x0 + s.pixel * (0.5 + i) - centre_x_m, dy = s.y0 + s.pixel * (0.5 + j) - centre_y_m;
      double degrees = std::fmod(std::atan2(dy, dx) * (180.0 / std::numbers::pi), 360.0);
      if (degrees < 0.0) degrees += 360.0;
      const int bin = static_cast<int>(degrees) % 360;
      radius[bin] = std::max(radius[bin], std::hypot(dx, dy));
    }
  return radius;
}

int count_folds(const std::array<double, 360>& r, double prominence_m) {
  constexpr int n = 360, window = 90;
  auto at = [](const std::array<double, n>& a, int k) { return a[((k % n) + n) % n]; };
  std::array<double, n> smooth{};
  for (int k = 0; k < n; ++k) {
    double sum = 0.0;
    for (int d = -2; d <= 2; ++d) sum += 0.2 * at(r, k + d);
    smooth[k] = sum;
  }
  // The lowest value on one side (step ±1) before the radius first rises above the peak at k.
  auto lowest_beside = [&](int k, int step) {
    double lowest = smooth[k];
    for (int d = 1; d < window && at(smooth, k + step * d) <= smooth[k]; ++d)
      lowest = std::min(lowest, at(smooth, k + step * d));
    return lowest;
  };
  int folds = 0;
  for (int k = 0; k < n; ++k) {
    if (smooth[k] <= at(smooth, k - 1) || smooth[k] < at(smooth, k + 1)) continue;
    if (smooth[k] - std::max(lowest_beside(k, -1), lowest_beside(k, +1)) >= prominence_m) ++folds;
  }
  return folds;
}

std::optional<DrapeMeasure> measure_drape(const Frame& frame, const DrapeGeometry& g) {
  const std::optional<Shadow> shadow = rasterize_shadow(frame, g.pixel_m);
  if (!shadow) return std::nullopt;
  const double pedestal_area = std::numbers::pi * g.pedestal_radius_m * g.pedestal_radius_m;
  DrapeMeasure m;
  m.time_s = frame.time;
  m.projected_area_m2 = shadow->area_m2();
  m.coefficient = (m.projected_area_m2 - pedestal_area) / (g.cloth_area_m2 - pedestal_area);
  m.folds = count_folds(outer_radius_per_degree(*shadow, g.centre_x_m, g.centre_y_m), g.fold_prominence_m);
  return m;
}

}  // namespace wl
