#include "models/knit/knit_scene_error.h"

#include <set>

#include "models/scene/format_number.h"

namespace wl {

std::string knit_geometry_values(const Scene& scene) {
  using scene_detail::format_number;
  const KnitPattern& k = *scene.knit;
  std::string values = "cloth.spacing_m = " + format_number(scene.spacing_m) +
                       ", cloth.pattern.course_spacing_m = " + format_number(k.course_spacing_m) +
                       ", cloth.radius_m = " + format_number(scene.radius_m) +
                       ", knit.stitch_length_stiffness_N = " + format_number(k.stitch_length_stiffness_N) +
                       ", knit.roll_stiffness_N = " + format_number(k.roll_stiffness_N) +
                       ", knit.compression_stiffness_N_per_m = " + format_number(k.compression_stiffness_N_per_m);
  const std::set<std::string> types(scene.warp_yarn_types.begin(), scene.warp_yarn_types.end());
  for (const std::string& name : types) {
    const YarnType& y = scene.yarn_types.at(name);
    const std::string key = "yarn_types." + name + ".";
    values += ", " + key + "stretch_modulus_Pa = " + format_number(y.stretch_modulus_Pa) + ", " + key +
              "bending_modulus_Pa = " + format_number(y.bending_modulus_Pa);
  }
  return values;
}

void refuse_knit_scene(const Scene& scene, const std::string& expected, const std::string& what_failed) {
  const auto kind = scene.key_lines.find("cloth.pattern.kind");
  const int line = kind != scene.key_lines.end() ? kind->second : 1;
  throw SceneError(scene.source, line, "cloth.pattern", knit_geometry_values(scene), expected + ": " + what_failed);
}

}  // namespace wl
