// The drape coefficient and fold count of a cloth over a disk pedestal
// (docs/models.md §3.11.6; scene key [measures] drape), defined as
// experiments/drape_measure.py defines them:
// - the cloth's cells (quads split along their 0–2 diagonal, triangles) are
//   projected on the plane z = const and rasterized: square pixels over the
//   bounding box of the frame's points, a pixel covered when its centre lies in
//   a projected triangle (edges included);
// - DC = (A_projected − A_pedestal)/(A_cloth − A_pedestal), A_cloth the flat
//   cloth's area: 1 for the flat cloth, 0 for one hanging straight down;
// - folds: the shadow's outer radius r(φ) about the pedestal's axis, the
//   largest distance of a covered pixel's centre in each 1° bin, smoothed by a
//   circular moving average over 5 bins; a fold is a local maximum (above the
//   bin before it, not below the bin after it) standing at least the
//   prominence above the lowest value reached on each side before the radius
//   first rises above it (within 90 bins).
#pragma once
#include <array>
#include <optional>
#include <string>
#include <vector>

#include "models/core/frame.h"
#include "models/scene/scene.h"

namespace wl {

struct DrapeGeometry {
  double centre_x_m = 0.0, centre_y_m = 0.0;  // the pedestal's axis
  double pedestal_radius_m = 0.0;
  double cloth_area_m2 = 0.0;  // the flat cloth's area
  double pixel_m = 1e-4;
  double fold_prominence_m = 5e-4;
};

// From the scene's pedestal (the first disk, cylinder or sphere obstacle), its
// woven cloth ((wefts − 1)·L × (warps − 1)·L) and [measures].
DrapeGeometry drape_geometry(const Scene& scene);

// The covered pixels of the projected cells; pixel (i, j) has its centre at
// (x0 + pixel·(½ + i), y0 + pixel·(½ + j)).
struct Shadow {
  double x0 = 0.0, y0 = 0.0, pixel = 0.0;
  int nx = 0, ny = 0;
  std::vector<char> covered;  // nx·ny, index i·ny + j
  double area_m2() const;
};

// The largest raster a frame may need: a frame whose points spread over more
// pixels than this (a run that blew up) is not measured.
inline constexpr double kMaxShadowPixels = 1e8;

// nullopt when the raster would exceed kMaxShadowPixels.
std::optional<Shadow> rasterize_shadow(const Frame& frame, double pixel_m);

// r(φ) in 1° bins (φ = atan2(y − c_y, x − c_x) in [0°, 360°)); 0 in an empty bin.
std::array<double, 360> outer_radius_per_degree(const Shadow& shadow, double centre_x_m, double centre_y_m);

// The folds of an outer radius r(φ) (1° bins): smoothed, then counted as above.
int count_folds(const std::array<double, 360>& outer_radius_m, double prominence_m);

struct DrapeMeasure {
  double time_s = 0.0;
  double coefficient = 0.0;
  double projected_area_m2 = 0.0;
  int folds = 0;
};

// nullopt when the frame's shadow is too large to rasterize (kMaxShadowPixels).
std::optional<DrapeMeasure> measure_drape(const Frame& frame, const DrapeGeometry& geometry);

}  // namespace wl
