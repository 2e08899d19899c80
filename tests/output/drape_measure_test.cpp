// experiments/drape_measure.py (docs/models.md §3.11.6) on synthetic frames:
// the flat cloth has drape coefficient 1 and 4 folds (its corners), a cloth
// shrunk by s about the pedestal's axis has (s²A − A_p)/(A − A_p), and a cloth
// mapped onto a 6-lobed star has 6 folds.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <numbers>

#include "experiments/output/pvd_series.h"
#include "tests/output/output_test_util.h"

namespace wl {
namespace {

constexpr int kN = 33;        // crossings per side, 1 mm apart: a 32 mm square
constexpr double kC = 0.016;  // the pedestal's axis at the square's centre
constexpr double kPedestal = 0.008;

// The square's points mapped by `map` (offsets from the axis), as quads.
template <class Map>
Frame square(double t, Map map) {
  Frame f;
  f.time = t;
  f.points.resize(kN * kN, 3);
  for (int j = 0; j < kN; ++j)
    for (int i = 0; i < kN; ++i) {
      const Eigen::Vector2d p = map(Eigen::Vector2d(i * 1e-3 - kC, j * 1e-3 - kC));
      f.points.row(i + kN * j) << kC + p.x(), kC + p.y(), 0.0;
    }
  f.cells = {test::quad_grid_cells(kN)};
  return f;
}

TEST(DrapeMeasureScript, CoefficientAndFoldsOfKnownShapes) {
  ASSERT_TRUE(test::python_with("numpy, meshio"));
  test::ScratchDir dir;
  const auto run = dir.path() / "run";
  {
    PvdSeries series(run, "run");
    series.add(square(0.0, [](Eigen::Vector2d p) { return p; }));
    series.add(square(1.0, [](Eigen::Vector2d p) { return Eigen::Vector2d(0.7 * p); }));
    series.add(square(2.0, [](Eigen::Vector2d p) {  // the square's rings onto a 6-lobed star
      const double r = p.cwiseAbs().maxCoeff(), phi = std::atan2(p.y(), p.x());
      return Eigen::Vector2d(r * (1.0 + 0.2 * std::cos(6 * phi)) * Eigen::Vector2d(std::cos(phi), std::sin(phi)));
    }));
  }
  const auto scene = dir.path() / "scene.toml";
  std::ofstream(scene) << "[cloth]\nwarps = 33\nwefts = 33\nspacing_m = 0.001\n[[obstacles]]\nshape = \"disk\"\n"
                          "center_m = [0.016, 0.016, -0.001]\nradius_m = 0.008\nthickness_m = 0.002\n";
  const auto csv = dir.path() / "drape.csv";
  const auto r = test::run_command(std::string(test::python()) + " " + WEAVELAB_SOURCE_DIR +
                                   "/experiments/drape_measure.py " + test::shell_quote(run.string()) + " " +
                                   test::shell_quote(scene.string()) + " --out " + test::shell_quote(csv.string()));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  std::ifstream in(csv);
  std::string header, line;
  std::getline(in, header);
  EXPECT_EQ(header, "time_s,drape_coefficient,folds");
  std::vector<std::array<double, 3>> rows;
  while (std::getline(in, line)) {
    std::array<double, 3> v{};
    ASSERT_EQ(std::sscanf(line.c_str(), "%lf,%lf,%lf", &v[0], &v[1], &v[2]), 3) << line;
    rows.push_back(v);
  }
  ASSERT_EQ(rows.size(), 3u);
  const double area = 0.032 * 0.032, ped = std::numbers::pi * kPedestal * kPedestal;
  EXPECT_NEAR(rows[0][1], 1.0, 1e-3);
  EXPECT_EQ(rows[0][2], 4.0);
  EXPECT_NEAR(rows[1][1], (0.49 * area - ped) / (area - ped), 5e-3);
  EXPECT_EQ(rows[2][2], 6.0);
}

}  // namespace
}  // namespace wl
