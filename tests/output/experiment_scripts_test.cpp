// Light end-to-end checks of the Python experiment scripts on tiny synthetic
// runs written with the C++ writers.
#include <gtest/gtest.h>

#include <cmath>
#include <sstream>

#include "output/atomic_file.h"
#include "output/json_writer.h"
#include "output/metrics_csv.h"
#include "output/pvd_series.h"
#include "tests/output/output_test_util.h"

namespace wl {
namespace {

constexpr double kSide = 0.1;     // material square [0, 0.1 m]²
constexpr double kOffset = 1e-3;  // run A sits 1 mm above run B

// An affine deformation of the material plane (exact under barycentric interpolation).
Eigen::Vector3d place(double u, double v, double t) {
  return {u + 0.2 * v, 0.9 * v + 0.1 * t, 0.3 * u - 0.1 * v + 0.5 * t};
}

// Continuum run: an n×n vertex grid with rest "uv", triangles and cell "tension".
Frame continuum_frame(int n, double t, double dz) {
  Frame f;
  f.time = t;
  f.points.resize(n * n, 3);
  DataArray uv{"uv", 2, {}};
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const double u = kSide * i / (n - 1), v = kSide * j / (n - 1);
      f.points.row(i * n + j) = (place(u, v, t) + Eigen::Vector3d(0, 0, dz)).transpose();
      uv.values.insert(uv.values.end(), {u, v});
    }
  CellBlock tris{CellType::triangle, {}};
  for (int i = 0; i + 1 < n; ++i)
    for (int j = 0; j + 1 < n; ++j) {
      const int a = i * n + j;
      tris.connectivity.insert(tris.connectivity.end(), {a, a + n, a + n + 1, a, a + n + 1, a + 1});
    }
  DataArray tension{"tension", 1, std::vector<double>(tris.size(), 0.0)};
  for (int c = 0; c < tris.size(); ++c) tension.values[c] = 10.0 + c;
  f.cells.push_back(std::move(tris));
  f.point_data.push_back(std::move(uv));
  f.cell_data.push_back(std::move(tension));
  return f;
}

// Yarn-like run: crossings on an n×n grid whose current material coordinates
// "u", "v" have slid off the continuum vertices; warp and weft lines.
Frame yarn_frame(int n, double t, double dz) {
  Frame f;
  f.time = t;
  f.points.resize(n * n, 3);
  DataArray u{"u", 1, {}}, v{"v", 1, {}};
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const double s = (i > 0 && i + 1 < n && j > 0 && j + 1 < n) ? 0.3 : 0.0;  // interior nodes slide
      const double ui = kSide * (i + s * std::sin(3.0 * j + t)) / (n - 1);
      const double vj = kSide * (j + s * std::cos(2.0 * i - t)) / (n - 1);
      f.points.row(i * n + j) = (place(ui, vj, t) + Eigen::Vector3d(0, 0, dz)).transpose();
      u.values.push_back(ui);
      v.values.push_back(vj);
    }
  CellBlock lines{CellType::line, {}};
  for (int i = 0; i < n; ++i)
    for (int j = 0; j + 1 < n; ++j) {
      lines.connectivity.insert(lines.connectivity.end(), {i * n + j, i * n + j + 1});
      lines.connectivity.insert(lines.connectivity.end(), {j * n + i, (j + 1) * n + i});
    }
  f.cell_data.push_back({"tension", 1, std::vector<double>(lines.size(), 1.5)});
  f.cells.push_back(std::move(lines));
  f.point_data.push_back(std::move(u));
  f.point_data.push_back(std::move(v));
  return f;
}

