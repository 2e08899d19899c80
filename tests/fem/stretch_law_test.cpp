// The stretch law's warp–weft coupling and quartic stiffening (docs/models.md §6.3.1):
// derivatives through the FD checker, the energy against its hand-written form, the
// convexity bound, and the keys of the scene and the parameter file.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <random>

#include "models/fem/deformation_gradient.h"
#include "models/fem/fem_material.h"
#include "models/fem/terms/warp_weft_stretch.h"
#include "models/scene/scene.h"
#include "tests/support/fd_check.h"

namespace wl {
namespace {

const Vec2 kUv0(0.001, 0.002), kUv1(0.013, 0.001), kUv2(0.004, 0.011);
const StretchLaw kLaw{120.0, 45.0, 50.0, 900.0, 3000.0, 2000.0};  // k_c² = 2500 < k_u k_v = 5400

// Near rest, moderately and far from rest: stretched and compressed along both columns.
std::vector<test::LocalState> states() {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> d(-1.0, 1.0);
  std::vector<test::LocalState> out;
  for (double amp : {1e-4, 2e-3, 6e-3}) {
    test::LocalState s{{kUv0.x(), kUv0.y(), 0.5, kUv1.x(), kUv1.y(), 0.5, kUv2.x(), kUv2.y(), 0.5},
                       std::vector<double>(9, 0.0)};
    for (double& x : s.q) x += amp * d(rng);
    out.push_back(s);
  }
  return out;
}

std::unique_ptr<Term> stretch_term(const StretchLaw& law) {
  auto t = std::make_unique<WarpWeftStretchTerm>(law);
  t->add({0, 1, 2, 3, 4, 5, 6, 7, 8}, triangle_rest(kUv0, kUv1, kUv2));
  return t;
}

TEST(StretchLaw, ForceAndJacobianMatchFiniteDifferences) {
  const auto r = test::check_element(*stretch_term(kLaw), 0, states());
  EXPECT_TRUE(r.ok) << r.detail;
}

TEST(StretchLaw, ParameterDerivativesMatchFiniteDifferences) {
  double StretchLaw::*fields[] = {&StretchLaw::k_u, &StretchLaw::k_v, &StretchLaw::k_c,
                                  &StretchLaw::q_u, &StretchLaw::q_v, &StretchLaw::q_a};
  const std::vector<std::string> keys{kFemWarpStretch,        kFemWeftStretch,        kFemStretchCoupling,
                                      kFemWarpStretchQuartic, kFemWeftStretchQuartic, kFemArealStretchQuartic};
  EXPECT_EQ(stretch_term(kLaw)->parameter_keys(), keys);
  for (int k = 0; k < 6; ++k) {
    auto make = [&](double p) {
      StretchLaw law = kLaw;
      law.*fields[k] = p;
      return stretch_term(law);
    };
    const auto r = test::check_parameter_derivative(make, kLaw.*fields[k], k, 0, states());
    EXPECT_TRUE(r.ok) << keys[k] << ": " << r.detail;
  }
}

TEST(StretchLaw, EnergyOfAStretchAlongBothColumns) {
  // Unit right triangle, w_u = (1.1, 0, 0), w_v = (0, 0.95, 0): ε_u = 0.1, ε_v = −0.05 and
  // V = ½(½·120·0.01 + ½·45·0.0025 + 50·(−0.005) + ¼·900·10⁻⁴ + ¼·3000·6.25·10⁻⁶ + ¼·2000·0.05⁴).
  auto t = std::make_unique<WarpWeftStretchTerm>(kLaw);
  t->add({0, 1, 2, 3, 4, 5, 6, 7, 8}, triangle_rest(Vec2(0, 0), Vec2(1, 0), Vec2(0, 1)));
  const double q[9] = {0, 0, 0, 1.1, 0, 0, 0, 0.95, 0};
  EXPECT_NEAR(t->energy(0, q), 0.5 * (0.6 + 0.05625 - 0.25 + 0.0225 + 0.0046875 + 0.003125), 1e-14);
  // and the linear law (no extras) keeps its two keys
  EXPECT_EQ(WarpWeftStretchTerm(120.0, 45.0).parameter_keys().size(), 2u);
}

TEST(StretchLaw, CouplingBeyondTheConvexityBoundIsRefused) {
  EXPECT_THROW(WarpWeftStretchTerm(StretchLaw{120.0, 45.0, 73.5}), std::invalid_argument);  // 73.5² > 5400
  EXPECT_THROW(WarpWeftStretchTerm(StretchLaw{120.0, 45.0, -73.5}), std::invalid_argument);
  EXPECT_THROW(WarpWeftStretchTerm(StretchLaw{120.0, 45.0, 0, -1.0}), std::invalid_argument);
  EXPECT_NO_THROW(WarpWeftStretchTerm(StretchLaw{120.0, 45.0, 73.4}));
}

TEST(StretchLaw, SceneAndParameterFileKeys) {
  const Scene s = parse_scene(
      "[fem]\nwarp_stretch_N_per_m = 100\nweft_stretch_N_per_m = 64\nstretch_coupling_N_per_m = 30\n"
      "warp_stretch_quartic_N_per_m = 500\nweft_stretch_quartic_N_per_m = 700\nareal_stretch_quartic_N_per_m = 900\n",
      "s.toml");
  const FemMaterial m = fem_material(s);
  EXPECT_EQ(m.stretch_coupling_N_per_m, 30.0);
  EXPECT_EQ(m.warp_stretch_quartic_N_per_m, 500.0);
  EXPECT_EQ(m.weft_stretch_quartic_N_per_m, 700.0);
  EXPECT_EQ(m.areal_stretch_quartic_N_per_m, 900.0);
  EXPECT_EQ(fem_material(parse_scene("", "s.toml")).stretch_coupling_N_per_m, 0.0);  // off by default
  // the scene's coupling beyond √(k_u k_v) = 80: file, line, key, value and the bound
  try {
    (void)fem_material(parse_scene(
        "[fem]\nwarp_stretch_N_per_m = 100\nweft_stretch_N_per_m = 64\n\nstretch_coupling_N_per_m = 80\n", "s.toml"));
    ADD_FAILURE() << "no error";
  } catch (const FemParameterError& e) {
    const std::string w = e.what();
    EXPECT_EQ(w.rfind("s.toml:5: key 'stretch_coupling_N_per_m': got 80, expected", 0), 0u) << w;
    EXPECT_NE(w.find("√(k_u·k_v) = 80"), std::string::npos) << w;
  }
  // a parameter file's coupling beyond the bound is located in the file
  const std::string file = ::testing::TempDir() + "stretch_law_cal.toml";
  {
    std::ofstream f(file);
    f << "warp_stretch_N_per_m = 100\nweft_stretch_N_per_m = 64\nstretch_coupling_N_per_m = 81\n";
  }
  try {
    (void)fem_material(parse_scene("[fem]\nparameter_file = \"" + file + "\"\n", "s.toml"));
    ADD_FAILURE() << "no error";
  } catch (const FemParameterError& e) {
    EXPECT_EQ(std::string(e.what()).rfind(file + ":3: key 'stretch_coupling_N_per_m': got 81", 0), 0u) << e.what();
  }
  // the parameter file's keys, and their round trip
  FemMaterial base;
  base.warp_stretch_N_per_m = base.weft_stretch_N_per_m = 10.0;
  const FemMaterial p =
      parse_fem_parameters("stretch_coupling_N_per_m = 5\nweft_stretch_quartic_N_per_m = 2\n", "cal.toml", base);
  EXPECT_EQ(p.stretch_coupling_N_per_m, 5.0);
  EXPECT_EQ(p.stretch_coupling_source, "cal.toml:1");
  EXPECT_EQ(p.weft_stretch_quartic_N_per_m, 2.0);
  EXPECT_THROW(parse_fem_parameters("stretch_coupling_N_per_m = 0\n", "cal.toml", base), FemParameterError);
  FemMaterial all = p;
  all.warp_stretch_quartic_N_per_m = 3.0;
  all.areal_stretch_quartic_N_per_m = 4.0;
  write_fem_parameter_file(file, all);
  const FemMaterial back = read_fem_parameter_file(file, FemMaterial{});
  EXPECT_EQ(back.stretch_coupling_N_per_m, 5.0);
  EXPECT_EQ(back.warp_stretch_quartic_N_per_m, 3.0);
  EXPECT_EQ(back.weft_stretch_quartic_N_per_m, 2.0);
  EXPECT_EQ(back.areal_stretch_quartic_N_per_m, 4.0);
}

}  // namespace
}  // namespace wl
