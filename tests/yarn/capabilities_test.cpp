// The capabilities beside the core Model and Term interfaces (docs/design.md
// §3.1, §3.2): which models and terms offer them, and the node speed of a
// model with sliding coordinates, which leaves the coordinates' rates out.
#include <gtest/gtest.h>

#include <type_traits>

#include "models/core/sliding_coordinates.h"
#include "models/fem/fem_model.h"
#include "models/knit/knit_model.h"
#include "models/yarn/frozen_input_reader.h"
#include "models/yarn/yarn_model.h"

namespace wl {
namespace {

Scene hanging_wind() { return load_scene(WEAVELAB_SOURCE_DIR "/experiments/scenes/hanging_wind.toml"); }

const Term& term_named(const TermModel& model, const std::string& name) {
  for (const auto& t : model.terms())
    if (t->name() == name) return *t;
  throw std::runtime_error("no term " + name);
}

TEST(Capabilities, TheYarnLevelModelsOfferSlidingCoordinatesAndTheFemDoesNot) {
  static_assert(std::is_base_of_v<SlidingCoordinates, KnitModel>);
  const Scene scene = hanging_wind();
  YarnModel yarn(scene);
  FemModel fem(scene);
  EXPECT_NE(sliding_coordinates(yarn), nullptr);
  EXPECT_NE(sliding_coordinates(static_cast<Model&>(yarn)), nullptr);
  EXPECT_EQ(sliding_coordinates(static_cast<const Model&>(fem)), nullptr);
}

TEST(Capabilities, NodeSpeedOfTheYarnModelLeavesTheSlidingRatesOut) {
  YarnModel yarn(hanging_wind());
  Vec v = Vec::Zero(yarn.num_dofs());
  int sliding = 0;
  for (int k = 0; k < yarn.grid().num_nodes(); ++k) {
    const NodeDofs& d = yarn.grid().dofs(k);
    for (int c : {d.u, d.v})
      if (is_dof(c)) v[c] = 100.0, ++sliding;
  }
  ASSERT_GT(sliding, 0);
  EXPECT_EQ(max_node_speed(yarn, v), 0.0);
  const int node = yarn.grid().node(3, 2);
  v.segment<3>(yarn.grid().dofs(node).x) = Vec3(0.0, 3.0, 4.0);
  EXPECT_EQ(max_node_speed(yarn, v), 5.0);
}

TEST(Capabilities, NodeSpeedOfTheFemReadsConsecutiveTriplets) {
  FemModel fem(hanging_wind());
  Vec v = Vec::Zero(fem.num_dofs());
  v.segment<3>(3 * 2) = Vec3(3.0, 0.0, 4.0);
  v[3 * 5 + 1] = -2.0;
  EXPECT_EQ(max_node_speed(fem, v), 5.0);
}

TEST(Capabilities, OnlyTheReadersOfFrozenInputsAndTheSlidingInertiaOfferTheirs) {
  const Scene scene = hanging_wind();
  YarnModel yarn(scene);
  EXPECT_NE(frozen_input_reader(term_named(yarn, "friction")), nullptr);
  EXPECT_NE(frozen_input_reader(term_named(yarn, "shear")), nullptr);
  EXPECT_EQ(frozen_input_reader(term_named(yarn, "stretch")), nullptr);
  EXPECT_EQ(frozen_input_reader(term_named(yarn, "inertia")), nullptr);
  EXPECT_NE(position_dependent_mass(term_named(yarn, "inertia")), nullptr);
  EXPECT_EQ(position_dependent_mass(term_named(yarn, "stretch")), nullptr);
  FemModel fem(scene);
  EXPECT_EQ(position_dependent_mass(term_named(fem, "fem-mass")), nullptr);
}

}  // namespace
}  // namespace wl