template <class MakeFrame>
void write_run(const std::filesystem::path& dir, const std::string& name, const std::vector<double>& times,
               const std::vector<double>& step_wall_s, MakeFrame make_frame) {
  PvdSeries series(dir, name);
  for (double t : times) series.add(make_frame(t));
  MetricsCsv metrics(dir / "metrics.csv",
                     {"time_s", "kinetic_J", "potential_J", "max_speed_m_per_s", "newton_iters", "step_wall_s"});
  for (size_t k = 0; k < step_wall_s.size(); ++k)
    metrics.row({0.01 * k, 1.0 / (k + 1), 0.5 * k, 0.1 * k, 3.0, step_wall_s[k]});
  metrics.commit();
  Json summary = Json::object();
  summary["scene"]["name"] = "synthetic-" + name;
  summary.set("git", git_revision());
  write_file_atomically(dir / "summary.json", summary.dump());
}

struct Runs {
  test::ScratchDir dir;
  std::filesystem::path yarn = dir / "yarn", fine = dir / "fine", coarse = dir / "coarse";
  Runs() {
    // A: frames at 0, 0.1, 0.2 s; B: every 0.05 s accumulated (times off by rounding only).
    std::vector<double> b_times;
    double tb = 0.0;
    for (int k = 0; k < 5; ++k, tb += 0.05) b_times.push_back(tb);
    write_run(yarn, "yarn", {0.0, 0.1, 0.2}, {1.0, 2.0, 3.0}, [](double t) { return yarn_frame(6, t, kOffset); });
    write_run(fine, "fine", {0.0, 0.1, 0.2}, {0.5, 4.0, 1.0}, [](double t) { return continuum_frame(9, t, kOffset); });
    write_run(coarse, "coarse", b_times, {3.0, 5.0, 7.0, 100.0}, [](double t) { return continuum_frame(5, t, 0.0); });
  }
};

std::string script(const char* name) { return std::string(WEAVELAB_SOURCE_DIR) + "/experiments/common/" + name; }

test::CommandResult run_script(const char* name, const std::string& args) {
  return test::run_command(std::string(test::python()) + " " + test::shell_quote(script(name)) + " " + args);
}

std::vector<std::vector<double>> read_csv_rows(const std::filesystem::path& path, std::string& header) {
  std::istringstream in(test::read_text(path));
  std::getline(in, header);
  std::vector<std::vector<double>> rows;
  for (std::string line; std::getline(in, line);) {
    std::vector<double> row;
    std::istringstream cells(line);
    for (std::string cell; std::getline(cells, cell, ',');) row.push_back(std::stod(cell));
    rows.push_back(row);
  }
  return rows;
}

void expect_one_millimetre(const std::filesystem::path& csv, double ratio) {
  std::string header;
  const auto rows = read_csv_rows(csv, header);
  EXPECT_EQ(header, "time_s,rms_distance_m,max_distance_m,step_time_ratio_B_over_A");
  ASSERT_EQ(rows.size(), 3u);  // A's frames at 0, 0.1, 0.2 s each found in B
  const double times[] = {0.0, 0.1, 0.2};
  for (size_t k = 0; k < rows.size(); ++k) {
    ASSERT_EQ(rows[k].size(), 4u);
    EXPECT_NEAR(rows[k][0], times[k], 1e-12);
    EXPECT_NEAR(rows[k][1], kOffset, 1e-12) << "RMS distance at t=" << times[k];
    EXPECT_NEAR(rows[k][2], kOffset, 1e-12) << "max distance at t=" << times[k];
    EXPECT_NEAR(rows[k][3], ratio, 1e-12);
  }
}

TEST(CompareScript, YarnAgainstContinuumIsTheKnownOffset) {
  ASSERT_TRUE(test::python_with("numpy, meshio, matplotlib"));
  Runs runs;
  const auto csv = runs.dir / "distance.csv";
  const auto png = runs.dir / "distance.png";
  const auto r = run_script(
      "compare.py", test::shell_quote(runs.yarn.string()) + " " + test::shell_quote(runs.coarse.string()) + " --out " +
                        test::shell_quote(csv.string()) + " --plot " + test::shell_quote(png.string()));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  expect_one_millimetre(csv, 6.0 / 2.0);  // median step 6 s (B) over 2 s (A)
  EXPECT_GT(std::filesystem::file_size(png), 1000u);
  EXPECT_GT(std::filesystem::file_size(runs.dir / "distance.svg"), 1000u);
}

