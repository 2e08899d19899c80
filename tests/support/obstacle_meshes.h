// Triangle-mesh obstacles for tests (docs/models.md §3.11.9): small OBJ files
// written into a temporary folder and read back by the scene's reader.
#pragma once
#include <array>
#include <filesystem>
#include <string>
#include <vector>

#include "models/core/types.h"
#include "models/scene/scene.h"

namespace wl::test {

struct PolyMesh {
  std::vector<Vec3> vertices;
  std::vector<std::vector<int>> faces;  // 0-based, any number of corners
};

// The box [−h, h] (8 vertices, 6 quads, counter-clockwise seen from outside).
PolyMesh box_mesh(const Vec3& h);
// The square [−a, a]² of the plane z = 0 as two triangles (open).
PolyMesh square_mesh(double a);

// Writes `m` as OBJ text (1-based faces) to `path`, coordinates divided by `scale`.
void write_obj(const std::filesystem::path& path, const PolyMesh& m, double scale = 1.0);

// A mesh obstacle read from `path` as the scene reader does (scale, side,
// oriented when closed), at pose (center, rotation) with velocity v.
ObstacleSpec mesh_obstacle(const std::filesystem::path& path, ObstacleSpec::Side side, double scale = 1.0,
                           const Vec3& center = Vec3::Zero(), const Vec3& rotation_deg = Vec3::Zero());

// The unit icosphere shipped with the scenes (experiments/scenes/meshes/icosphere.obj).
std::filesystem::path icosphere_file();

// x = c + R p with R = R_z R_y R_x (the scene's convention), computed here
// independently of the model code.
Vec3 world_point(const ObstacleSpec& s, const Vec3& p);

// A fresh temporary folder named after the running test.
std::filesystem::path temp_folder();

}  // namespace wl::test
