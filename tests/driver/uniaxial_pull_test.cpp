// `weavelab pull` (docs/models.md §11.8): the woven strip against its closed
// form, the knit softer than the woven of the same yarn length per area, and
// bad input refused before anything is written.
#include "driver/uniaxial_pull.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

namespace wl {
namespace {

Scene flat(const std::string& cloth) {
  return parse_scene(cloth + "[pose]\nkind = \"flat\"\n[gravity]\nacceleration_m_per_s2 = [0, 0, 0]\n", "pull.toml");
}

double k_s(const Scene& s) { return 5e5 * M_PI * s.radius_m * s.radius_m; }

// Pulled along y, each of the n wefts is stretched by λ (straight yarns, no
// crimp): F/W = n k_s λ / ((n − 1) L), and the yarn density is 2n / ((n − 1) L).
TEST(UniaxialPull, AWovenStripPullsWithItsWeftsTension) {
  const Scene s = flat("[cloth]\nwarps = 5\nwefts = 5\nspacing_m = 1e-3\nradius_m = 2e-4\n");
  PullConfig c;
  c.strains = {0.005, 0.01};
  c.hold_z = true;
  const PullResult r = run_pull(s, c);
  ASSERT_TRUE(r.complete) << r.message;
  ASSERT_EQ(r.points.size(), 3u);
  EXPECT_NEAR(r.yarn_length_per_area_per_m, 2.0 * 5.0 / (4.0 * 1e-3), 1e-9);
  for (const PullPoint& p : r.points)
    EXPECT_NEAR(p.force_per_width_N_per_m, 5.0 * k_s(s) * p.strain / (4.0 * 1e-3), 1e-9) << p.strain;
}

// A stockinette of the same yarn and about the same yarn length per area
// pulled wale-wise to the same strain: the loops open before the yarn
// stretches, so it pulls with less than half the woven's F/W.
TEST(UniaxialPull, AKnitPullsWithLessThanTheWovenOfTheSameDensity) {
  const Scene knit = flat(
      "[cloth]\nspacing_m = 2e-3\nradius_m = 2e-4\n[cloth.pattern]\nkind = \"stockinette\"\ncourses = 4\n"
      "wales = 4\n");
  PullConfig c;
  c.strains = {0.02};
  c.hold_z = true;
  const PullResult k = run_pull(knit, c);
  ASSERT_TRUE(k.complete) << k.message;
  const double rho = k.yarn_length_per_area_per_m, spacing = 2.0 * 5.0 / (4.0 * rho);
  const Scene woven =
      flat("[cloth]\nwarps = 5\nwefts = 5\nspacing_m = " + std::to_string(spacing) + "\nradius_m = 2e-4\n");
  const PullResult w = run_pull(woven, c);
  ASSERT_TRUE(w.complete) << w.message;
  EXPECT_NEAR(w.yarn_length_per_area_per_m / rho, 1.0, 1e-3);
  const double knit_pull = k.points.back().force_per_width_N_per_m - k.points.front().force_per_width_N_per_m;
  EXPECT_GT(knit_pull, 0.0);
  EXPECT_LT(knit_pull, 0.5 * w.points.back().force_per_width_N_per_m);
}

TEST(UniaxialPull, RefusesAnUprightSceneAndABadLadderBeforeWriting) {
  const std::filesystem::path out = std::filesystem::temp_directory_path() / "weavelab_pull_refused";
  std::filesystem::remove_all(out);
  PullConfig c;
  c.out_dir = out;
  EXPECT_THROW(pull_command(parse_scene("[cloth]\nwarps = 5\nwefts = 5\n", "upright.toml"), c), std::invalid_argument);
  c.strains = {0.02, 0.01};
  EXPECT_THROW(pull_command(flat("[cloth]\nwarps = 5\nwefts = 5\n"), c), std::invalid_argument);
  EXPECT_FALSE(std::filesystem::exists(out));
}

}  // namespace
}  // namespace wl