TEST(CompareScript, ContinuumAgainstContinuumUsesUv) {
  ASSERT_TRUE(test::python_with("numpy, meshio"));
  Runs runs;
  const auto csv = runs.dir / "distance.csv";
  const auto r =
      run_script("compare.py", test::shell_quote(runs.fine.string()) + " " + test::shell_quote(runs.coarse.string()) +
                                   " --out " + test::shell_quote(csv.string()));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  expect_one_millimetre(csv, 6.0 / 1.0);
}

TEST(CompareScript, PointsOutsideTheSurfaceUseTheNearestTriangle) {
  ASSERT_TRUE(test::python_with("numpy, meshio"));
  Runs runs;
  // Two crossings: one inside B's material square, one 1 cm left of its edge u = 0.
  const auto outside = runs.dir / "outside";
  write_run(outside, "outside", {0.0}, {1.0}, [](double t) {
    Frame f;
    f.time = t;
    f.points.resize(2, 3);
    f.points.row(0) = (place(0.05, 0.05, t) + Eigen::Vector3d(0, 0, kOffset)).transpose();
    f.points.row(1) = (place(-0.01, 0.05, t) + Eigen::Vector3d(0, 0, kOffset)).transpose();
    f.point_data.push_back({"u", 1, {0.05, -0.01}});
    f.point_data.push_back({"v", 1, {0.05, 0.05}});
    f.cells.push_back({CellType::line, {0, 1}});  // meshio 5 cannot read a VTU without cells
    return f;
  });
  const auto csv = runs.dir / "distance.csv";
  const auto r =
      run_script("compare.py", test::shell_quote(outside.string()) + " " + test::shell_quote(runs.coarse.string()) +
                                   " --out " + test::shell_quote(csv.string()));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  std::string header;
  const auto rows = read_csv_rows(csv, header);
  ASSERT_EQ(rows.size(), 1u);
  // The outside point is compared with B at (0, 0.05): place(-0.01,·) − place(0,·) + 1 mm z
  // = (−0.01, 0, −0.003 + 0.001) m.
  const double far = std::sqrt(0.01 * 0.01 + 0.002 * 0.002);
  EXPECT_NEAR(rows[0][2], far, 1e-12);
  EXPECT_NEAR(rows[0][1], std::sqrt((kOffset * kOffset + far * far) / 2), 1e-12);
}

TEST(CompareScript, StepTimeRatioSkipsTheInitialStateRow) {
  ASSERT_TRUE(test::python_with("numpy, meshio"));
  Runs runs;
  // The driver's first metrics row is the initial state, with 0 s of step time:
  // it is no step, so A's median step is that of {2, 3} s.
  const auto start = runs.dir / "start";
  write_run(start, "start", {0.0, 0.1, 0.2}, {0.0, 2.0, 3.0}, [](double t) { return yarn_frame(6, t, kOffset); });
  const auto csv = runs.dir / "distance.csv";
  const auto r =
      run_script("compare.py", test::shell_quote(start.string()) + " " + test::shell_quote(runs.coarse.string()) +
                                   " --out " + test::shell_quote(csv.string()));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  expect_one_millimetre(csv, 6.0 / 2.5);
}

