// evaluate(kMass) alone (the kinetic energy of every metrics row) forms the
// same M(q) as a full evaluation, without the force terms and auxiliaries.
#include <gtest/gtest.h>

#include "models/model_factory.h"
#include "models/scene/scene.h"

namespace wl {
namespace {

TEST(MassOnlyEvaluation, SameMassAsAFullEvaluation) {
  const Scene scene = load_scene(std::string(WEAVELAB_SOURCE_DIR) + "/experiments/scenes/hanging_wind.toml");
  for (const std::string name : {"yarn", "fem"}) {
    auto model = make_model(scene, name);
    srand(11);
    const Vec q = model->initial_q() + 1e-4 * Vec::Random(model->num_dofs());
    const Vec v = 1e-2 * Vec::Random(model->num_dofs());
    Evaluation full, mass;
    model->evaluate(0.0, q, v, kForce | kDfdq | kDfdv | kMass, full);
    model->evaluate(0.0, q, v, kMass, mass);
    ASSERT_GT(full.mass.norm(), 0.0);
    EXPECT_EQ((full.mass - mass.mass).norm(), 0.0) << name;
    const double ke = kinetic_energy(*model, 0.0, q, v, mass);
    EXPECT_DOUBLE_EQ(ke, 0.5 * v.dot(full.mass * v)) << name;
    EXPECT_GT(ke, 0.0);
  }
}

}  // namespace
}  // namespace wl
