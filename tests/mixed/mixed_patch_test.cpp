// Patch tests of the mixed cloth (docs/models.md §12.3–§12.5): under uniform
// deformations it stores the continuum's energy where the yarn level's and the
// continuum's agree cell by cell, its excess over the continuum is additive
// over disjoint regions where they do not (shear), with the continuum
// calibrated on the same fabric it stays within 1 % of the continuum under
// stretch and shear (bending: the calibration's N/(N−1), measured), and at the
// continuum's hanging equilibrium it adds no force at the interface, its
// corners included (the interface mass, §12.4).
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <functional>
#include <iostream>
#include <sstream>

#include "calibration/equilibrium.h"
#include "models/fem/fem_material.h"
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

// The flat 10×10 patch of tests/mixed/patch_fabric.toml with its continuum calibrated by
// `weavelab calibrate` (tests/mixed/patch_fabric_params.toml: border strip, spline shear, relative
// residuals, as that file's provenance says) and the yarn level on `region`.
Scene calibrated_patch(const std::string& region) {
  const std::string dir = std::string(WEAVELAB_SOURCE_DIR) + "/tests/mixed/";
  std::ifstream in(dir + "patch_fabric.toml");
  std::stringstream text;
  text << in.rdbuf();
  return parse_scene(text.str() + "[fem]\nparameter_file = \"" + dir +
                         "patch_fabric_params.toml\"\nborder_strip = true\nshear_law = \"spline\"\n"
                         "shear_knots_rad = [0.1, 0.2, 0.3, 0.4]\n[mixed]\nyarn_region = " +
                         region + "\n",
                     dir + "patch_fabric.toml");
}

// Picture-frame shear by γ: both yarn directions turned by γ/2 towards each other, lengths kept.
Map picture_frame(double gamma) {
  return [gamma](double u, double v) {
    const double c = std::cos(gamma / 2), s = std::sin(gamma / 2);
    return Vec3(c * u + s * v, s * u + c * v, 0.0);
  };
}

// With the continuum calibrated on the same fabric a mixed cloth (16 of 81 cells yarn) stores the
// all-continuum cloth's energy under stretch and picture-frame shear to 1 % (the border strip takes
// the border's half spacing out of the stretch fit, the spline shear law follows the yarn level
// below its lock). Per yarn cell the shear differs by more: Gong's stiffness (F_n + 1)SπR² grows
// with the crimp's normal force, which is 0 on the outer ring (docs/models.md §3.6), so the yarn
// level's ring cells shear less than the calibrated continuum and its inner cells more; the
// calibration averages both over its patch. Bending is not within 1 %: the patch's N yarns bend over
// (N−1)L of width, so the calibrated continuum is N/(N−1) = 10/9 stiffer per area than a yarn cell
// (docs/models.md §12.5).
TEST(MixedPatch, CalibratedContinuumStoresTheYarnCellsEnergy) {
  const Scene s = calibrated_patch("[[2, 2, 6, 6]]");
  FemModel fem(s);
  MixedModel mixed(s);
  const double yarn_part = 16.0 / 81.0;
  auto excess = [&](Model& m, const Map& map) {
    const double e_fem = energy(fem, map);
    return (energy(m, map) - e_fem) / e_fem;
  };
  for (const auto& [name, map] : std::vector<std::pair<std::string, Map>>{{"biaxial stretch", kBiaxial},
                                                                          {"shear 0.1 rad", picture_frame(0.1)},
                                                                          {"shear 0.3 rad", picture_frame(0.3)}}) {
    const double relative = excess(mixed, map);
    std::cout << name << ": mixed over calibrated continuum " << relative << ", per yarn cell " << relative / yarn_part
              << "\n";
    EXPECT_LT(std::abs(relative), 0.01) << name;
  }
  MixedModel ring(calibrated_patch("[[0, 0, 9, 1], [0, 8, 9, 9], [0, 0, 1, 9], [8, 0, 9, 9]]"));
  MixedModel inner(calibrated_patch("[[1, 1, 8, 8]]"));
  const double per_ring_cell = excess(ring, picture_frame(0.1)) / (32.0 / 81.0),
               per_inner_cell = excess(inner, picture_frame(0.1)) / (49.0 / 81.0);
  std::cout << "shear 0.1 rad per yarn cell over the calibrated continuum: ring cells " << per_ring_cell
            << ", inner cells " << per_inner_cell << "\n";
  EXPECT_LT(per_ring_cell, 0.0);
  EXPECT_GT(per_inner_cell, 0.0);

  const double k_yarn = default_fem_material(flat_patch("[]")).warp_bending_N_m;  // k_b/L (§6.7)
  EXPECT_NEAR(fem.material().warp_bending_N_m / k_yarn, 10.0 / 9.0, 1e-3);
  for (const auto& [name, map] :
       std::vector<std::pair<std::string, Map>>{{"bent about v", kBentAboutV}, {"bent about u", kBentAboutU}}) {
    const double relative = excess(mixed, map);
    std::cout << name << ": mixed over calibrated continuum " << relative << ", per yarn cell " << relative / yarn_part
              << "\n";
    EXPECT_LT(relative, -0.01) << name << ": the calibration's N/(N−1) is gone, expect |relative| < 1 % here";
  }
}

