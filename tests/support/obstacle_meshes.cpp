#include "tests/support/obstacle_meshes.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <fstream>
#include <iomanip>
#include <memory>
#include <numbers>

#include <Eigen/Geometry>

#include "models/scene/obstacle_mesh.h"

namespace wl::test {

PolyMesh box_mesh(const Vec3& h) {
  PolyMesh m;
  for (int k = 0; k < 8; ++k)
    m.vertices.push_back(h.cwiseProduct(Vec3(k & 1 ? 1.0 : -1.0, k & 2 ? 1.0 : -1.0, k & 4 ? 1.0 : -1.0)));
  m.faces = {{0, 4, 6, 2}, {1, 3, 7, 5}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 2, 3, 1}, {4, 5, 7, 6}};
  return m;
}

PolyMesh square_mesh(double a) {
  return {{Vec3(-a, -a, 0), Vec3(a, -a, 0), Vec3(a, a, 0), Vec3(-a, a, 0)}, {{0, 1, 2}, {0, 2, 3}}};
}

void write_obj(const std::filesystem::path& path, const PolyMesh& m, double scale) {
  std::ofstream out(path);
  out << std::setprecision(17) << "# test mesh\n";
  for (const Vec3& v : m.vertices) out << "v " << v.x() / scale << " " << v.y() / scale << " " << v.z() / scale << "\n";
  for (const auto& f : m.faces) {
    out << "f";
    for (int i : f) out << " " << i + 1;
    out << "\n";
  }
}

ObstacleSpec mesh_obstacle(const std::filesystem::path& path, ObstacleSpec::Side side, double scale, const Vec3& center,
                           const Vec3& rotation_deg) {
  ObstacleSpec s;
  s.shape = ObstacleSpec::Shape::mesh;
  s.mesh_file = path.string();
  s.scale = scale;
  s.side = side;
  s.center_m = {center.x(), center.y(), center.z()};
  s.rotation_deg = {rotation_deg.x(), rotation_deg.y(), rotation_deg.z()};
  auto mesh = std::make_shared<ObstacleMesh>(read_obj_mesh(s.mesh_file, scale));
  if (side == ObstacleSpec::Side::outside) orient_closed_mesh(*mesh);
  s.mesh = std::move(mesh);
  return s;
}

Vec3 world_point(const ObstacleSpec& s, const Vec3& p) {
  const double k = std::numbers::pi / 180.0;
  const Mat3 R = (Eigen::AngleAxisd(k * s.rotation_deg[2], Vec3::UnitZ()) *
                  Eigen::AngleAxisd(k * s.rotation_deg[1], Vec3::UnitY()) *
                  Eigen::AngleAxisd(k * s.rotation_deg[0], Vec3::UnitX()))
                     .toRotationMatrix();
  return Vec3(s.center_m[0], s.center_m[1], s.center_m[2]) + R * p;
}

std::filesystem::path icosphere_file() {
  return std::filesystem::path(WEAVELAB_SOURCE_DIR) / "experiments/scenes/meshes/icosphere.obj";
}

std::filesystem::path temp_folder() {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  std::string name = std::string(info->test_suite_name()) + "_" + info->name();
  std::replace(name.begin(), name.end(), '/', '_');
  const auto dir =
      std::filesystem::temp_directory_path() / ("weavelab_mesh_" + std::to_string(::getpid()) + "_" + name);
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

}  // namespace wl::test
