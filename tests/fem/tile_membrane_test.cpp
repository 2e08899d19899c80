// The tile law as a continuum law (docs/models.md §6.9): the file reader and its
// located errors, the membrane term's force, Jacobian and coefficient derivatives
// against finite differences inside and outside the sampled box, its energy
// against the hand-computed law, the split against the fitted law of `weavelab
// tiles`, and the law as the scene's parameter file.
#include <gtest/gtest.h>

#include <unistd.h>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>

#include <Eigen/Geometry>

#include "calibration/tile_law.h"
#include "driver/tiles.h"
#include "models/fem/fem_material.h"
#include "models/fem/fem_model.h"
#include "models/fem/terms/tile_membrane.h"
#include "models/fem/tile_law_file.h"
#include "tests/fem/fem_test_scene.h"
#include "tests/fem/tile_law_test_data.h"
#include "tests/support/fd_check.h"

namespace wl {
namespace {

const std::string& kHeader = test::kTileLawHeader;  // tests/fem/tile_law_test_data.h
const std::string kTerms =
    "stretch_warp^2,0.6\nstretch_weft^2,0.4\nshear^2,0.3\nstretch_warp*stretch_weft,0.1\nstretch_warp^3,0.05\n"
    "shear^4,0.2\nstretch_warp*shear^2,0.05\nstretch_warp*stretch_weft*shear,0.02\n"
    "curvature_warp^2,0.1\ncurvature_weft^2,0.08\nstretch_warp*curvature_warp^2,-0.03\n";

std::shared_ptr<const TileMembraneLaw> membrane(const std::string& terms = kTerms) {
  return std::make_shared<const TileMembraneLaw>(parse_tile_law(kHeader + terms, "law.csv"));
}

const Vec2 kUv0(0.001, 0.002), kUv1(0.013, 0.001), kUv2(0.004, 0.011);

std::unique_ptr<Term> membrane_term(std::shared_ptr<const TileMembraneLaw> law) {
  auto t = std::make_unique<TileMembraneTerm>(std::move(law));
  t->add({0, 1, 2, 3, 4, 5, 6, 7, 8}, triangle_rest(kUv0, kUv1, kUv2));
  return t;
}

// The triangle under the tile's map A (docs/calibration.md §9.1) at strains (ε_u, ε_v, γ), turned
// about an oblique axis and lifted out of plane, plus seeded noise of 10⁻⁶ m.
test::LocalState strained(double eu, double ev, double gamma, unsigned seed) {
  Eigen::Matrix<double, 3, 2> a;
  a.col(0) = (1 + eu) * Vec3(std::cos(gamma / 2), std::sin(gamma / 2), 0);
  a.col(1) = (1 + ev) * Vec3(std::sin(gamma / 2), std::cos(gamma / 2), 0);
  const Mat3 turn = Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized()).toRotationMatrix();
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> noise(-1e-6, 1e-6);
  test::LocalState s{{}, std::vector<double>(9, 0.0)};
  for (const Vec2& uv : {kUv0, kUv1, kUv2}) {
    const Vec3 x = turn * (a * uv) + Vec3(0, 0, 0.002);
    for (int c = 0; c < 3; ++c) s.q.push_back(x[c] + noise(rng));
  }
  return s;
}

// Inside the box; beyond it in compression, in stretch and shear, and in negative shear.
std::vector<test::LocalState> states() {
  return {strained(0.004, 0.002, 0.2, 1), strained(-0.012, 0.006, -0.1, 2), strained(0.03, -0.009, 0.7, 3),
          strained(0.01, 0.025, -0.65, 4)};
}

TEST(TileMembrane, ForceAndJacobianMatchFiniteDifferences) {
  const auto r = test::check_element(*membrane_term(membrane()), 0, states());
  EXPECT_TRUE(r.ok) << r.detail;
}

TEST(TileMembrane, CoefficientDerivativesMatchFiniteDifferences) {
  const std::shared_ptr<const TileMembraneLaw> law = membrane();
  const std::vector<std::string> keys = membrane_term(law)->parameter_keys();
  ASSERT_EQ(keys.size(), 8u);  // the membrane monomials; the curvature rows stay out
  EXPECT_EQ(keys[0], "fem.tile_law.stretch_warp^2");
  EXPECT_EQ(keys[7], "fem.tile_law.stretch_warp*stretch_weft*shear");
  // The coefficient of each row of kTerms, set to p in the law's text.
  const std::vector<std::pair<std::string, double>> rows{
      {"stretch_warp^2", 0.6}, {"shear^4", 0.2}, {"stretch_warp*stretch_weft*shear", 0.02}};
  for (const auto& [row, value] : rows) {
    const int k = static_cast<int>(std::find(keys.begin(), keys.end(), "fem.tile_law." + row) - keys.begin());
    auto make = [&, row = row, value = value](double p) {
      std::string terms = kTerms;
      const std::string old = row + "," + [&] {
        std::ostringstream s;
        s << value;
        return s.str();
      }();
      std::ostringstream now;
      now.precision(17);
      now << row << "," << p;
      terms.replace(terms.find(old), old.size(), now.str());
      return membrane_term(membrane(terms));
    };
    const auto r = test::check_parameter_derivative(make, value, k, 0, states());
    EXPECT_TRUE(r.ok) << row << ": " << r.detail;
  }
}

TEST(TileMembrane, EnergyInsideAndBeyondTheBox) {
  // Unit right triangle, w_u = (1 + ε, 0, 0), w_v = (0, 1, 0): only stretch_warp acts, t = ε/0.02.
  auto t = std::make_unique<TileMembraneTerm>(membrane());
  t->add({0, 1, 2, 3, 4, 5, 6, 7, 8}, triangle_rest(Vec2(0, 0), Vec2(1, 0), Vec2(0, 1)));
  auto energy = [&](double eps) {
    const double q[9] = {0, 0, 0, 1 + eps, 0, 0, 0, 1, 0};
    return t->energy(0, q);
  };
  // Inside, t = 0.5: A·W₀(0.6 t² + 0.05 t³) = ½·1.5·(0.15 + 0.00625).
  EXPECT_NEAR(energy(0.01), 0.5 * 1.5 * 0.15625, 1e-14);
  // Beyond hi, t = 1.5, p = 1, d = 0.5: P(1) + P'(1)·d + ½·(2·0.6)·d² = 0.65 + 1.35·0.5 + 0.15 = 1.475.
  EXPECT_NEAR(energy(0.03), 0.5 * 1.5 * 1.475, 1e-13);
  // Beyond lo, t = −0.5, p = −0.25, d = −0.25: P(p) = 0.6/16 − 0.05/64, P'(p) = −0.3 + 0.15/16, h = 1.2.
  const double p = 0.6 / 16 - 0.05 / 64, dp = -0.3 + 0.15 / 16;
  EXPECT_NEAR(energy(-0.01), 0.5 * 1.5 * (p + dp * -0.25 + 0.6 * 0.0625), 1e-14);
}

TEST(TileMembrane, SplitOfTheFittedLaw) {
  // A law of the tiles basis with seeded coefficients, through the file `weavelab tiles` writes:
  // the membrane is W at zero curvature, the bending stiffness ∂²W/∂κ² at rest.
  TileLaw law;
  law.scale = {0.02, 0.02, 0.6, 50, 50, 50};
  law.energy_scale = 0.8;
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-0.1, 0.1);
  for (double& c : law.coefficients) c = u(rng);
  for (int i = 0; i < kTileLawBasisSize; ++i)  // stiff at rest along every membrane strain
    for (const char* n : {"stretch_warp^2", "stretch_weft^2", "shear^2", "curvature_warp^2", "curvature_weft^2"})
      if (TileLaw::basis_name(i) == n) law.coefficients[i] = 1.0;
  TileRanges ranges;
  ranges.lo = {-0.005, -0.005, -0.6, -50, -50, -50};
  ranges.hi = {0.02, 0.02, 0.6, 50, 50, 50};
  const TileLawFile file = parse_tile_law(tile_law_csv(law, ranges), "tile_law.csv");
  const TileMembraneLaw m(file);
  for (const std::array<double, 3>& x : {std::array<double, 3>{0.01, -0.003, 0.3}, {-0.004, 0.015, -0.5}}) {
    double w;
    std::array<double, 3> g;
    m.evaluate(x, &w, &g, nullptr);
    const MacroStrain theta{x[0], x[1], x[2], 0, 0, 0};
    EXPECT_NEAR(w, law.energy(theta), 1e-12 * std::abs(law.energy(theta)));
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(g[k], law.stress(theta)[k], 1e-11 * std::abs(law.stress(theta)[k]));
  }
  const double h = 1e-3;  // the moment's slope in κ_u, κ_v at rest (central differences of the law's stress)
  const double warp = (law.stress({0, 0, 0, h, 0, 0})[3] - law.stress({0, 0, 0, -h, 0, 0})[3]) / (2 * h);
  const double weft = (law.stress({0, 0, 0, 0, h, 0})[4] - law.stress({0, 0, 0, 0, -h, 0})[4]) / (2 * h);
  EXPECT_NEAR(file.warp_bending_N_m(), warp, 1e-9 * warp);
  EXPECT_NEAR(file.weft_bending_N_m(), weft, 1e-9 * weft);
  EXPECT_NEAR(warp, 2 * 0.8 / (50.0 * 50.0), 1e-6 * warp);
}

