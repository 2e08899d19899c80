#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>

#include "models/fem/fem_mesh.h"
#include "models/fem/fem_model.h"
#include "tests/fem/fem_test_scene.h"

namespace wl {
namespace {

TEST(FemMesh, GridHasVertexAtEveryCrossing) {
  Scene s = test::fem_scene(4, 3, Scene::Pose::upright);
  const FemMesh m = build_grid_mesh(s);
  ASSERT_EQ(m.num_vertices(), 12);
  EXPECT_EQ(m.num_triangles(), 2 * 3 * 2);
  // vertex (a, b) at material (iL, jL), upright pose x = (u, 0, h − v)
  const int v = m.grid_vertex(2, 1);
  EXPECT_NEAR((m.uv[v] - Vec2(2e-3, 1e-3)).norm(), 0, 1e-15);
  EXPECT_NEAR((m.x[v] - Vec3(2e-3, 0, 0.1 - 1e-3)).norm(), 0, 1e-15);
  s.pose = Scene::Pose::flat;
  EXPECT_NEAR((build_grid_mesh(s).x[v] - Vec3(2e-3, 1e-3, 0.1)).norm(), 0, 1e-15);
}

TEST(FemMesh, TrianglesAreCcwInUvAlongTheDiagonal) {
  const FemMesh m = build_grid_mesh(test::fem_scene(3, 3));
  for (const auto& t : m.triangles) {
    const Vec2 e1 = m.uv[t[1]] - m.uv[t[0]], e2 = m.uv[t[2]] - m.uv[t[0]];
    EXPECT_NEAR(e1.x() * e2.y() - e1.y() * e2.x(), 1e-6, 1e-18);  // 2·area = L²
  }
  // first cell: (0,0),(1,0),(1,1) and (0,0),(1,1),(0,1)
  EXPECT_EQ(m.triangles[0], (std::array<int, 3>{0, 1, 4}));
  EXPECT_EQ(m.triangles[1], (std::array<int, 3>{0, 4, 3}));
}

TEST(FemMesh, StrideKeepsLastRowAndColumn) {
  Scene s = test::fem_scene(6, 5);
  s.fem.stride = 2;
  const FemMesh m = build_grid_mesh(s);
  EXPECT_EQ(m.grid_i, (std::vector<int>{0, 2, 4, 5}));
  EXPECT_EQ(m.grid_j, (std::vector<int>{0, 2, 4}));
  EXPECT_NEAR((m.uv[m.grid_vertex(3, 2)] - Vec2(5e-3, 4e-3)).norm(), 0, 1e-15);
  EXPECT_EQ(m.num_triangles(), 2 * 3 * 2);
}

TEST(FemMesh, HingesAreInteriorEdgesWithConsistentOrientation) {
  const FemMesh m = build_grid_mesh(test::fem_scene(3, 3));
  const auto h = interior_hinges(m);
  // 2×2 cells: interior edges = 4 diagonals + 2 vertical + 2 horizontal
  EXPECT_EQ(h.size(), 8u);
  for (const Hinge& e : h) {
    // v0→v1 runs CCW in tri0 whose apex is v2; v1→v0 in tri1 with apex v3
    const auto& t0 = m.triangles[e.tri0];
    const auto& t1 = m.triangles[e.tri1];
    bool in0 = false, in1 = false;
    for (int k = 0; k < 3; ++k) {
      in0 |= t0[k] == e.v[0] && t0[(k + 1) % 3] == e.v[1] && t0[(k + 2) % 3] == e.v[2];
      in1 |= t1[k] == e.v[1] && t1[(k + 1) % 3] == e.v[0] && t1[(k + 2) % 3] == e.v[3];
    }
    EXPECT_TRUE(in0 && in1);
  }
}

class VtuFile : public ::testing::Test {
 protected:
  std::string write(const std::string& text) {
    path_ = (std::filesystem::temp_directory_path() / ("wl_fem_" + std::to_string(::getpid()) + ".vtu")).string();
    std::ofstream(path_) << text;
    return path_;
  }
  void TearDown() override {
    if (!path_.empty()) std::remove(path_.c_str());
  }
  std::string path_;
};

// As meshio 5 writes it (`binary=False`); the second triangle is clockwise in UV.
std::string vtu(const std::string& uv_name = "uv", const std::string& format = "ascii", int type2 = 5) {
  return R"(<?xml version="1.0"?>
<VTKFile type="UnstructuredGrid" version="0.1" byte_order="LittleEndian">
<!--This file was created by meshio v5.0.0-->
<UnstructuredGrid>
<Piece NumberOfPoints="4" NumberOfCells="2">
<Points>
<DataArray type="Float64" Name="Points" NumberOfComponents="3" format=")" +
         format + R"(">
0 0 1  0.01 0 1  0.01 0.01 1  0 0.01 1
</DataArray>
</Points>
<Cells>
<DataArray type="Int64" Name="connectivity" format="ascii">
0 1 2 0 3 2
</DataArray>
<DataArray type="Int64" Name="offsets" format="ascii">
3 6
</DataArray>
<DataArray type="Int64" Name="types" format="ascii">
5 )" + std::to_string(type2) +
         R"(
</DataArray>
</Cells>
<PointData>
<DataArray type="Float64" Name=")" +
         uv_name + R"(" NumberOfComponents="2" format="ascii">
0.00000000000e+00 0 0.01 0 0.01 0.01 0 1.0e-2
</DataArray>
</PointData>
</Piece>
</UnstructuredGrid>
</VTKFile>
)";
}

