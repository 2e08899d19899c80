#include "models/scene/measure_reader.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace wl::scene_detail {
namespace {

// The pedestal a drape is measured over: the first disk, cylinder or sphere
// obstacle (docs/models.md §3.11.6); nullptr when there is none.
const ObstacleSpec* pedestal(const Scene& s) {
  for (const ObstacleSpec& o : s.obstacles)
    if (o.shape == ObstacleSpec::Shape::disk || o.shape == ObstacleSpec::Shape::cylinder ||
        o.shape == ObstacleSpec::Shape::sphere)
      return &o;
  return nullptr;
}

// A drape is measured in the plane z = const under a woven cloth, over a
// pedestal whose axis is z.
void check_drape_scene(TableReader& m, const Scene& s) {
  if (s.knit)
    m.fail_key("drape", "false in a knit scene (the drape coefficient needs a woven cloth's flat area)", "true");
  const ObstacleSpec* p = pedestal(s);
  if (!p)
    m.fail_key("drape", "false in a scene without a pedestal (a disk, cylinder or sphere in [[obstacles]])", "true");
  if (p->rotation_deg[0] != 0.0 || p->rotation_deg[1] != 0.0)
    m.fail_key("drape",
               "false over a pedestal turned about x or y (obstacle on line " + std::to_string(p->line) +
                   ": the drape is projected on the plane z = const)",
               "true");
}

}  // namespace

void read_measures(TableReader& top, Scene& s) {
  auto m = top.subtable("measures");
  if (!m) return;
  MeasureSettings& ms = s.measures;
  ms.line = m->line();
  m->read_bool("drape", ms.drape);
  // A pixel fine enough to resolve a yarn spacing, coarse enough for at most 8192 pixels along the flat cloth.
  const double side = std::max(s.wefts - 1, s.warps - 1) * s.spacing_m;
  const double finest = side / 8192.0;
  const std::string pixel = "a number ≥ cloth side / 8192 (= " + format_number(finest) +
                            ") and ≤ cloth.spacing_m (= " + format_number(s.spacing_m) + ") (m)";
  m->read_number("drape_pixel_m", ms.drape_pixel_m, pixel, [&](double x) { return x >= finest && x <= s.spacing_m; });
  m->read_number("fold_prominence_m", ms.fold_prominence_m, "a finite number > 0 (m)",
                 [](double x) { return std::isfinite(x) && x > 0.0; });
  m->finish();
  if (!ms.drape) {
    for (const char* key : {"drape_pixel_m", "fold_prominence_m"})
      if (m->table().get(key)) m->fail_key(key, "no " + std::string(key) + " without drape = true", "");
    return;
  }
  if (!(ms.drape_pixel_m >= finest && ms.drape_pixel_m <= s.spacing_m))  // the default against this cloth
    m->fail_key("drape_pixel_m", pixel, format_number(ms.drape_pixel_m));
  check_drape_scene(*m, s);
}

}  // namespace wl::scene_detail
