#include "output/pvd_series.h"

#include <gtest/gtest.h>

#include "tests/output/output_test_util.h"

namespace wl {
namespace {

Frame triangle_at(double time, double z) {
  Frame f;
  f.time = time;
  f.points.resize(3, 3);
  f.points << 0, 0, z, 1, 0, z, 0, 1, z;
  f.cells.push_back({CellType::triangle, {0, 1, 2}});
  return f;
}

// Parses the .pvd with Python's XML parser, checks the listed timesteps and
// that each listed file (relative to the .pvd) holds the expected frame.
const char* kCheckScript = R"PY(
import sys, os
import xml.etree.ElementTree as ET
import numpy as np
import meshio

pvd = sys.argv[1]
want_times = [float(t) for t in sys.argv[2:]]
root = ET.parse(pvd).getroot()
assert root.get("type") == "Collection", root.get("type")
sets = root.find("Collection").findall("DataSet")
times = [float(s.get("timestep")) for s in sets]
if times != want_times:
    sys.exit(f"timesteps {times} != {want_times}")
for k, s in enumerate(sets):
    f = s.get("file")
    if os.path.isabs(f):
        sys.exit(f"absolute path {f}")
    m = meshio.read(os.path.join(os.path.dirname(pvd), f))
    z = m.points[:, 2]
    if not np.allclose(z, 0.01 * k, rtol=0, atol=1e-15):
        sys.exit(f"frame {k} ({f}) has z {z}")
print("OK")
)PY";

TEST(PvdSeries, ListsFramesInOrderAfterEveryFrame) {
  ASSERT_TRUE(test::python_with("numpy, meshio"));
  test::ScratchDir dir;
  const auto run = dir / "run";
  PvdSeries series(run, "cloth");
  EXPECT_EQ(series.pvd_path(), run / "cloth.pvd");
  std::string want_times;
  const double times[] = {0.0, 0.5, 1.25};
  for (int k = 0; k <= 3; ++k) {
    // Before frame k is added (as if the run stopped here), the series holds frames 0..k-1.
    if (k == 1 || k == 3) {  // each check starts Python (~1 s), so check two states
      const auto r =
          test::run_python_script(dir.path(), kCheckScript, test::shell_quote(series.pvd_path().string()) + want_times);
      EXPECT_EQ(r.exit_code, 0) << "after " << k << " frames:\n" << r.output;
    }
    if (k == 3) break;
    series.add(triangle_at(times[k], 0.01 * k));
    want_times.append(1, ' ').append(std::to_string(times[k]));  // (not " " + ...: GCC 12 -Wrestrict false positive)
  }
  EXPECT_EQ(series.size(), 3);
  EXPECT_TRUE(std::filesystem::exists(run / "frames" / "cloth_00000.vtu"));
  EXPECT_TRUE(std::filesystem::exists(run / "frames" / "cloth_00002.vtu"));
  EXPECT_EQ(test::count_entries(run / "frames"), 3);  // no temporaries left
  EXPECT_EQ(test::count_entries(run), 2);             // cloth.pvd and frames/
}

TEST(PvdSeries, FrameNamesAreZeroPaddedAndRelative) {
  test::ScratchDir dir;
  PvdSeries series(dir.path(), "yarn");
  EXPECT_EQ(series.relative_frame_path(0), "frames/yarn_00000.vtu");
  EXPECT_EQ(series.relative_frame_path(123), "frames/yarn_00123.vtu");
  series.add(triangle_at(0.25, 0.0));
  const std::string pvd = test::read_text(series.pvd_path());
  EXPECT_NE(pvd.find("timestep=\"0.25\""), std::string::npos) << pvd;
  EXPECT_NE(pvd.find("file=\"frames/yarn_00000.vtu\""), std::string::npos) << pvd;
}

TEST(PvdSeries, RejectsBadBasename) {
  test::ScratchDir dir;
  EXPECT_THROW(PvdSeries(dir.path(), ""), std::invalid_argument);
  EXPECT_THROW(PvdSeries(dir.path(), "a/b"), std::invalid_argument);
}

}  // namespace
}  // namespace wl
