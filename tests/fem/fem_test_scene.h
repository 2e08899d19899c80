// Small scenes for the FEM tests.
#pragma once
#include "models/scene/scene.h"

namespace wl::test {

inline Scene fem_scene(int wefts, int warps, Scene::Pose pose = Scene::Pose::flat) {
  Scene s;
  s.source = "test";
  s.wefts = wefts;
  s.warps = warps;
  s.spacing_m = 1e-3;
  s.radius_m = 4e-4;
  s.yarn_types["default"] = YarnType{};
  s.pose = pose;
  s.height_m = 0.1;
  s.gravity_m_per_s2 = {0, 0, 0};
  s.terms.wind = false;
  return s;
}

}  // namespace wl::test
