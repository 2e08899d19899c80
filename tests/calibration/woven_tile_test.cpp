// The periodic woven tile (calibration/woven_tile.h), its relaxed energy
// density and stress (calibration/tile_sampling.h) and the law fitted to
// samples (calibration/tile_law.h), docs/calibration.md §9.
#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <random>

#include "calibration/tile_law.h"
#include "calibration/tile_sampling.h"
#include "calibration/woven_tile.h"
#include "models/scene/scene.h"
#include "tests/support/fd_check.h"

namespace wl {
namespace {

// The fabric of hanging_wind_damped.toml: Plain-(1,2), L = 1 mm, R = 0.5 mm, Gong's shear.
Scene plain_12(const std::string& pattern = "kind = \"plain\"") {
  return parse_scene(
      "[cloth]\nwarps = 17\nwefts = 17\nspacing_m = 0.001\nradius_m = 0.0005\nsliding = false\n"
      "warp_yarn_types = [\"yarn1\", \"yarn2\"]\nweft_yarn_types = [\"yarn1\", \"yarn2\"]\n"
      "[cloth.pattern]\n" +
          pattern +
          "\n[yarn_types.yarn1]\ndensity_kg_per_m = 0.002\nstretch_modulus_Pa = 500000.0\n"
          "bending_modulus_Pa = 0.00014\n[yarn_types.yarn2]\ndensity_kg_per_m = 0.0025\n"
          "stretch_modulus_Pa = 170000.0\nbending_modulus_Pa = 0.00011\n"
          "[contact]\nshear_model = \"gong\"\nshear_modulus_Pa = 1000.0\nlock_exponent = 3.0\nlock_sigma = 0.6\n",
      "tile_test.toml");
}

// A strain with every component inside the default ranges and none zero.
const MacroStrain kGeneric{0.012, 0.004, 0.21, 35.0, -20.0, 15.0};

Eigen::VectorXd normalized(const MacroStrain& theta, const TileRanges& r) {
  Eigen::VectorXd t(6);
  for (int k = 0; k < 6; ++k) t[k] = theta[k] / r.hi[k];
  return t;
}
MacroStrain denormalized(const Eigen::VectorXd& t, const TileRanges& r) {
  MacroStrain theta{};
  for (int k = 0; k < 6; ++k) theta[k] = t[k] * r.hi[k];
  return theta;
}

Mat3 turn() { return Eigen::AngleAxisd(2.0, Vec3(1, 2, 3).normalized()).toRotationMatrix(); }

TEST(WovenTile, SmallestTileRepeatsPatternAndYarnTypes) {
  EXPECT_EQ(woven_tile_size(plain_12()).nu, 2);
  EXPECT_EQ(woven_tile_size(plain_12()).nv, 2);
  const WovenTileSize twill = woven_tile_size(plain_12("kind = \"twill\"\nover = 2\nunder = 1\nshift = 1"));
  EXPECT_EQ(twill.nu, 6);  // period 3 along the warp, with the two yarn types: 6
  EXPECT_EQ(twill.nv, 6);
  const WovenTileSize satin = woven_tile_size(plain_12("kind = \"satin\"\nharness = 5\nstep = 2"));
  EXPECT_EQ(satin.nu, 10);
  EXPECT_EQ(satin.nv, 10);
}

// ∂φ/∂θ of the macroscopic map (forward-mode AD) against central differences.
TEST(WovenTile, MacroMapDerivativeMatchesDifferences) {
  const TileRanges r = default_tile_ranges(plain_12());
  const Vec2 X(0.7e-3, -1.3e-3);
  StrainJacobian J;
  macro_map(kGeneric, X, &J);
  const test::FdReport rep = test::check_jacobian_columns(
      [&](const Eigen::VectorXd& t) -> Eigen::VectorXd { return macro_map(denormalized(t, r), X); },
      normalized(kGeneric, r), [&](int k) -> Eigen::VectorXd { return J.col(k) * r.hi[k]; }, {0, 1, 2, 3, 4, 5},
      {.rel_step = 1e-6, .rtol = 1e-7});
  EXPECT_TRUE(rep.ok) << rep.detail;
}

// A cylinder keeps the yarns' lengths: φ's first fundamental form is exact to O(|X|³).
TEST(WovenTile, CylinderMapIsNearlyIsometric) {
  const double kappa = 60.0, h = 1e-7;
  for (const Vec2& X : {Vec2(1e-3, 0.0), Vec2(2e-3, 1e-3), Vec2(-1.5e-3, 0.5e-3)}) {
    const Vec3 d =
        (macro_map({0, 0, 0, kappa, 0, 0}, X + Vec2(h, 0)) - macro_map({0, 0, 0, kappa, 0, 0}, X - Vec2(h, 0))) /
        (2 * h);
    // Without the cubic term the stretch would be √(1 + κ²X²) − 1 ≈ ½κ²X².
    EXPECT_LT(std::abs(d.norm() - 1.0), 0.05 * 0.5 * kappa * kappa * X.squaredNorm()) << X.transpose();
  }
}

// ∂E/∂θ at fixed q (the images' forces on their shifts) against differences of E at fixed q.
TEST(WovenTile, StrainPartialAtFixedStateMatchesDifferences) {
  const Scene scene = plain_12();
  const TileRanges r = default_tile_ranges(scene);
  const WovenTileModel tile(scene, kGeneric);
  Vec q = tile.initial_q();
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> jitter(-2e-5, 2e-5);
  for (int a = 3; a < q.size(); ++a) q[a] += jitter(rng);  // off the affine state
  const Eigen::Matrix<double, 1, 6> dE = tile.strain_partial(q);
  const test::FdReport rep = test::check_jacobian_columns(
      [&](const Eigen::VectorXd& t) -> Eigen::VectorXd {
        return Eigen::VectorXd::Constant(1, WovenTileModel(scene, denormalized(t, r)).potential_energy(q));
      },
      normalized(kGeneric, r), [&](int k) -> Eigen::VectorXd { return Eigen::VectorXd::Constant(1, dE[k] * r.hi[k]); },
      {0, 1, 2, 3, 4, 5}, {.rel_step = 1e-6, .rtol = 1e-6});
  EXPECT_TRUE(rep.ok) << rep.detail;
}

TEST(WovenTile, RestStateIsStressFree) {
  const Scene scene = plain_12();
  const TileSample rest = relax_tile(scene, {0, 0, 0, 0, 0, 0});
  ASSERT_TRUE(rest.converged) << rest.message;
  EXPECT_EQ(rest.energy_density, 0.0);  // the flat woven tile at rest stores nothing
  // Each stress at rest against its value at 1 % of the range: zero to the equilibrium tolerance.
  const TileRanges r = default_tile_ranges(scene);
  for (int k = 0; k < 6; ++k) {
    MacroStrain small{};
    small[k] = 0.01 * r.hi[k];
    const TileSample s = relax_tile(scene, small);
    ASSERT_TRUE(s.converged) << s.message;
    ASSERT_GT(std::abs(s.stress[k]), 0.0) << kMacroStrainNames[k];
    EXPECT_LT(std::abs(rest.stress[k]), 1e-9 * std::abs(s.stress[k])) << kMacroStrainNames[k];
  }
}

TEST(WovenTile, RelaxedEnergyIsInvariantToRigidRotation) {
  const Scene scene = plain_12();
  const TileSample a = relax_tile(scene, kGeneric), b = relax_tile(scene, kGeneric, turn());
  ASSERT_TRUE(a.converged && b.converged) << a.message << b.message;
  ASSERT_GT(a.energy_density, 0.0);
  EXPECT_NEAR(b.energy_density, a.energy_density, 1e-10 * a.energy_density);
  for (int k = 0; k < 6; ++k) EXPECT_NEAR(b.stress[k], a.stress[k], 1e-8 * std::abs(a.stress[k])) << k;
}

// The implicit-function theorem: the stress (∂E/∂θ at the relaxed q) is the
// derivative of the relaxed energy density; the relaxation itself matters.
TEST(WovenTile, StressIsDerivativeOfRelaxedEnergy) {
  const Scene scene = plain_12();
  const TileRanges r = default_tile_ranges(scene);
  const TileSample s = relax_tile(scene, kGeneric);
  ASSERT_TRUE(s.converged) << s.message;
  const WovenTileModel affine(scene, kGeneric);
  const double affine_W = affine.potential_energy(affine.initial_q()) / affine.rest_area();
  EXPECT_LT(s.energy_density, (1.0 - 1e-3) * affine_W);  // the crossings moved off the affine map
  for (int k = 0; k < 6; ++k) EXPECT_GT(std::abs(s.stress[k]), 0.0) << kMacroStrainNames[k];
  const test::FdReport rep = test::check_jacobian_columns(
      [&](const Eigen::VectorXd& t) -> Eigen::VectorXd {
        const TileSample d = relax_tile(scene, denormalized(t, r));
        EXPECT_TRUE(d.converged) << d.message;
        return Eigen::VectorXd::Constant(1, d.energy_density);
      },
      normalized(kGeneric, r),
      [&](int k) -> Eigen::VectorXd { return Eigen::VectorXd::Constant(1, s.stress[k] * r.hi[k]); }, {0, 1, 2, 3, 4, 5},
      {.rel_step = 1e-5, .rtol = 1e-6});
  EXPECT_TRUE(rep.ok) << rep.detail;
}

TEST(TileSampling, LatinHypercubeFillsEveryStratumOnce) {
  const TileRanges r = default_tile_ranges(plain_12());
  const int n = 40;
  const std::vector<MacroStrain> pts = latin_hypercube(r, n, 7);
  ASSERT_EQ(static_cast<int>(pts.size()), n);
  for (int k = 0; k < 6; ++k) {
    std::vector<int> hits(n, 0);
    for (const MacroStrain& p : pts) ++hits[static_cast<int>((p[k] - r.lo[k]) / (r.hi[k] - r.lo[k]) * n)];
    for (int h : hits) EXPECT_EQ(h, 1) << kMacroStrainNames[k];
  }
  EXPECT_NE(latin_hypercube(r, n, 8)[0][0], pts[0][0]);
}

// The cache: samples read back exactly under their key, not under another fabric's.
TEST(TileSampling, CacheReadsBackUnderItsKeyOnly) {
  Scene scene = plain_12();
  const TileRanges r = default_tile_ranges(scene);
  std::vector<TileSample> samples;
  for (const MacroStrain& theta : latin_hypercube(r, 3, 1)) samples.push_back(relax_tile(scene, theta));
  const std::string key = tile_fabric_key(scene, r, 3, 1);
  const std::filesystem::path file =
      std::filesystem::temp_directory_path() / ("weavelab_tile_cache_" + std::to_string(::getpid()) + ".csv");
  write_tile_samples(file, key, samples);
  const auto back = read_tile_samples(file, key);
  ASSERT_TRUE(back.has_value());
  ASSERT_EQ(back->size(), samples.size());
  for (size_t p = 0; p < samples.size(); ++p) {
    EXPECT_EQ((*back)[p].strain, samples[p].strain);
    EXPECT_EQ((*back)[p].energy_density, samples[p].energy_density);
    EXPECT_EQ((*back)[p].stress, samples[p].stress);
    EXPECT_EQ((*back)[p].converged, samples[p].converged);
  }
  scene.yarn_types.at("yarn2").bending_modulus_Pa *= 1.01;
  const std::string other = tile_fabric_key(scene, r, 3, 1);
  EXPECT_NE(other, key);
  EXPECT_FALSE(read_tile_samples(file, other).has_value());
  std::filesystem::remove(file);
}

// Samples made by a known law: the fit finds its coefficients again.
TEST(TileLaw, FitRecoversKnownLaw) {
  const TileRanges r = default_tile_ranges(plain_12());
  TileLaw truth;
  for (int k = 0; k < 6; ++k) truth.scale[k] = r.hi[k];
  truth.energy_scale = 0.37;
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> coef(-1.0, 1.0);
  for (double& c : truth.coefficients) c = coef(rng);
  std::vector<TileSample> samples;
  for (const MacroStrain& theta : latin_hypercube(r, 150, 5)) {
    TileSample s;
    s.strain = theta;
    s.energy_density = truth.energy(theta);
    s.stress = truth.stress(theta);
    s.converged = true;
    samples.push_back(s);
  }
  const TileLawFit fit = fit_tile_law(samples, truth.scale);
  ASSERT_TRUE(fit.converged) << fit.message;
  // The fit's W₀ is the samples' RMS energy, not the truth's: compare W₀·c.
  for (int i = 0; i < kTileLawBasisSize; ++i)
    EXPECT_NEAR(fit.law.energy_scale * fit.law.coefficients[i], truth.energy_scale * truth.coefficients[i],
                1e-8 * truth.energy_scale)
        << TileLaw::basis_name(i);
  const TileLawErrors e = tile_law_errors(fit.law, samples);
  EXPECT_LT(e.energy, 1e-9);
  EXPECT_LT(e.stress_max, 1e-9);
}

// The law's stress is the derivative of its energy.
TEST(TileLaw, StressIsDerivativeOfEnergy) {
  const TileRanges r = default_tile_ranges(plain_12());
  TileLaw law;
  for (int k = 0; k < 6; ++k) law.scale[k] = r.hi[k];
  std::mt19937 rng(2);
  std::uniform_real_distribution<double> coef(-1.0, 1.0);
  for (double& c : law.coefficients) c = coef(rng);
  const std::array<double, 6> s = law.stress(kGeneric);
  const test::FdReport rep = test::check_jacobian_columns(
      [&](const Eigen::VectorXd& t) -> Eigen::VectorXd {
        return Eigen::VectorXd::Constant(1, law.energy(denormalized(t, r)));
      },
      normalized(kGeneric, r), [&](int k) -> Eigen::VectorXd { return Eigen::VectorXd::Constant(1, s[k] * r.hi[k]); },
      {0, 1, 2, 3, 4, 5}, {.rel_step = 1e-6, .rtol = 1e-7});
  EXPECT_TRUE(rep.ok) << rep.detail;
}

TEST(TileSampling, BadRangeNamesOptionAndItem) {
  TileRanges r = default_tile_ranges(plain_12());
  for (const std::string item : {"shear=0.5,0.1", "bogus=0,1", "shear=a,b", "shear", "twist=0,inf"}) {
    try {
      apply_tile_range(r, item, "--range");
      ADD_FAILURE() << item << " accepted";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("--range " + item), std::string::npos) << e.what();
    }
  }
  apply_tile_range(r, "shear=-0.1,0.3", "--range");
  EXPECT_EQ(r.lo[2], -0.1);
  EXPECT_EQ(r.hi[2], 0.3);
}

}  // namespace
}  // namespace wl
