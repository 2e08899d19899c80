// Warp/weft split of the stretch and bending energies (driver/energy_split.h):
// the parts sum to the term's energy, and a deformation of the warps alone
// (stretched and bent along u, the wefts straight and unstretched) has no weft
// part, and the other way round, in both models.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <random>

#include "driver/energy_split.h"
#include "models/core/term_model.h"
#include "models/fem/fem_model.h"
#include "models/model_factory.h"
#include "models/yarn/yarn_model.h"
#include "tests/support/test_scenes.h"

namespace wl {
namespace {

Scene scene() { return parse_scene(test::hanging_cloth_toml(6, 0.05), "test.toml"); }

std::map<std::string, double> by_quantity(const std::vector<EnergyPart>& parts) {
  std::map<std::string, double> m;
  for (const EnergyPart& p : parts) m[p.term + (p.warp ? " warp" : " weft")] = p.energy_J;
  return m;
}

// The position DoFs of every crossing (yarn) or vertex (continuum) and its rest position.
std::vector<int> position_dofs(const Model& model) {
  std::vector<int> out;
  if (const auto* yarn = dynamic_cast<const YarnModel*>(&model)) {
    for (int n = 0; n < yarn->grid().num_nodes(); ++n) out.push_back(yarn->grid().dofs(n).x);
  } else {
    for (int d = 0; d < model.num_dofs(); d += 3) out.push_back(d);
  }
  return out;
}

TEST(EnergySplit, WarpAndWeftPartsSumToEachTermsEnergy) {
  const Scene s = scene();
  std::mt19937 rng(3);
  std::normal_distribution<double> n01;
  for (const char* name : {"yarn", "fem"}) {
    SCOPED_TRACE(name);
    auto model = make_model(s, name);
    Vec q = model->initial_q();
    for (Eigen::Index i = 0; i < q.size(); ++i) q[i] += 5e-5 * n01(rng);
    const EnergySplit split(*model, s);
    const auto parts = by_quantity(split.parts(*model, q));
    const auto readings = dynamic_cast<TermModel&>(*model).term_readings(0.0, q, Vec::Zero(q.size()));
    const std::string prefix = std::string(name) == "fem" ? "fem-" : "";
    int checked = 0;
    for (const auto& r : readings) {
      if (r.name != prefix + "stretch" && r.name != prefix + "bending") continue;
      const double warp = parts.at(r.name + " warp"), weft = parts.at(r.name + " weft");
      EXPECT_GT(warp, 0.0) << r.name;
      EXPECT_GT(weft, 0.0) << r.name;
      EXPECT_NEAR(warp + weft, r.energy_J, 1e-12 * r.energy_J) << r.name;
      ++checked;
    }
    EXPECT_EQ(checked, 2);
  }
}

// Upright pose: material u runs along x, v along −z (docs/models.md §2.5). A
// deformation along one direction: stretch it by 1 % and roll it onto a
// cylinder of radius r whose axis is the other direction.
Vec deform_along(const Model& model, bool warp, double r) {
  Vec q = model.initial_q();
  for (int x : position_dofs(model)) {
    const Vec3 p = q.segment<3>(x);
    const double s = 1.01 * (warp ? p.x() : -p.z());  // arc length along the deformed direction
    const double along = r * std::sin(s / r), out = r * (1 - std::cos(s / r));
    if (warp) q.segment<3>(x) = Vec3(along, out, p.z());
    else q.segment<3>(x) = Vec3(p.x(), out, -along);
  }
  return q;
}

TEST(EnergySplit, ADeformationOfOneDirectionHasNoPartInTheOther) {
  const Scene s = scene();
  for (const char* name : {"yarn", "fem"}) {
    const std::string prefix = std::string(name) == "fem" ? "fem-" : "";
    auto model = make_model(s, name);
    const EnergySplit split(*model, s);
    for (bool warp : {true, false}) {
      SCOPED_TRACE(std::string(name) + (warp ? ": warps deformed" : ": wefts deformed"));
      const auto parts = by_quantity(split.parts(*model, deform_along(*model, warp, 4e-3)));
      const std::string on = warp ? " warp" : " weft", off = warp ? " weft" : " warp";
      for (const std::string& term : {prefix + "stretch", prefix + "bending"}) {
        EXPECT_GT(parts.at(term + on), 0.0) << term;
        EXPECT_LT(parts.at(term + off), 1e-12 * parts.at(term + on)) << term;
      }
    }
  }
}

}  // namespace
}  // namespace wl
