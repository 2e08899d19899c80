// Patch tests of the mixed cloth (docs/models.md §12.3–§12.5): under uniform
// deformations it stores the continuum's energy where the yarn level's and the
// continuum's agree cell by cell, its excess over the continuum is additive
// over disjoint regions where they do not (shear), and at the continuum's
// hanging equilibrium it adds no force at the interface but the known mass
// lumping difference at the region's corners.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <iostream>

#include "calibration/equilibrium.h"
#include "models/fem/fem_model.h"
#include "models/mixed/mixed_model.h"

namespace wl {
namespace {

constexpr double kL = 1e-3;  // cloth.spacing_m's default

// A flat 10×10 cloth of the default yarn, sliding, no loads; the continuum's first-guess
// parameters (docs/models.md §6.7: k_u = k_s/L, k_warp = k_b/L) and the yarn level on `region`.
Scene flat_patch(const std::string& region) {
  return parse_scene(
      "[cloth]\nwarps = 10\nwefts = 10\n[pose]\nkind = \"flat\"\n[gravity]\nacceleration_m_per_s2 = [0.0, 0.0, 0.0]\n"
      "[mixed]\nyarn_region = " +
          region + "\n",
      "patch.toml");
}

using Map = std::function<Vec3(double u, double v)>;

// The model's state with crossing (i, j) at map(iL, jL), sliding coordinates at rest.
Vec deformed(const Model& m, int nu, int nv, const Map& map) {
  Vec q = m.initial_q();
  const auto* yarn = dynamic_cast<const YarnModel*>(&m);
  for (int j = 0; j < nv; ++j)
    for (int i = 0; i < nu; ++i) {
      const int x = yarn ? yarn->grid().dofs(yarn->grid().node(i, j)).x : 3 * (i + nu * j);
      q.segment<3>(x) = map(i * kL, j * kL);
    }
  return q;
}

// Potential energy at a state, the contact normal forces evaluated there first.
double energy_at(Model& m, const Vec& q) {
  Evaluation ev;
  m.evaluate(0.0, q, Vec::Zero(q.size()), kForce, ev);
  return m.potential_energy(q);
}

// Potential energy at the map above that at rest (the yarn level's is not zero at rest).
double energy(Model& m, const Map& map) { return energy_at(m, deformed(m, 10, 10, map)) - energy_at(m, m.initial_q()); }

const Map kBiaxial = [](double u, double v) { return Vec3(1.03 * u, 0.98 * v, 0.0); };
// A cylinder of radius 5L about the v axis, then one about the u axis.
const Map kBentAboutV = [](double u, double v) {
  const double r = 5 * kL;
  return Vec3(r * std::sin(u / r), v, r * (1 - std::cos(u / r)));
};
const Map kBentAboutU = [](double u, double v) {
  const double r = 5 * kL;
  return Vec3(u, r * std::sin(v / r), r * (1 - std::cos(v / r)));
};
const Map kSheared = [](double u, double v) { return Vec3(u + 0.1 * v, v, 0.0); };

// Stretch (Δu = L) and bending (U = 2L) of a yarn cell equal the grid continuum's with the
// first-guess parameters for these deformations, so the mixed cloth stores the continuum's
// energy to round-off: no element is counted twice or left out at the interface.
TEST(MixedPatch, StretchAndBendingStoreTheContinuumsEnergy) {
  const Scene s = flat_patch("[[2, 2, 6, 6]]");
  FemModel fem(s);
  MixedModel mixed(s);
  for (const auto& [name, map] : std::vector<std::pair<std::string, Map>>{
           {"biaxial stretch", kBiaxial}, {"bent about v", kBentAboutV}, {"bent about u", kBentAboutU}}) {
    const double e_fem = energy(fem, map), e_mixed = energy(mixed, map);
    ASSERT_GT(e_fem, 0.0) << name;
    std::cout << name << ": mixed " << e_mixed << " J, continuum " << e_fem << " J, relative difference "
              << (e_mixed - e_fem) / e_fem << "\n";
    EXPECT_LT(std::abs(e_mixed - e_fem), 1e-10 * e_fem) << name;
  }
}

// Under shear the two models differ cell by cell (Gong's shear with its lock and F_n against the
// continuum's first-guess k_sh): the mixed cloth's excess over the continuum is the sum of its
// regions' excesses, so the interface adds nothing of its own. The relative difference is printed
// (first-guess continuum, not the calibrated one).
TEST(MixedPatch, ShearExcessIsAdditiveOverRegions) {
  const Scene s = flat_patch("[]");
  FemModel fem(s);
  const double e_fem = energy(fem, kSheared);
  ASSERT_GT(e_fem, 0.0);
  auto excess = [&](const std::string& region) {
    MixedModel m(flat_patch(region));
    return energy(m, kSheared) - e_fem;
  };
  const double a = excess("[[1, 1, 3, 3]]"), b = excess("[[5, 5, 8, 8]]"),
               both = excess("[[1, 1, 3, 3], [5, 5, 8, 8]]");
  ASSERT_NE(a, 0.0);
  EXPECT_LT(std::abs(both - (a + b)), 1e-9 * std::abs(both));
  MixedModel all(flat_patch("[[0, 0, 9, 9]]"));
  const double e_yarn = energy(all, kSheared);
  std::cout << "shear 0.1: continuum " << e_fem << " J, yarn level " << e_yarn << " J; mixed (13 of 81 yarn cells) "
            << "relative difference " << both / e_fem << ", per yarn cell " << both / 13 / (e_fem / 81) << "\n";
}

// A 9×9 cloth hanging from its pinned top row under gravity, stretch alone (sliding frozen): the
// yarn level's stretch of a cell is the grid continuum's for every state (w_u, w_v of its two
// triangles are its four edges), so at the continuum's equilibrium the mixed force vanishes to the
// equilibrium's tolerance everywhere but at the region's four corners. There the two lumpings
// differ: the yarn gives each corner of a cell a quarter of its mass, the continuum's triangles a
// third at the corners of the diagonal (i, j)–(i+1, j+1) and a sixth at the others, so a corner
// crossing of the region carries 1/12 of a cell's mass less ((i0, j0), (i1, j1)) or more.
TEST(MixedPatch, AtRestUnderGravityTheInterfaceAddsNoForce) {
  std::string toml =
      "[cloth]\nwarps = 9\nwefts = 9\nsliding = false\n[pose]\nkind = \"upright\"\n"
      "[terms]\nbending = false\nshear = false\nwind = false\n[mixed]\nyarn_region = [[2, 2, 6, 6]]\n";
  for (int i = 0; i < 9; ++i) toml += "[[pins]]\nnode = [" + std::to_string(i) + ", 0]\n";
  const Scene s = parse_scene(toml, "hanging.toml");
  FemModel fem(s);
  MixedModel mixed(s);
  ASSERT_EQ(fem.num_dofs(), mixed.num_dofs());  // no sliding: both 3 DoFs per crossing, same order
  Vec q = fem.initial_q();
  for (int j = 0; j < 9; ++j)  // a start under tension (at rest stretch alone has no transverse stiffness)
    for (int i = 0; i < 9; ++i) q[3 * (i + 9 * j) + 2] -= 1e-3 * j * kL;
  EquilibriumSolver solver(fem, {});
  const EquilibriumResult eq = solver.solve(q);
  ASSERT_TRUE(eq.converged) << eq.message;
  Evaluation ev, ev_fem;
  mixed.evaluate(0.0, q, Vec::Zero(q.size()), kForce, ev);
  fem.evaluate(0.0, q, Vec::Zero(q.size()), kForce, ev_fem);
  const double cell_weight = s.yarn_types.at("default").density_kg_per_m * 2 * kL * 9.81;
  double worst = 0.0, worst_mixed = 0.0;  // the mixed force's difference from the continuum's, the mixed force
  for (int j = 1; j < 9; ++j)
    for (int i = 0; i < 9; ++i) {
      const Vec3 f = ev.force.segment<3>(3 * (i + 9 * j)) - ev_fem.force.segment<3>(3 * (i + 9 * j));
      const bool corner = (i == 2 || i == 6) && (j == 2 || j == 6);
      if (!corner) {
        worst = std::max(worst, f.lpNorm<Eigen::Infinity>());
        worst_mixed = std::max(worst_mixed, ev.force.segment<3>(3 * (i + 9 * j)).lpNorm<Eigen::Infinity>());
        continue;
      }
      const double sign = (i == 2) == (j == 2) ? 1.0 : -1.0;  // less mass: less weight, a force up
      EXPECT_NEAR(f.z(), sign * cell_weight / 12, 1e-9 * cell_weight) << "corner (" << i << ", " << j << ")";
      EXPECT_LT(std::abs(f.x()) + std::abs(f.y()), 1e-9 * cell_weight);
    }
  std::cout << "at the continuum's equilibrium (residual " << eq.residual << " N): off the region's corners the "
            << "largest mixed force " << worst_mixed << " N, its largest difference from the continuum's " << worst
            << " N; a cell's weight " << cell_weight << " N\n";
  EXPECT_LT(worst, 1e-9 * cell_weight);
  EXPECT_LE(worst_mixed, eq.residual + 1e-9 * cell_weight);
}

}  // namespace
}  // namespace wl