// The 9×9 cloth hanging from its pinned top row under gravity, stretch alone (sliding frozen), the
// yarn level on [[2, 2, 6, 6]].
Scene hanging_patch() {
  std::string toml =
      "[cloth]\nwarps = 9\nwefts = 9\nsliding = false\n[pose]\nkind = \"upright\"\n"
      "[terms]\nbending = false\nshear = false\nwind = false\n[mixed]\nyarn_region = [[2, 2, 6, 6]]\n";
  for (int i = 0; i < 9; ++i) toml += "[[pins]]\nnode = [" + std::to_string(i) + ", 0]\n";
  return parse_scene(toml, "hanging.toml");
}

// Each crossing's mass (the row sums of M) is the continuum's: a cell gives each corner a quarter at
// yarn level, while the continuum's triangles give a third at the corners of the diagonal
// (i, j)–(i+1, j+1) and a sixth at the other two, so without the interface term a corner crossing
// of the region would carry 1/12 of a cell's mass less ((i0, j0), (i1, j1)) or more (the others).
TEST(MixedPatch, EveryCrossingCarriesTheContinuumsMass) {
  const Scene s = hanging_patch();
  FemModel fem(s);
  MixedModel mixed(s);
  ASSERT_EQ(fem.num_dofs(), mixed.num_dofs());  // no sliding: both 3 DoFs per crossing, same order
  Evaluation ev, ev_fem;
  const Vec q = fem.initial_q(), v = Vec::Zero(q.size());
  mixed.evaluate(0.0, q, v, kMass, ev);
  fem.evaluate(0.0, q, v, kMass, ev_fem);
  const Vec rows = ev.mass * Vec::Ones(q.size()), rows_fem = ev_fem.mass * Vec::Ones(q.size());
  const double cell_mass = s.yarn_types.at("default").density_kg_per_m * 2 * kL;
  EXPECT_NEAR(rows_fem[3 * (4 + 9 * 4)], cell_mass, 1e-12 * cell_mass);  // an interior crossing: one cell
  for (int k = 0; k < 81; ++k) EXPECT_NEAR(rows[3 * k], rows_fem[3 * k], 1e-12 * cell_mass) << "crossing " << k;
  // The interface term holds the twelfth at the four corners and nothing else.
  double held = 0.0;
  int corners = 0;
  for (const auto& term : mixed.terms()) {
    if (term->name() != "mixed-interface-mass") continue;
    for (int e = 0; e < term->num_elements(); ++e) {
      double m[9] = {}, f[3] = {}, x[3] = {};
      term->evaluate(e, x, x, ElementOutput{f, nullptr, nullptr, m});
      const int k = term->stencil(e)[0] / 3, i = k % 9, j = k / 9;
      ASSERT_TRUE((i == 2 || i == 6) && (j == 2 || j == 6)) << "crossing (" << i << ", " << j << ")";
      EXPECT_NEAR(m[0], ((i == 2) == (j == 2) ? 1.0 : -1.0) * cell_mass / 12, 1e-12 * cell_mass);
      held += m[0];
      ++corners;
    }
  }
  EXPECT_EQ(corners, 4);
  EXPECT_NEAR(held, 0.0, 1e-12 * cell_mass);  // the cloth's total mass unchanged
}

// At the continuum's equilibrium the mixed force is the continuum's to round-off at every crossing,
// interface and corners included: the yarn level's stretch of a cell is the grid continuum's for
// every state with the first-guess parameters (w_u, w_v of its two triangles are its four edges) and
// every crossing carries the same weight, so the interface adds no force above the equilibrium's
// tolerance. Without the interface mass the corners would be off by 1/12 of a cell's weight.
TEST(MixedPatch, AtRestUnderGravityTheInterfaceAddsNoForce) {
  const Scene s = hanging_patch();
  FemModel fem(s);
  MixedModel mixed(s);
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
  for (int k = 9; k < 81; ++k) {          // the free crossings (the top row is pinned)
    worst = std::max(worst, (ev.force.segment<3>(3 * k) - ev_fem.force.segment<3>(3 * k)).lpNorm<Eigen::Infinity>());
    worst_mixed = std::max(worst_mixed, ev.force.segment<3>(3 * k).lpNorm<Eigen::Infinity>());
  }
  std::cout << "at the continuum's equilibrium (residual " << eq.residual << " N): the largest mixed force "
            << worst_mixed << " N, its largest difference from the continuum's " << worst
            << " N; a twelfth of a cell's weight " << cell_weight / 12 << " N\n";
  EXPECT_LT(worst, 1e-9 * cell_weight);
  EXPECT_LE(worst_mixed, eq.residual + 1e-9 * cell_weight);
}

}  // namespace
}  // namespace wl
