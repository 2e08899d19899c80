#include "output/vtu_writer.h"

#include <gtest/gtest.h>

#include "output/atomic_file.h"
#include "tests/output/output_test_util.h"

namespace wl {
namespace {

// Five points, two triangles then three lines; arrays with 1 and 3 components.
// The Python side states the same numbers as Python expressions, so it checks
// the file against values it did not read from the writer.
Frame small_frame() {
  Frame f;
  f.time = 0.125;
  f.points.resize(5, 3);
  f.points << 0.0, 0.0, 0.0, 1.0 / 3.0, 0.0, -2.5e-3, 1.0, 0.7, 0.1, 0.0, 1.0, 1e-15, -2.0, 3.0, 12345.678;
  f.cells.push_back({CellType::triangle, {0, 1, 2, 0, 2, 3}});
  f.cells.push_back({CellType::line, {0, 4, 4, 3, 1, 4}});
  f.point_data.push_back({"u", 1, {0.0, 0.1, 0.2, 1.0 / 7.0, -5.0}});
  f.point_data.push_back({"velocity", 3, {1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 2.0 / 3.0}});
  f.cell_data.push_back({"tension", 1, {10.5, -1.0 / 3.0, 7.0, 8.0, 9.0}});
  f.cell_data.push_back({"direction", 3, {1, 0, 0, 0, 1, 0, 0, 0, 1, 0.5, 0.5, 0, -1, -1, -1}});
  return f;
}

const char* kCheckScript = R"PY(
import sys
import numpy as np
import meshio

m = meshio.read(sys.argv[1])
problems = []
def close(name, got, want):
    got = np.asarray(got, dtype=float); want = np.asarray(want, dtype=float)
    if got.shape != want.shape:
        problems.append(f"{name}: shape {got.shape} != {want.shape}")
    elif not np.allclose(got, want, rtol=1e-12, atol=1e-12):
        problems.append(f"{name}: {got.tolist()} != {want.tolist()}")

close("points", m.points, [[0, 0, 0], [1/3, 0, -2.5e-3], [1, 0.7, 0.1], [0, 1, 1e-15], [-2, 3, 12345.678]])
types = [b.type for b in m.cells]
if types != ["triangle", "line"]:
    problems.append(f"cell block types {types}")
else:
    close("triangles", m.cells[0].data, [[0, 1, 2], [0, 2, 3]])
    close("lines", m.cells[1].data, [[0, 4], [4, 3], [1, 4]])
if sorted(m.point_data) != ["u", "velocity"]:
    problems.append(f"point data names {sorted(m.point_data)}")
else:
    close("u", m.point_data["u"], [0, 0.1, 0.2, 1/7, -5])
    close("velocity", m.point_data["velocity"],
          [[1, 2, 3], [4, 5, 6], [7, 8, 9], [10, 11, 12], [13, 14, 2/3]])
if sorted(m.cell_data) != ["direction", "tension"]:
    problems.append(f"cell data names {sorted(m.cell_data)}")
else:
    t = m.cell_data["tension"]
    close("tension triangles", t[0], [10.5, -1/3])
    close("tension lines", t[1], [7, 8, 9])
    d = m.cell_data["direction"]
    close("direction triangles", d[0], [[1, 0, 0], [0, 1, 0]])
    close("direction lines", d[1], [[0, 0, 1], [0.5, 0.5, 0], [-1, -1, -1]])
if problems:
    print("\n".join(problems))
    sys.exit(1)
print("OK")
)PY";

TEST(VtuWriter, SmallFrameReadsBackWithMeshio) {
  ASSERT_TRUE(test::python_with("numpy, meshio"));
  test::ScratchDir dir;
  const auto file = dir / "frame.vtu";
  write_file_atomically(file, to_vtu(small_frame()));
  const auto r = test::run_python_script(dir.path(), kCheckScript, test::shell_quote(file.string()));
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("OK"), std::string::npos) << r.output;
}

TEST(VtuWriter, WritesFullDoublePrecision) {
  Frame f;
  f.points.resize(1, 3);
  f.points << 1.0 / 3.0, 0.1, -2.0 / 7.0;
  const std::string vtu = to_vtu(f);
  char expected[128];
  std::snprintf(expected, sizeof expected, "%.17g %.17g %.17g", 1.0 / 3.0, 0.1, -2.0 / 7.0);
  EXPECT_NE(vtu.find(expected), std::string::npos) << vtu;
  EXPECT_NE(vtu.find("0.33333333333333331"), std::string::npos) << vtu;
}

TEST(VtuWriter, RejectsWrongArraySizesWithTheirName) {
  Frame f = small_frame();
  f.point_data[1].values.pop_back();
  try {
    to_vtu(f);
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("'velocity'"), std::string::npos) << e.what();
  }
  f = small_frame();
  f.cell_data[0].values.push_back(1.0);
  EXPECT_THROW(to_vtu(f), std::invalid_argument);
  f = small_frame();
  f.cells[1].connectivity.push_back(5);
  f.cells[1].connectivity.push_back(0);
  EXPECT_THROW(to_vtu(f), std::invalid_argument);  // point 5 does not exist
}

TEST(VtuWriter, EscapesArrayNames) {
  Frame f = small_frame();
  f.point_data[0].name = "a<b&\"c\"";
  const std::string vtu = to_vtu(f);
  EXPECT_NE(vtu.find("Name=\"a&lt;b&amp;&quot;c&quot;\""), std::string::npos);
}

}  // namespace
}  // namespace wl