std::string error_of(const std::string& text) {
  try {
    (void)TileMembraneLaw(parse_tile_law(text, "law.csv"));
  } catch (const FemParameterError& e) {
    return e.what();
  }
  return "no error";
}

TEST(TileMembrane, BadFilesAreRefusedLocated) {
  EXPECT_EQ(error_of(kHeader + kTerms), "no error");
  EXPECT_NE(error_of("W,value\n").find("law.csv:1: header 'W,value'"), std::string::npos);
  EXPECT_NE(error_of(kHeader + "shear^2,nan\n").find("law.csv:21: value 'nan', expected a finite number"),
            std::string::npos);
  EXPECT_NE(error_of(kHeader + "shear^2,inf\n").find("law.csv:21: value 'inf'"), std::string::npos);
  EXPECT_NE(error_of(kHeader + "shear^2,1,2\n").find("law.csv:21: row 'shear^2,1,2', expected two fields"),
            std::string::npos);
  EXPECT_NE(error_of(kHeader + "shear^2\n").find("law.csv:21: row 'shear^2', expected two fields"), std::string::npos);
  EXPECT_NE(error_of(kHeader + "bend^2,1\n").find("law.csv:21: row 'bend^2', expected a strain"), std::string::npos);
  EXPECT_NE(error_of(kHeader + "shear,1\n").find("law.csv:21: row 'shear'"), std::string::npos);  // degree 1
  EXPECT_NE(error_of(kHeader + "shear*shear,1\n").find("law.csv:21"), std::string::npos);         // a strain twice
  EXPECT_NE(error_of(kHeader + kTerms + "shear^2,1\n").find("row 'shear^2' again"), std::string::npos);
  // a header row missing: the last line, and the row's name
  std::string no_scale = kHeader;
  no_scale.erase(no_scale.find("scale:shear,0.5\n"), 16);
  EXPECT_NE(error_of(no_scale + kTerms).find("law.csv:30: no row scale:shear"), std::string::npos);
  EXPECT_NE(error_of(kHeader).find("no monomial row"), std::string::npos);
  const std::string bending = "curvature_warp^2,1\ncurvature_weft^2,1\n";
  EXPECT_NE(error_of(kHeader + bending + "stretch_warp^2,1\nstretch_weft^2,1\n").find("stiffness at rest along shear"),
            std::string::npos);
  EXPECT_NE(
      error_of(kHeader + "shear^2,1\ncurvature_warp^2,1\ncurvature_weft^2,-1\n").find("law.csv:23: bending at rest"),
      std::string::npos);
  EXPECT_THROW(read_tile_law_file("/nonexistent/tile_law.csv"), FemParameterError);
}

