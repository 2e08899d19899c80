#include "models/scene/obstacle_mesh.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <fstream>
#include <map>
#include <sstream>

#include <Eigen/Geometry>

#include "models/core/types.h"

namespace wl {
namespace {

// Text as it can be printed: ASCII, at most 60 characters, '?' for the rest.
std::string printable(const std::string& text) {
  std::string s;
  for (char c : text.substr(0, 60)) s += std::isprint(static_cast<unsigned char>(c)) ? c : '?';
  return s + (text.size() > 60 ? "…" : "");
}

Vec3 mesh_vertex(const std::array<double, 3>& a) { return Vec3(a[0], a[1], a[2]); }

// A vertex reference "i", "i/t", "i//n" or "i/t/n" → 0-based index, or −1.
int vertex_index(const std::string& token, int vertices_so_far) {
  const std::string head = token.substr(0, token.find('/'));
  if (head.empty()) return -1;
  size_t used = 0;
  long long i = 0;
  try {
    i = std::stoll(head, &used);
  } catch (const std::exception&) {
    return -1;
  }
  if (used != head.size() || i == 0) return -1;
  if (i < 0) i += vertices_so_far + 1;  // relative: −1 is the last vertex so far
  return i >= 1 && i <= 100000000 ? static_cast<int>(i - 1) : -1;
}

}  // namespace

ObstacleMesh read_obj_mesh(const std::string& path, double scale) {
  ObstacleMesh m;
  m.file = path;
  std::ifstream in(path, std::ios::binary);
  if (!in) throw SceneError(path, 0, "file", '"' + path + '"', "a readable OBJ file");
  auto fail = [&](int line, const std::string& key, const std::string& text, const std::string& expected) {
    throw SceneError(path, line, printable(key), '"' + printable(text) + '"', expected);
  };
  std::string text;
  int line = 0;
  std::vector<std::array<int, 2>> refs;  // (vertex, line) of every face corner, checked at the end
  while (std::getline(in, text)) {
    ++line;
    const std::string body = text.substr(0, text.find('#'));
    std::istringstream words(body);
    std::string key;
    if (!(words >> key)) continue;
    if (key == "v") {
      std::array<double, 3> x{};
      std::string w;
      int n = 0;
      while (words >> w) {
        char* end = nullptr;
        const double value = std::strtod(w.c_str(), &end);
        if (*end != '\0' || !std::isfinite(value) || n >= 4)
          fail(line, "v", text, "v x y z [w]: 3 finite numbers (and an optional weight)");
        if (n < 3) x[n] = scale * value;
        ++n;
      }
      if (n < 3) fail(line, "v", text, "v x y z [w]: 3 finite numbers (and an optional weight)");
      m.vertices.push_back(x);
    } else if (key == "f") {
      std::vector<int> corner;
      std::string w;
      while (words >> w) {
        const int i = vertex_index(w, static_cast<int>(m.vertices.size()));
        if (i < 0)
          fail(line, "f", text,
               "f with vertex references i, i/t, i//n or i/t/n (i a non-zero integer; negative counts back from the "
               "last vertex)");
        corner.push_back(i);
      }
      if (corner.size() < 3) fail(line, "f", text, "a face of at least 3 vertices");
      for (size_t k = 1; k + 1 < corner.size(); ++k) {  // a fan from the first vertex
        m.faces.push_back({corner[0], corner[k], corner[k + 1]});
        m.face_lines.push_back(line);
      }
    } else if (key != "vt" && key != "vn" && key != "vp" && key != "o" && key != "g" && key != "s" && key != "usemtl" &&
               key != "mtllib") {
      fail(line, key, text,
           "an OBJ statement of a triangle mesh (v, f; vt, vn, vp, o, g, s, usemtl, mtllib are ignored)");
    }
  }
  if (in.bad()) throw SceneError(path, line, "file", '"' + path + '"', "a readable OBJ file (read error)");
  if (m.faces.empty()) throw SceneError(path, line, "f", "no face", "a mesh with at least one triangle (f a b c)");
  const int nv = static_cast<int>(m.vertices.size());
  for (size_t f = 0; f < m.faces.size(); ++f) {
    const auto& t = m.faces[f];
    for (int v : t)
      if (v >= nv)
        throw SceneError(path, m.face_lines[f], "f", "vertex " + std::to_string(v + 1),
                         "a vertex index from 1 to " + std::to_string(nv) + " (the file's vertex count)");
    const Vec3 a = mesh_vertex(m.vertices[t[0]]), b = mesh_vertex(m.vertices[t[1]]), c = mesh_vertex(m.vertices[t[2]]);
    const double longest = std::max({(b - a).squaredNorm(), (c - b).squaredNorm(), (a - c).squaredNorm()});
    const double area2 = (b - a).cross(c - a).norm();
    if (!(area2 > 1e-12 * longest))
      throw SceneError(path, m.face_lines[f], "f",
                       "a degenerate triangle (vertices " + std::to_string(t[0] + 1) + ", " + std::to_string(t[1] + 1) +
                           ", " + std::to_string(t[2] + 1) + ", area " + std::to_string(0.5 * area2) + " m²)",
                       "a triangle of positive area (three distinct, non-collinear vertices)");
  }
  return m;
}

std::vector<std::array<int, 3>> face_neighbours(const ObstacleMesh& m) {
  std::map<std::pair<int, int>, std::vector<int>> edge_faces;  // undirected edge → faces
  const int nf = static_cast<int>(m.faces.size());
  for (int f = 0; f < nf; ++f)
    for (int k = 0; k < 3; ++k) {
      const int a = m.faces[f][k], b = m.faces[f][(k + 1) % 3];
      edge_faces[{std::min(a, b), std::max(a, b)}].push_back(f);
    }
  std::vector<std::array<int, 3>> out(nf, {-1, -1, -1});
  for (int f = 0; f < nf; ++f)
    for (int k = 0; k < 3; ++k) {
      const int a = m.faces[f][k], b = m.faces[f][(k + 1) % 3];
      const auto& faces = edge_faces[{std::min(a, b), std::max(a, b)}];
      out[f][k] = faces.size() == 2 ? faces[faces[0] == f ? 1 : 0] : faces.size() > 2 ? -2 : -1;
    }
  return out;
}

void orient_closed_mesh(ObstacleMesh& m) {
  const auto nb = face_neighbours(m);
  const std::string expected =
      "a closed surface for side = \"outside\" (every edge in exactly two faces, run in opposite directions); "
      "use side = \"both\" for an open, two-sided surface";
  for (size_t f = 0; f < m.faces.size(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int a = m.faces[f][k], b = m.faces[f][(k + 1) % 3], g = nb[f][k];
      const std::string edge = "the edge from vertex " + std::to_string(a + 1) + " to " + std::to_string(b + 1);
      if (g == -1) throw SceneError(m.file, m.face_lines[f], "f", edge + " in no other face (a hole)", expected);
      if (g == -2) throw SceneError(m.file, m.face_lines[f], "f", edge + " in more than two faces", expected);
      const auto& o = m.faces[g];
      for (int j = 0; j < 3; ++j)
        if (o[j] == a && o[(j + 1) % 3] == b)
          throw SceneError(m.file, m.face_lines[f], "f",
                           edge + " run in the same direction by the face on line " + std::to_string(m.face_lines[g]) +
                               " (inconsistent orientation)",
                           expected);
    }
  double volume6 = 0.0;  // Σ a·(b × c) = 6 × the enclosed volume
  for (const auto& t : m.faces)
    volume6 += mesh_vertex(m.vertices[t[0]]).dot(mesh_vertex(m.vertices[t[1]]).cross(mesh_vertex(m.vertices[t[2]])));
  if (volume6 < 0.0)
    for (auto& t : m.faces) std::swap(t[1], t[2]);
}

}  // namespace wl