// Two runs of the same yarn model are paired point by point, and the closing
// lines set the distance (1 mm) beside each run's time error from its summary.
TEST(CompareScript, SameModelRunsAndTheErrorBudget) {
  ASSERT_TRUE(test::python_with("numpy, meshio"));
  Runs runs;
  const auto lower = runs.dir / "lower";
  write_run(lower, "lower", {0.0, 0.1, 0.2}, {1.0, 2.0, 3.0}, [](double t) { return yarn_frame(6, t, 0.0); });
  auto with_time_error = [](const std::filesystem::path& run, double mean_rms_m) {
    Json te = Json::object();
    te.set("method", "richardson");
    te.set("mean_rms_m", mean_rms_m);
    te.set("max_m", 2 * mean_rms_m);
    Json summary = Json::object();
    summary.set("time_error", te);
    write_file_atomically(run / "summary.json", summary.dump());
  };
  const auto csv = runs.dir / "d.csv";
  const std::string args = test::shell_quote(runs.yarn.string()) + " " + test::shell_quote(lower.string()) + " --out " +
                           test::shell_quote(csv.string());
  auto r = run_script("compare.py", args);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  expect_one_millimetre(csv, 1.0);
  EXPECT_NE(r.output.find("distance: 1 mm"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("budget: incomplete"), std::string::npos) << r.output;
  with_time_error(runs.yarn, 2e-5);
  with_time_error(lower, 5e-5);
  r = run_script("compare.py", args);
  EXPECT_NE(r.output.find("time error of B (" + lower.string() + "): 0.05 mm mean RMS, 0.1 mm max (richardson)"),
            std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find("budget: both time errors are below a tenth of the distance"), std::string::npos) << r.output;
  with_time_error(lower, 3e-4);
  r = run_script("compare.py", args);
  EXPECT_NE(r.output.find("above a tenth of the distance"), std::string::npos) << r.output;
  with_time_error(lower, 2e-3);
  r = run_script("compare.py", args);
  EXPECT_NE(r.output.find("EXCEEDS the distance"), std::string::npos) << r.output;
}

TEST(CompareScript, MissingRunFolderExitsWithStatus2) {
  ASSERT_TRUE(test::python_with("numpy, meshio"));
  Runs runs;
  const auto missing = runs.dir / "no-such-run";
  const auto r =
      run_script("compare.py", test::shell_quote(missing.string()) + " " + test::shell_quote(runs.coarse.string()) +
                                   " --out " + test::shell_quote((runs.dir / "d.csv").string()));
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find(missing.string()), std::string::npos) << r.output;
  EXPECT_FALSE(std::filesystem::exists(runs.dir / "d.csv"));
  std::filesystem::remove(runs.coarse / "metrics.csv");
  const auto r2 =
      run_script("compare.py", test::shell_quote(runs.yarn.string()) + " " + test::shell_quote(runs.coarse.string()) +
                                   " --out " + test::shell_quote((runs.dir / "d.csv").string()));
  EXPECT_EQ(r2.exit_code, 2) << r2.output;
  EXPECT_NE(r2.output.find("metrics.csv"), std::string::npos) << r2.output;
}

TEST(PlotScripts, WriteImagesForSyntheticRuns) {
  ASSERT_TRUE(test::python_with("numpy, meshio, matplotlib"));
  Runs runs;
  const auto tension = runs.dir / "tension.png";
  auto r = run_script("plot_tension.py", test::shell_quote(runs.coarse.string()) + " --frame 2 --out " +
                                             test::shell_quote(tension.string()));
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_GT(std::filesystem::exists(tension) ? std::filesystem::file_size(tension) : 0u, 1000u);
  r = run_script("plot_tension.py",
                 test::shell_quote(runs.coarse.string()) + " --frame 9 --out " + test::shell_quote(tension.string()));
  EXPECT_EQ(r.exit_code, 2) << r.output;  // only 5 frames
  const auto energy = runs.dir / "energy.png";
  r = run_script("plot_run.py", test::shell_quote(runs.yarn.string()) + " --out " + test::shell_quote(energy.string()));
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_TRUE(std::filesystem::exists(energy));
  EXPECT_TRUE(std::filesystem::exists(runs.dir / "energy.svg"));
}

}  // namespace
}  // namespace wl
