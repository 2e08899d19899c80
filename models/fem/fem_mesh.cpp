#include "models/fem/fem_mesh.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <map>
#include <sstream>

#include "models/fem/deformation_gradient.h"
#include "models/fem/knit_contact_mesh.h"

namespace wl {

Vec3 pose_position(const Scene& s, double u, double v) {
  // Same convention as the yarn model: upright (u, 0, h − v), flat (u, v, h).
  return s.pose == Scene::Pose::upright ? Vec3(u, 0.0, s.height_m - v) : Vec3(u, v, s.height_m);
}

namespace {

std::vector<int> lattice(int n, int stride) {
  std::vector<int> r;
  for (int i = 0; i < n; i += stride) r.push_back(i);
  if (r.back() != n - 1) r.push_back(n - 1);
  return r;
}

}  // namespace

FemMesh build_grid_mesh(const Scene& s) {
  if (s.fem.stride < 1) throw std::invalid_argument("fem.stride must be ≥ 1, got " + std::to_string(s.fem.stride));
  if (s.nodes_u() < 2 || s.nodes_v() < 2) throw std::invalid_argument("the cloth needs at least 2×2 crossings");
  FemMesh m;
  m.source = "grid";
  m.grid_i = lattice(s.nodes_u(), s.fem.stride);
  m.grid_j = lattice(s.nodes_v(), s.fem.stride);
  const int na = static_cast<int>(m.grid_i.size()), nb = static_cast<int>(m.grid_j.size());
  const double L = s.spacing_m;
  for (int b = 0; b < nb; ++b)
    for (int a = 0; a < na; ++a) {
      const double u = m.grid_i[a] * L, v = m.grid_j[b] * L;
      m.uv.emplace_back(u, v);
      m.x.push_back(pose_position(s, u, v));
    }
  add_grid_triangles(m);
  return m;
}

bool boundary_on_lattice(const Scene& s, int k) {
  for (const NodeRef& n : s.pins)
    if (n.i % k != 0 || n.j % k != 0) return false;
  for (const Handle& h : s.handles)
    if (h.node.i % k != 0 || h.node.j % k != 0) return false;
  return true;
}

void add_grid_triangles(FemMesh& m) {
  const int na = static_cast<int>(m.grid_i.size()), nb = static_cast<int>(m.grid_j.size());
  for (int b = 0; b + 1 < nb; ++b)
    for (int a = 0; a + 1 < na; ++a) {
      const int v00 = m.grid_vertex(a, b), v10 = m.grid_vertex(a + 1, b), v11 = m.grid_vertex(a + 1, b + 1),
                v01 = m.grid_vertex(a, b + 1);
      m.triangles.push_back({v00, v10, v11});
      m.triangles.push_back({v00, v11, v01});
    }
}

// ---------------------------------------------------------------------------
// A minimal reader for ASCII VTK XML UnstructuredGrid files (as meshio writes
// them with --ascii): one Piece, Points, Cells (connectivity, offsets, types)
// and PointData. Only what the FEM needs; anything else is ignored.
namespace {

struct XmlArray {
  std::string section;  // Points, Cells, PointData, CellData, ...
  std::string name;
  int components = 1;
  int line = 0;
  std::vector<double> values;
};

class VtuParser {
 public:
  VtuParser(std::string path) : path_(std::move(path)) {
    std::ifstream in(path_, std::ios::binary);
    if (!in) fail(0, "cannot open the mesh file");
    std::ostringstream ss;
    ss << in.rdbuf();
    text_ = ss.str();
  }

  [[noreturn]] void fail(int line, const std::string& what) const {
    throw FemMeshError(path_ + ":" + std::to_string(line) + ": " + what);
  }
  int line_at(size_t pos) const { return 1 + static_cast<int>(std::count(text_.begin(), text_.begin() + pos, '\n')); }

  static std::string attribute(const std::string& tag, const std::string& key) {
    size_t p = 0;
    while ((p = tag.find(key + "=", p)) != std::string::npos) {
      if (p > 0 && !std::isspace(static_cast<unsigned char>(tag[p - 1]))) {
        ++p;
        continue;
      }
      const size_t q = p + key.size() + 1;
      if (q >= tag.size()) return "";
      const char quote = tag[q];
      const size_t end = tag.find(quote, q + 1);
      return end == std::string::npos ? "" : tag.substr(q + 1, end - q - 1);
    }
    return "";
  }