TEST(TileMembrane, ParameterFileOfTheSceneBuildsTheMembraneAndTheBending) {
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("wl_tile_law_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "law.csv") << kHeader << kTerms;
  std::ofstream(dir / "bad.csv") << kHeader << "shear^2,x\n";
  std::ofstream(dir / "params.toml") << "warp_bending_N_m = 3e-6\n";
  EXPECT_TRUE(is_tile_law_file((dir / "law.csv").string()));
  EXPECT_FALSE(is_tile_law_file((dir / "params.toml").string()));
  EXPECT_FALSE(is_tile_law_file(""));
  const std::string cloth = "[cloth]\nwarps = 3\nwefts = 3\n[gravity]\nacceleration_m_per_s2 = [0, 0, 0]\n";
  auto scene = [&](const std::string& file) {
    return parse_scene(cloth + "[fem]\nparameter_file = \"" + file + "\"\n", (dir / "s.toml").string());
  };
  const FemModel model(scene("law.csv"));
  EXPECT_NE(model.describe().at("terms").find("fem-tile-membrane (8)"), std::string::npos);
  EXPECT_EQ(model.describe().at("terms").find("fem-stretch"), std::string::npos);
  EXPECT_EQ(model.describe().at("terms").find("fem-shear"), std::string::npos);
  EXPECT_DOUBLE_EQ(model.material().warp_bending_N_m, 2 * 1.5 * 0.1 / 100);
  EXPECT_DOUBLE_EQ(model.material().weft_bending_N_m, 2 * 1.5 * 0.08 / 100);
  // the yarn level's mass: 3 warps and 3 wefts of 2 spacings each over (2 spacings)², 3/2 of the
  // per-area default 2ρ/L of an endless fabric
  EXPECT_NEAR(model.material().areal_density_kg_per_m2,
              1.5 * default_fem_material(scene("law.csv")).areal_density_kg_per_m2, 1e-12);
  // a TOML parameter file keeps the stretch and shear terms
  const FemModel plain(scene("params.toml"));
  EXPECT_NE(plain.describe().at("terms").find("fem-stretch"), std::string::npos);
  EXPECT_DOUBLE_EQ(plain.material().warp_bending_N_m, 3e-6);
  try {  // the file's own error, located in it
    (void)fem_material(scene("bad.csv"));
    ADD_FAILURE() << "no error";
  } catch (const FemParameterError& e) {
    EXPECT_NE(std::string(e.what()).find("bad.csv:21: value 'x'"), std::string::npos) << e.what();
  }
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace wl
