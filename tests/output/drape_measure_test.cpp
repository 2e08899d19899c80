// experiments/cusick/scripts/drape_measure.py (docs/models.md §3.11.6) on synthetic frames:
// the flat cloth has drape coefficient 1 and 4 folds (its corners), a cloth
// shrunk by s about the pedestal's axis has (s²A − A_p)/(A − A_p), and a cloth
// mapped onto a 6-lobed star has 6 folds. --state adds per frame the kinetic
// energy and intersecting pairs at the frame's time and the closest node to the pedestal.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <numbers>
#include <sstream>
#include <vector>

#include "output/pvd_series.h"
#include "tests/output/output_test_util.h"

namespace wl {
namespace {

constexpr int kN = 33;        // crossings per side, 1 mm apart: a 32 mm square
constexpr double kC = 0.016;  // the pedestal's axis at the square's centre
constexpr double kPedestal = 0.008;

// The square's points mapped by `map` (offsets from the axis), as quads.
template <class Map>
Frame square(double t, Map map, double z = 0.0) {
  Frame f;
  f.time = t;
  f.points.resize(kN * kN, 3);
  for (int j = 0; j < kN; ++j)
    for (int i = 0; i < kN; ++i) {
      const Eigen::Vector2d p = map(Eigen::Vector2d(i * 1e-3 - kC, j * 1e-3 - kC));
      f.points.row(i + kN * j) << kC + p.x(), kC + p.y(), z;
    }
  f.cells = {test::quad_grid_cells(kN)};
  return f;
}

const std::string kScene =
    "[cloth]\nwarps = 33\nwefts = 33\nspacing_m = 0.001\n[[obstacles]]\nshape = \"disk\"\n"
    "center_m = [0.016, 0.016, -0.001]\nradius_m = 0.008\nthickness_m = 0.002\n";

// drape_measure.py on the run folder: its exit, output and CSV (header, rows).
struct Measured {
  test::CommandResult command;
  std::string header;
  std::vector<std::vector<double>> rows;
};

Measured measure(const std::filesystem::path& dir, const std::string& flags = "") {
  const auto scene = dir / "scene.toml", csv = dir / "drape.csv";
  std::ofstream(scene) << kScene;
  Measured m;
  m.command =
      test::run_command(std::string(test::python()) + " " + WEAVELAB_SOURCE_DIR +
                        "/experiments/cusick/scripts/drape_measure.py " + test::shell_quote((dir / "run").string()) +
                        " " + test::shell_quote(scene.string()) + " --out " + test::shell_quote(csv.string()) + flags);
  std::ifstream in(csv);
  std::getline(in, m.header);
  for (std::string line; std::getline(in, line);) {
    std::stringstream cells(line);
    m.rows.emplace_back();
    for (std::string cell; std::getline(cells, cell, ',');) m.rows.back().push_back(std::stod(cell));
  }
  return m;
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
  const Measured m = measure(dir.path());
  ASSERT_EQ(m.command.exit_code, 0) << m.command.output;
  EXPECT_EQ(m.header, "time_s,drape_coefficient,folds");
  const auto& rows = m.rows;
  ASSERT_EQ(rows.size(), 3u);
  for (const auto& r : rows) ASSERT_EQ(r.size(), 3u);
  const double area = 0.032 * 0.032, ped = std::numbers::pi * kPedestal * kPedestal;
  EXPECT_NEAR(rows[0][1], 1.0, 1e-3);
  EXPECT_EQ(rows[0][2], 4.0);
  EXPECT_NEAR(rows[1][1], (0.49 * area - ped) / (area - ped), 5e-3);
  EXPECT_EQ(rows[2][2], 6.0);
}

// The pedestal's top is z = 0: the flat cloth 0.5 mm above it has its closest
// node 0.5 mm away, 0.3 mm below its top the centre node is 0.3 mm inside
// (signed distance −0.3 mm); kinetic energy and pairs are read at the frames' times.
TEST(DrapeMeasureScript, StateColumnsAtTheFrameTimes) {
  ASSERT_TRUE(test::python_with("numpy, meshio"));
  test::ScratchDir dir;
  const auto run = dir.path() / "run";
  {
    PvdSeries series(run, "run");
    const auto same = [](Eigen::Vector2d p) { return p; };
    series.add(square(0.0, same, 5e-4));
    series.add(square(0.5, same, -3e-4));
  }
  std::ofstream(run / "metrics.csv") << "time_s,kinetic_J\n0,1e-3\n0.25,7\n0.5,2e-6\n";
  std::ofstream(run / "self_intersections.csv") << "time_s,intersecting_triangle_pairs\n0,0\n0.5,12\n";
  const Measured m = measure(dir.path(), " --state");
  ASSERT_EQ(m.command.exit_code, 0) << m.command.output;
  EXPECT_EQ(m.header, "time_s,drape_coefficient,folds,kinetic_J,intersecting_triangle_pairs,closest_to_pedestal_m");
  const auto& rows = m.rows;
  ASSERT_EQ(rows.size(), 2u);
  for (const auto& r : rows) ASSERT_EQ(r.size(), 6u);
  EXPECT_EQ(rows[0][3], 1e-3);
  EXPECT_EQ(rows[1][3], 2e-6);
  EXPECT_EQ(rows[0][4], 0.0);
  EXPECT_EQ(rows[1][4], 12.0);
  EXPECT_NEAR(rows[0][5], 5e-4, 1e-12);
  EXPECT_NEAR(rows[1][5], -3e-4, 1e-12);
}

}  // namespace
}  // namespace wl
