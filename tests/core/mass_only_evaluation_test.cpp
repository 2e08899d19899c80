// evaluate(kMass) alone forms the same M(q) as a full evaluation, without the
// force terms and auxiliaries; the kinetic energy of every metrics row, summed
// per element without a matrix, is ½ vᵀ M(q) v of that full evaluation.
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
    const double ke = model->kinetic_energy(0.0, q, v, mass);
    EXPECT_NEAR(ke, 0.5 * v.dot(full.mass * v), 1e-13 * ke) << name;
    EXPECT_GT(ke, 0.0);
    EXPECT_DOUBLE_EQ(model->Model::kinetic_energy(0.0, q, v, mass), 0.5 * v.dot(full.mass * v)) << name;
  }
}

}  // namespace
}  // namespace wl