  void parse() {
    std::vector<std::string> stack;
    size_t pos = 0;
    bool seen_grid = false;
    while ((pos = text_.find('<', pos)) != std::string::npos) {
      if (text_.compare(pos, 4, "<!--") == 0) {
        pos = text_.find("-->", pos);
        if (pos == std::string::npos) fail(line_at(text_.size()), "unterminated XML comment");
        continue;
      }
      const size_t end = text_.find('>', pos);
      if (end == std::string::npos) fail(line_at(pos), "unterminated XML tag");
      const std::string tag = text_.substr(pos + 1, end - pos - 1);
      const int line = line_at(pos);
      pos = end + 1;
      if (tag.empty() || tag[0] == '?' || tag[0] == '!') continue;
      if (tag[0] == '/') {
        if (!stack.empty()) stack.pop_back();
        continue;
      }
      const bool self_closing = tag.back() == '/';
      const std::string name = tag.substr(0, tag.find_first_of(" \t\r\n/"));
      if (name == "VTKFile") {
        const std::string type = attribute(tag, "type");
        if (type != "UnstructuredGrid")
          fail(line, "VTKFile type '" + type + "', expected 'UnstructuredGrid' (a .vtu file)");
        if (attribute(tag, "compressor") != "") fail(line, "compressed VTU; write it with meshio ... --ascii");
      } else if (name == "UnstructuredGrid") {
        seen_grid = true;
      } else if (name == "AppendedData") {
        fail(line, "appended (binary) data; only ASCII VTU is read: convert with `meshio convert IN OUT.vtu --ascii`");
      } else if (name == "Piece") {
        if (++pieces_ > 1) fail(line, "more than one Piece; expected a single-piece mesh");
        points_ = count(tag, "NumberOfPoints", line);
        cells_ = count(tag, "NumberOfCells", line);
        piece_line_ = line;
      } else if (name == "DataArray") {
        XmlArray a;
        a.section = stack.empty() ? "" : stack.back();
        a.name = attribute(tag, "Name");
        a.line = line;
        const std::string comps = attribute(tag, "NumberOfComponents");
        a.components = comps.empty() ? 1 : std::atoi(comps.c_str());
        const std::string format = attribute(tag, "format");
        if (format != "ascii")
          fail(line, "DataArray '" + a.name + "' has format '" + format +
                         "'; only ASCII VTU is read: convert with `meshio convert IN OUT.vtu --ascii`");
        if (!self_closing) {
          const size_t close = text_.find("</DataArray>", pos);
          if (close == std::string::npos) fail(line, "DataArray '" + a.name + "' is not closed");
          std::istringstream body(text_.substr(pos, close - pos));
          std::string tok;
          while (body >> tok) {
            char* e = nullptr;
            const double x = std::strtod(tok.c_str(), &e);
            if (*e != '\0') fail(line, "DataArray '" + a.name + "': '" + tok + "' is not a number");
            a.values.push_back(x);
          }
          pos = close + std::string("</DataArray>").size();
        }
        arrays_.push_back(std::move(a));
        continue;  // DataArray is never pushed on the stack
      }
      if (!self_closing) stack.push_back(name);
    }
    if (!seen_grid) fail(1, "no <UnstructuredGrid> element: not a VTK XML .vtu file");
    if (pieces_ == 0) fail(1, "no <Piece> element");
  }

  // A Piece's NumberOfPoints / NumberOfCells: an integer in [1, 10^8].
  int count(const std::string& tag, const std::string& key, int line) const {
    const std::string text = attribute(tag, key);
    char* end = nullptr;
    const long long n = std::strtoll(text.c_str(), &end, 10);
    if (text.empty() || *end != '\0' || n < 1 || n > 100000000)
      fail(line, "Piece " + key + "=\"" + text + "\", expected an integer from 1 to 100000000");
    return static_cast<int>(n);
  }

  const XmlArray* find(const std::string& section, const std::string& name, bool any_name = false) const {
    for (const auto& a : arrays_)
      if (a.section == section && (any_name || a.name == name)) return &a;
    return nullptr;
  }