TEST_F(VtuFile, ReadsTrianglesPointsAndUv) {
  const FemMesh m = read_vtu_mesh(write(vtu()));
  ASSERT_EQ(m.num_vertices(), 4);
  ASSERT_EQ(m.num_triangles(), 2);
  EXPECT_NEAR((m.x[2] - Vec3(0.01, 0.01, 1)).norm(), 0, 1e-15);
  EXPECT_NEAR((m.uv[3] - Vec2(0, 0.01)).norm(), 0, 1e-15);
  EXPECT_EQ(m.triangles[1], (std::array<int, 3>{0, 2, 3}));  // reoriented CCW
  EXPECT_EQ(interior_hinges(m).size(), 1u);
  EXPECT_FALSE(m.is_grid());
}

TEST_F(VtuFile, AcceptsMeshioObjTextureName) { EXPECT_EQ(read_vtu_mesh(write(vtu("obj:vt"))).num_triangles(), 2); }

TEST_F(VtuFile, BadFilesGiveClearErrors) {
  auto message = [&](const std::string& text) {
    try {
      read_vtu_mesh(write(text));
    } catch (const FemMeshError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message(vtu("velocity")).find("no point-data array \"uv\""), std::string::npos);
  EXPECT_NE(message(vtu("uv", "binary")).find(":7: DataArray 'Points' has format 'binary'"), std::string::npos)
      << message(vtu("uv", "binary"));
  EXPECT_NE(message(vtu("uv", "ascii", 9)).find("cell 1 has VTK type 9, expected 5 (triangle)"), std::string::npos);
  EXPECT_NE(message("<VTKFile type=\"PolyData\">").find("expected 'UnstructuredGrid'"), std::string::npos);
  try {
    read_vtu_mesh("/nonexistent/dir/mesh.vtu");
    FAIL();
  } catch (const FemMeshError& e) {
    EXPECT_NE(std::string(e.what()).find("mesh.vtu:0: cannot open"), std::string::npos);
  }
}

// `text` with the first occurrence of `from` replaced by `to`.
std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return at == std::string::npos ? text : text.replace(at, from.size(), to);
}
std::string vtu_with(const std::string& from, const std::string& to) { return replaced(vtu(), from, to); }

TEST_F(VtuFile, BrokenMeshesAreLocatedErrors) {
  struct Case {
    std::string text, fragment;
  };
  const Case cases[] = {
      {"", ":1: no <UnstructuredGrid>"},
      {vtu().substr(0, vtu().find("</DataArray>")), "is not closed"},
      {vtu_with("0 0 1  0.01", "0 nan 1  0.01"), "point 0 has a non-finite"},
      {vtu_with("0 1 2 0 3 2", "0 1 2 0 7 2"), "refers to point"},
      {vtu_with("0 1 2 0 3 2", "0 1 2 0 1.5 2"), "refers to point"},
      {vtu_with("NumberOfPoints=\"4\"", "NumberOfPoints=\"99999999999\""), ":5: Piece NumberOfPoints"},
      {vtu_with("NumberOfPoints=\"4\"", "NumberOfPoints=\"-4\""), ":5: Piece NumberOfPoints"},
      {vtu_with("0 0.01 1\n", "0 0.01 1  0.5 0.5 1\n"), ":7: Points: expected"},
      // a fifth point no triangle uses
      {replaced(
           replaced(vtu_with("NumberOfPoints=\"4\"", "NumberOfPoints=\"5\""), "0 0.01 1\n", "0 0.01 1 0.5 0.5 1\n"),
           "0 1.0e-2", "0 1.0e-2 0.005 0.005"),
       "point 4 is used by no triangle"},
      {vtu_with("0.01 0.01 0 1.0e-2", "0.01 0 0 1.0e-2"), "degenerate"},
  };
  for (const Case& c : cases) {
    try {
      read_vtu_mesh(write(c.text));
      ADD_FAILURE() << "accepted:\n" << c.text;
    } catch (const FemMeshError& e) {
      EXPECT_NE(std::string(e.what()).find(c.fragment), std::string::npos) << e.what();
      EXPECT_EQ(std::string(e.what()).rfind(path_ + ":", 0), 0u) << e.what();
      EXPECT_TRUE(dynamic_cast<const std::invalid_argument*>(&e)) << "a bad mesh is bad input (exit 2)";
    }
  }
}

TEST_F(VtuFile, ModelFromMeshFileMapsPinsToNearestVertex) {
  Scene s = test::fem_scene(11, 11);  // L = 1 mm: crossing (10, 10) at uv (0.01, 0.01)
  s.fem.mesh_file = write(vtu());
  s.pins = {{10, 10}, {1, 0}};  // (1, 0) is 1 mm from vertex 0
  FemModel m(s);
  EXPECT_EQ(m.mesh().num_vertices(), 4);
  EXPECT_EQ(m.num_dofs(), 12);
  EXPECT_EQ(m.vertex_of_node({10, 10}), 2);
  EXPECT_EQ(m.vertex_of_node({1, 0}), 0);
  EXPECT_EQ(m.fixed_dofs().size(), 6u);
  EXPECT_LT(m.initial_q().segment<3>(6).norm(), 2.0);  // positions from the file (z = 1)
  EXPECT_DOUBLE_EQ(m.initial_q()[8], 1.0);
  s.pins = {{30, 30}};  // far outside the mesh
  EXPECT_THROW(FemModel{s}, std::invalid_argument);
}

}  // namespace
}  // namespace wl
