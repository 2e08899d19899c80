// A model of the 6×6 hanging cloth in wind after its scene's be-linear steps
// (history set, moving), for tests that need a state away from rest.
#pragma once
#include <gtest/gtest.h>

#include <memory>
#include <string>

#include "integrators/integrator.h"
#include "models/model_factory.h"
#include "tests/support/test_scenes.h"

namespace wl::test {

// `extra_toml` is appended to the scene (inside its [time] table); q and v
// receive the state reached after 0.02 s of 1 ms steps.
inline std::unique_ptr<Model> advanced_model(const std::string& model_name, const std::string& extra_toml, Vec& q,
                                             Vec& v) {
  const Scene scene = parse_scene(hanging_cloth_toml(6, 0.02) + extra_toml, "advanced.toml");
  auto model = make_model(scene, model_name);
  auto integrator = make_integrator("be-linear");
  IntegratorOptions opt;
  opt.dt = 1e-3;
  integrator->initialize(*model, 0.0, model->initial_q(), model->initial_v(), opt);
  EXPECT_EQ(integrator->advance_to(scene.duration_s).outcome, Outcome::ok);
  q = integrator->q();
  v = integrator->v();
  return model;
}

}  // namespace wl::test
