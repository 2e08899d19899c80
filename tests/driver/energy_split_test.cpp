// Warp/weft split of the stretch and bending energies (driver/energy_split.h):
// the parts sum to the term's energy, and a deformation of the warps alone
// (stretched and bent along u, the wefts straight and unstretched) has no weft
// part, and the other way round, in both models; with a tile law, the parts are
// the energies of its monomials of each direction (against the hand-computed law)
// and a deformation of one direction has no part in the other, inside the law's
// box and beyond it.
#include <gtest/gtest.h>

#include <unistd.h>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>

#include "driver/energy_split.h"
#include "models/core/term_model.h"
#include "models/fem/fem_model.h"
#include "models/model_factory.h"
#include "models/yarn/yarn_model.h"
#include "tests/fem/tile_law_test_data.h"
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

// A tile law (tests/fem/tile_law_test_data.h) with monomials of the warp alone, of the weft alone,
// a shear, a twist and couplings across the directions.
const std::string kTileLawTerms =
    "stretch_warp^2,0.6\nstretch_weft^2,0.4\nshear^2,0.3\nstretch_warp*stretch_weft,0.1\n"
    "curvature_warp^2,0.1\ncurvature_weft^2,0.08\ntwist^2,0.03\nstretch_warp*curvature_warp^2,-0.03\n"
    "curvature_warp*curvature_weft,0.02\n";

struct TileLawScene {
  std::filesystem::path law =
      std::filesystem::temp_directory_path() / ("wl_energy_split_law_" + std::to_string(::getpid()) + ".csv");
  Scene scene_ = scene();
  TileLawScene() {
    std::ofstream(law) << test::kTileLawHeader << kTileLawTerms;
    scene_.fem.tile_law = law.string();
  }
  ~TileLawScene() { std::filesystem::remove(law); }
};

// Stretched in plane by 1 % along the warp (x) and 0.5 % along the weft (−z), flat: inside the
// law's box, W = W₀(0.6 t_u² + 0.4 t_v² + 0.1 t_u t_v), t_u = 0.01/0.02, t_v = 0.005/0.02, so the
// warp part is 0.15 W₀A, the weft part 0.025 W₀A, the coupling 0.0125 W₀A is in neither, and
// the flat cloth has no curvature energy.
TEST(EnergySplit, TileLawPartsAreTheMonomialsOfEachDirection) {
  const TileLawScene t;
  auto model = make_model(t.scene_, "fem");
  Vec q = model->initial_q();
  for (int x : position_dofs(*model)) {
    q[x] *= 1.01;
    q[x + 2] *= 1.005;
  }
  const EnergySplit split(*model, t.scene_);
  const auto parts = by_quantity(split.parts(*model, q));
  double membrane = 0;
  for (const auto& r : dynamic_cast<TermModel&>(*model).term_readings(0.0, q, Vec::Zero(q.size())))
    if (r.name == "fem-tile-membrane") membrane = r.energy_J;
  const double warp = parts.at("fem-tile-membrane warp"), weft = parts.at("fem-tile-membrane weft");
  ASSERT_GT(weft, 0.0);
  EXPECT_NEAR(warp / weft, 0.15 / 0.025, 1e-9);
  EXPECT_NEAR((membrane - warp - weft) / warp, 0.0125 / 0.15, 1e-9);
  EXPECT_NEAR(parts.at("fem-tile-bending warp"), 0.0, 1e-12 * warp);
  EXPECT_NEAR(parts.at("fem-tile-bending weft"), 0.0, 1e-12 * warp);
}

TEST(EnergySplit, ATileLawDeformationOfOneDirectionHasNoPartInTheOther) {
  const TileLawScene t;
  auto model = make_model(t.scene_, "fem");
  const EnergySplit split(*model, t.scene_);
  for (bool warp : {true, false}) {
    SCOPED_TRACE(warp ? "warps deformed" : "wefts deformed");
    for (double r : {0.2, 4e-3}) {  // κ inside the law's box, and beyond it
      const auto parts = by_quantity(split.parts(*model, deform_along(*model, warp, r)));
      const std::string on = warp ? " warp" : " weft", off = warp ? " weft" : " warp";
      for (const std::string term : {"fem-tile-membrane", "fem-tile-bending"}) {
        EXPECT_GT(parts.at(term + on), 0.0) << term << " r " << r;
        EXPECT_LT(std::abs(parts.at(term + off)), 1e-12 * parts.at(term + on)) << term << " r " << r;
      }
    }
  }
}

}  // namespace
}  // namespace wl
