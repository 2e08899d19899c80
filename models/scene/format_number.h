// How scene errors quote a number: the shortest digits that read back to the
// same double, in fixed notation for ordinary magnitudes (1e-4 ≤ |x| < 1e7),
// e.g. "0.0002", "1e-12". Shared by the scene reader and the models that
// refuse a scene themselves (models/knit/knit_scene_error.h).
#pragma once
#include <string>

namespace wl::scene_detail {

std::string format_number(double x);

}  // namespace wl::scene_detail
