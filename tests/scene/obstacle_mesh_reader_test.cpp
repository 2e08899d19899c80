// Mesh obstacles in a scene (docs/models.md §3.11.9, experiments/scenes/README.md):
// a good OBJ is read, scaled and oriented; every bad input is a SceneError
// located in the scene (file, line, key) or in the OBJ (file, line, statement).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "models/common/obstacle.h"
#include "models/scene/obstacle_mesh.h"
#include "models/scene/scene.h"
#include "tests/support/obstacle_meshes.h"

namespace wl {
namespace {

namespace fs = std::filesystem;

class MeshScene : public ::testing::Test {
 protected:
  void SetUp() override { dir_ = test::temp_folder(); }
  void TearDown() override { fs::remove_all(dir_); }
  // A scene with one mesh obstacle whose entry ends with `keys`; the OBJ text as m.obj.
  std::string scene(const std::string& keys) const {
    return "[[obstacles]]\nshape = \"mesh\"\ncenter_m = [0, 0, -1]\n" + keys;
  }
  void obj(const std::string& text, const std::string& name = "m.obj") const { std::ofstream(dir_ / name) << text; }
  Scene load(const std::string& text) const {
    std::ofstream(dir_ / "s.toml") << text;
    return load_scene((dir_ / "s.toml").string());
  }
  // Expects a SceneError at file:line with `key` and `fragment` in its message.
  void expect_error(const std::string& text, const std::string& file, int line, const std::string& key,
                    const std::string& fragment) const {
    try {
      load(text);
      ADD_FAILURE() << "no error for:\n" << text;
    } catch (const SceneError& e) {
      EXPECT_EQ(fs::path(e.file).filename().string(), file) << e.what();
      EXPECT_EQ(e.line, line) << e.what();
      EXPECT_EQ(e.key, key) << e.what();
      EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
    }
  }
  fs::path dir_;
};

const std::string kTetra = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 2 3 4\nf 1 4 3\n";

TEST_F(MeshScene, AGoodMeshIsReadScaledAndOrientedOutwards) {
  // The tetrahedron written with every face turned inwards, in millimetres,
  // with comments, normals, groups, a quad split in a fan and negative indices.
  obj("# inward\no tet\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nvn 0 0 1\ng a\ns off\nf 1 2 3\nf 1//1 4 2\n"
      "f -3/1 -1 -2\nf 1 3/2/1 4\n");
  const Scene s = load(scene("file = \"m.obj\"\nscale = 0.001\nside = \"outside\"\nfriction_coefficient = 0.2\n"));
  ASSERT_EQ(s.obstacles.size(), 1u);
  const ObstacleSpec& o = s.obstacles[0];
  EXPECT_EQ(o.shape, ObstacleSpec::Shape::mesh);
  EXPECT_EQ(o.scale, 0.001);
  ASSERT_TRUE(o.mesh);
  EXPECT_EQ(o.mesh->faces.size(), 4u);
  EXPECT_EQ(o.mesh->vertices[1][0], 0.001);
  EXPECT_EQ(o.mesh->face_lines[2], 12);
  const Obstacle body(o);  // oriented outwards: the centroid is inside, a far point outside
  EXPECT_NEAR(body.signed_distance(Vec3(0.0001, 0.0001, -1 + 0.0001), 0.0), -0.0001, 1e-12);
  EXPECT_NEAR(body.signed_distance(Vec3(-0.001, 0.0002, -1 + 0.0003), 0.0), 0.001, 1e-12);
  // A quad "f 1 2 3 4" becomes two triangles from its first vertex.
  obj("v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n", "q.obj");
  const Scene q = load(scene("file = \"q.obj\"\nside = \"both\"\n"));
  EXPECT_EQ(q.obstacles[0].mesh->faces, (std::vector<std::array<int, 3>>{{0, 1, 2}, {0, 2, 3}}));
}

TEST_F(MeshScene, BadScenesAreLocatedInTheScene) {
  obj(kTetra);
  expect_error(scene("file = \"nope.obj\"\n"), "s.toml", 4, "obstacles[0].file", "looked for");
  expect_error(scene("scale = 0.1\n"), "s.toml", 1, "obstacles[0].file", "required for shape = \"mesh\"");
  expect_error(scene("file = \"m.obj\"\nscale = 0\n"), "s.toml", 5, "obstacles[0].scale", "a number > 0");
  expect_error(scene("file = \"m.obj\"\nscale = -2.0\n"), "s.toml", 5, "obstacles[0].scale", "a number > 0");
  expect_error(scene("file = \"m.obj\"\nside = \"inside\"\n"), "s.toml", 5, "obstacles[0].side", "\"both\"");
  expect_error(scene("file = \"m.obj\"\nradius_m = 0.1\n"), "s.toml", 5, "obstacles[0].radius_m", "file");
  // A scale whose mesh cubes past the doubles (or below them) is refused at the scale, not as a degenerate triangle.
  for (const char* scale : {"1e300", "1e101", "1e-300"})
    expect_error(scene(std::string("file = \"m.obj\"\nscale = ") + scale + "\n"), "s.toml", 5, "obstacles[0].scale",
                 "keeps the mesh's largest coordinate (1 in the file) within 1e-100 to 1e100 m once scaled");
  EXPECT_EQ(load(scene("file = \"m.obj\"\nscale = 1e100\n")).obstacles[0].mesh->vertices[1][0], 1e100);
}

TEST_F(MeshScene, BadMeshFilesAreLocatedInTheMesh) {
  struct Case {
    std::string obj;  // the file's text
    bool two_sided;   // side = "both", else "outside"
    int line;
    std::string key, fragment;
  };
  const std::string tri = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
  const std::vector<Case> cases = {
      {"v 0 0 0\nv 1 0 0\nv 0 x 0\nf 1 2 3\n", false, 3, "v", "3 finite numbers"},
      {tri + "f 1 2 4\n", true, 4, "f", "from 1 to 3"},
      {tri + "f 1 2 0\n", true, 4, "f", "vertex references"},
      {tri + "f 1 2\n", true, 4, "f", "at least 3 vertices"},
      {"\x89PNG\r\n\x1a\n\x00\x00garbage", false, 1, "?PNG", "an OBJ statement"},
      {tri + "l 1 2\n", false, 4, "l", "an OBJ statement"},
      {tri, false, 3, "f", "at least one triangle"},
      {"v 0 0 0\nv 1 0 0\nv 2 0 0\nv 0 1 0\nf 1 4 2\nf 1 2 3\n", true, 6, "f", "positive area"},  // collinear
      {tri + "f 1 2 2\n", true, 4, "f", "positive area"},                                         // a repeated vertex
      {tri + "f 1 2 3\n", false, 4, "f", "a closed surface"},  // open, asked to bound a solid
      // the tetrahedron with its last face turned
      {"v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 2 3 4\nf 1 3 4\n", false, 5, "f",
       "the face on line 8 (inconsistent orientation)"},
  };
  for (const Case& c : cases) {
    obj(c.obj);
    expect_error(scene(std::string("file = \"m.obj\"\n") + (c.two_sided ? "side = \"both\"\n" : "")), "m.obj", c.line,
                 c.key, c.fragment);
  }
}

}  // namespace
}  // namespace wl