  std::string path_, text_;
  std::vector<XmlArray> arrays_;
  int pieces_ = 0, points_ = 0, cells_ = 0, piece_line_ = 0;
};

// An integer-valued entry as int; -1 for anything else (NaN, fractions, out of range).
int whole(double x) { return x == std::floor(x) && x >= 0 && x < 2147483647.0 ? static_cast<int>(x) : -1; }

}  // namespace

FemMesh read_vtu_mesh(const std::string& path) {
  VtuParser p(path);
  p.parse();
  FemMesh m;
  m.source = path;
  const int n = p.points_;
  const XmlArray* pts = p.find("Points", "", true);
  if (!pts) p.fail(p.piece_line_, "no <Points> DataArray");
  if (pts->components != 3 || static_cast<int>(pts->values.size()) != 3 * n)
    p.fail(pts->line, "Points: expected " + std::to_string(n) + " points × 3 components, got " +
                          std::to_string(pts->values.size()) + " values in " + std::to_string(pts->components) +
                          " components");
  const XmlArray* uv = p.find("PointData", "uv");
  if (!uv) uv = p.find("PointData", "obj:vt");
  if (!uv)
    p.fail(p.piece_line_,
           "no point-data array \"uv\" (rest material coordinates in metres, 2 components); "
           "see experiments/scenes/README_fem.md");
  if (uv->components < 2 || static_cast<long long>(uv->values.size()) != static_cast<long long>(uv->components) * n)
    p.fail(uv->line, "point data '" + uv->name + "': expected " + std::to_string(n) + " entries × 2 components, got " +
                         std::to_string(uv->values.size()) + " values in " + std::to_string(uv->components) +
                         " components");
  const XmlArray* conn = p.find("Cells", "connectivity");
  const XmlArray* offs = p.find("Cells", "offsets");
  const XmlArray* types = p.find("Cells", "types");
  if (!conn || !offs || !types) p.fail(p.piece_line_, "<Cells> needs DataArrays 'connectivity', 'offsets' and 'types'");
  if (static_cast<int>(offs->values.size()) != p.cells_ || static_cast<int>(types->values.size()) != p.cells_)
    p.fail(offs->line, "Cells: expected " + std::to_string(p.cells_) + " offsets and types");
  for (int i = 0; i < n; ++i) {
    m.x.emplace_back(pts->values[3 * i], pts->values[3 * i + 1], pts->values[3 * i + 2]);
    m.uv.emplace_back(uv->values[uv->components * i], uv->values[uv->components * i + 1]);
    if (!m.x.back().allFinite() || !m.uv.back().allFinite())
      p.fail(pts->line, "point " + std::to_string(i) + " has a non-finite coordinate or uv");
  }
  int start = 0;
  for (int c = 0; c < p.cells_; ++c) {
    const int type = whole(types->values[c]);
    if (type != 5)
      p.fail(types->line, "cell " + std::to_string(c) + " has VTK type " + std::to_string(type) +
                              ", expected 5 (triangle); triangulate the mesh first");
    const int end = whole(offs->values[c]);
    if (end - start != 3 || end > static_cast<int>(conn->values.size()))
      p.fail(offs->line, "cell " + std::to_string(c) + ": offsets inconsistent with triangles");
    std::array<int, 3> t;
    for (int k = 0; k < 3; ++k) {
      t[k] = whole(conn->values[start + k]);
      if (t[k] < 0 || t[k] >= n)
        p.fail(conn->line,
               "cell " + std::to_string(c) + " refers to point " + std::to_string(t[k]) + " of " + std::to_string(n));
    }
    start = end;
    const Vec2 e1 = m.uv[t[1]] - m.uv[t[0]], e2 = m.uv[t[2]] - m.uv[t[0]];
    const double det = e1.x() * e2.y() - e1.y() * e2.x();
    if (det < 0) std::swap(t[1], t[2]);  // reorient: CCW in UV
    try {
      triangle_rest(m.uv[t[0]], m.uv[t[1]], m.uv[t[2]]);
    } catch (const std::invalid_argument&) {
      p.fail(uv->line, "cell " + std::to_string(c) + " is degenerate in uv (zero area)");
    }
    m.triangles.push_back(t);
  }
  if (m.triangles.empty()) p.fail(p.piece_line_, "the mesh has no triangles");
  std::vector<char> used(n, 0);
  for (const auto& t : m.triangles)
    for (int v : t) used[v] = 1;
  if (const auto it = std::find(used.begin(), used.end(), 0); it != used.end())
    p.fail(conn->line, "point " + std::to_string(it - used.begin()) + " is used by no triangle (remove unused points)");
  return m;
}

FemMesh make_fem_mesh(const Scene& scene) {
  if (scene.knit) return knit_contact_mesh(scene);
  return scene.fem.mesh_file.empty() ? build_grid_mesh(scene) : read_vtu_mesh(scene.fem.mesh_file);
}

std::vector<Hinge> interior_hinges(const FemMesh& m) {
  // Directed edge (a→b) → triangle and apex.
  std::map<std::pair<int, int>, std::pair<int, int>> directed;
  for (int t = 0; t < m.num_triangles(); ++t)
    for (int k = 0; k < 3; ++k) {
      const int a = m.triangles[t][k], b = m.triangles[t][(k + 1) % 3], c = m.triangles[t][(k + 2) % 3];
      if (!directed.emplace(std::make_pair(a, b), std::make_pair(t, c)).second)
        throw FemMeshError(m.source + ": edge (" + std::to_string(a) + ", " + std::to_string(b) +
                           ") is used twice in the same direction (non-manifold or inconsistent UV orientation)");
    }
  std::vector<Hinge> hinges;
  for (const auto& [ab, tc] : directed) {
    const auto [a, b] = ab;
    if (a > b) continue;
    auto other = directed.find({b, a});
    if (other == directed.end()) continue;  // boundary edge
    hinges.push_back({{a, b, tc.second, other->second.second}, tc.first, other->second.first});
  }
  return hinges;
}

int nearest_vertex(const FemMesh& m, const Vec2& uv) {
  int best = 0;
  double d = std::numeric_limits<double>::infinity();
  for (int i = 0; i < m.num_vertices(); ++i)
    if (const double di = (m.uv[i] - uv).squaredNorm(); di < d) d = di, best = i;
  return best;
}

}  // namespace wl
