// The rest tile's period (docs/models.md §11.3.1): the net force conjugate to
// each period length as the derivative of the relaxed energy, and the period
// relaxation's outcome with the present terms.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "models/knit/knit_model.h"
#include "models/knit/knit_rest_shape.h"
#include "tests/support/fd_check.h"

namespace wl {
namespace {

Scene period_scene(const std::string& kind, const std::string& extra = "") {
  return parse_scene(
      extra + "[cloth]\nspacing_m = 2e-3\nradius_m = 2e-4\n[cloth.pattern]\nkind = \"" + kind +
          "\"\ncourses = 4\nwales = 4\n[gravity]\nacceleration_m_per_s2 = [0, 0, 0]\n[pose]\nkind = \"flat\"\n",
      "knit.toml");
}

double k_s(const Scene& s) { return 5e5 * M_PI * s.radius_m * s.radius_m; }

// Without a contact-compression term nothing holds the loops open: the
// stockinette tile's relaxed energy keeps falling as its period widens along
// the course and shortens along the wale, so its period does not relax
// (docs/models.md §11.3.1); with it the next test finds one.
TEST(KnitPeriod, WithoutCompressionTheStockinetteTileHasNoRestPeriod) {
  const Scene s = period_scene("stockinette", "[knit]\ncompression_stiffness_N_per_m = 0\n");
  const KnitPeriodRelaxation early = relax_knit_period(s, 40), r = relax_knit_period(s, 100);
  const double bound = kKnitPeriodTolerance * k_s(s);
  EXPECT_FALSE(r.converged);
  EXPECT_NE(r.message.find("did not relax"), std::string::npos) << r.message;
  EXPECT_EQ(r.rest.period_iterations, 100);
  // Every step lowers the energy, and it is still falling: from 40 to 100 steps
  // the course widens further and the wale shortens further.
  EXPECT_LT(r.rest.energy_relaxed_J, early.rest.energy_relaxed_J);
  EXPECT_LT(early.rest.energy_relaxed_J, 0.9 * r.fixed_period_energy_J);
  EXPECT_GT(r.rest.period_scale[0], early.rest.period_scale[0]);
  EXPECT_LT(r.rest.period_scale[1], early.rest.period_scale[1]);
  EXPECT_GT(early.rest.period_scale[0], 1.5);
  EXPECT_LT(early.rest.period_scale[1], 0.8);
  EXPECT_LT(r.rest.period_force_N[0], -100.0 * bound);  // still pulled wider along the course
  EXPECT_GT(r.rest.period_force_N[1], 100.0 * bound);   // and shorter along the wale
  EXPECT_LE(r.rest.residual_N, kKnitRestTolerance * k_s(s));
  // At the generated period the force points the same way.
  const KnitRestShape fixed = relax_knit_tile(s);
  EXPECT_LT(fixed.period_force_N[0], -100.0 * bound);
  EXPECT_GT(fixed.period_force_N[1], 100.0 * bound);
}

// With the contact compression (default κ) the tiles have a rest period:
// Newton's method on P(ℓ) = 0 converges for stockinette and 2×2 rib, and the
// rib's relaxed course period, per wale, is markedly narrower than the
// stockinette's (real rib draws in; the rib's knit and purl wales fold onto
// each other), within a sane range. The cloth's rest shape uses it.
TEST(KnitPeriod, WithCompressionTheTilesHaveARestPeriodAndRibIsNarrower) {
  const Scene stockinette = period_scene("stockinette"), rib = period_scene("rib2x2");
  const double bound = kKnitPeriodTolerance * k_s(stockinette);
  std::array<double, 2> scale[2];
  int k = 0;
  for (const Scene* s : {&stockinette, &rib}) {
    const KnitRestShape& r = relaxed_tile(*s);
    EXPECT_TRUE(r.period_relaxed) << r.period_note;
    EXPECT_LE(std::abs(r.period_force_N[0]), bound);
    EXPECT_LE(std::abs(r.period_force_N[1]), bound);
    EXPECT_LE(r.residual_N, kKnitRestTolerance * k_s(*s));
    // Not the generated period: the fixed-period tile is not at rest.
    EXPECT_GT(std::abs(r.period_scale[0] - 1.0), 1e3 * kKnitRestTolerance);
    scale[k++] = r.period_scale;
  }
  const double width_ratio = scale[1][0] / scale[0][0];  // per wale: both tiles span their wales' generated width
  EXPECT_LT(width_ratio, 0.8);
  EXPECT_GT(width_ratio, 0.3);
  // The cloth is tiled at that period: a rib's course spans less than a stockinette's of as many wales.
  auto course_width = [](const Scene& s) {
    const KnitModel m(s);
    double lo = INFINITY, hi = -INFINITY;
    for (int n = 0; n < m.graph().num_nodes(); ++n) {
      lo = std::min(lo, m.position(m.initial_q(), n).x());
      hi = std::max(hi, m.position(m.initial_q(), n).x());
    }
    return hi - lo;
  };
  EXPECT_LT(course_width(rib), 0.8 * course_width(stockinette));
}

// P_i (a difference of the energy at a fixed state) against the derivative of
// the relaxed energy E*(ℓ) (each value a new relaxation): dE*/dℓ_i = P_i at a
// period that is not relaxed, where P is not zero.
TEST(KnitPeriod, ThePeriodForceIsTheDerivativeOfTheRelaxedEnergy) {
  const Scene s = period_scene("rib2x2");
  const std::array<double, 2> at{1.02, 0.97};
  const KnitRestShape r = relax_knit_tile(s, at);
  const std::array<double, 2> P = knit_period_force(s, at, knit_tile_state(s, r));
  const KnitLayout L = knit_layout(s, true);
  const std::array<double, 2> length{L.wales * L.wale_spacing, L.courses * L.course_spacing};
  auto energy = [&](const Vec& x) {
    Vec e(1);
    e[0] = relax_knit_tile(s, {x[0], x[1]}).energy_relaxed_J;
    return e;
  };
  test::FdOptions opt;
  opt.rel_step = 1e-5;
  opt.rtol = 1e-4;
  const auto check = test::check_jacobian_columns(
      energy, Vec2(at[0], at[1]), [&](int j) { return Vec::Constant(1, P[j] * length[j]); }, {0, 1}, opt);
  EXPECT_TRUE(check.ok) << check.detail;
}

}  // namespace
}  // namespace wl
