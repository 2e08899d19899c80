#include "models/knit/compression_pairs.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <tuple>
#include <unordered_map>

#include "models/knit/terms/yarn_compression.h"

namespace wl {
namespace {

constexpr double kSameShift = 1e-9;  // [m]: image shifts closer than this are one image

bool same_image(int n, const Vec3& dx, int m, const Vec3& dy) {
  return n == m && (dx - dy).cwiseAbs().maxCoeff() < kSameShift;
}

std::array<long long, 3> shift_key(const Vec3& d) {
  return {std::llround(d[0] / kSameShift), std::llround(d[1] / kSameShift), std::llround(d[2] / kSameShift)};
}

}  // namespace

std::vector<YarnPiece> unique_pieces(const std::vector<YarnPiece>& pieces) {
  std::map<std::tuple<int, int, std::array<long long, 3>>, int> seen;
  std::vector<YarnPiece> out;
  for (YarnPiece p : pieces) {
    if (p.n1 < p.n0) std::swap(p.n0, p.n1), std::swap(p.dx0, p.dx1);
    p.dx1 -= p.dx0;  // the image of the piece that starts at node n0 itself
    p.dx0.setZero();
    if (seen.emplace(std::make_tuple(p.n0, p.n1, shift_key(p.dx1)), static_cast<int>(out.size())).second)
      out.push_back(p);
  }
  return out;
}

std::vector<PiecePair> compression_pairs(const std::vector<Vec3>& x, const std::vector<YarnPiece>& pieces,
                                         const std::vector<Vec3>& images, double cutoff) {
  const int n = static_cast<int>(pieces.size());
  std::vector<Vec3> mid(n);
  std::vector<double> half(n);
  double reach = cutoff;
  for (int i = 0; i < n; ++i) {
    const Vec3 a = x[pieces[i].n0] + pieces[i].dx0, b = x[pieces[i].n1] + pieces[i].dx1;
    mid[i] = 0.5 * (a + b);
    half[i] = 0.5 * (b - a).norm();
    reach = std::max(reach, 2.0 * half[i] + cutoff);
  }
  // Every image of every piece in a grid of cells of size `reach` by midpoint:
  // two pieces within the cutoff have midpoints in neighbouring cells.
  auto cell = [&](const Vec3& p) {
    return std::array<long long, 3>{static_cast<long long>(std::floor(p[0] / reach)),
                                    static_cast<long long>(std::floor(p[1] / reach)),
                                    static_cast<long long>(std::floor(p[2] / reach))};
  };
  auto hash = [](const std::array<long long, 3>& c) {
    return static_cast<size_t>(c[0] * 73856093LL ^ c[1] * 19349663LL ^ c[2] * 83492791LL);
  };
  std::unordered_map<std::array<long long, 3>, std::vector<std::pair<int, int>>, decltype(hash)> grid(16, hash);
  for (int j = 0; j < n; ++j)
    for (int k = 0; k < static_cast<int>(images.size()); ++k) grid[cell(mid[j] + images[k])].push_back({j, k});
  std::vector<PiecePair> out;
  for (int i = 0; i < n; ++i) {
    const YarnPiece& a = pieces[i];
    const auto c = cell(mid[i]);
    for (long long di = -1; di <= 1; ++di)
      for (long long dj = -1; dj <= 1; ++dj)
        for (long long dk = -1; dk <= 1; ++dk) {
          const auto it = grid.find({c[0] + di, c[1] + dj, c[2] + dk});
          if (it == grid.end()) continue;
          for (const auto& [j, k] : it->second) {
            const Vec3& s = images[k];
            // Each pair once: (i, j, s) and (j, i, −s) are the same pair.
            const auto key = shift_key(s);
            if (j < i || (j == i && key <= std::array<long long, 3>{0, 0, 0})) continue;
            const YarnPiece& b = pieces[j];
            if ((mid[i] - mid[j] - s).norm() > half[i] + half[j] + cutoff) continue;
            if (same_image(a.n0, a.dx0, b.n0, b.dx0 + s) || same_image(a.n0, a.dx0, b.n1, b.dx1 + s) ||
                same_image(a.n1, a.dx1, b.n0, b.dx0 + s) || same_image(a.n1, a.dx1, b.n1, b.dx1 + s))
              continue;  // pieces that meet at a node
            std::array<double, 12> local;
            const Vec3 ends[4] = {x[a.n0] + a.dx0, x[a.n1] + a.dx1, x[b.n0] + b.dx0 + s, x[b.n1] + b.dx1 + s};
            for (int e = 0; e < 4; ++e)
              for (int d = 0; d < 3; ++d) local[3 * e + d] = ends[e][d];
            if (YarnCompressionTerm::distance(local.data()) < cutoff) out.push_back({i, j, s});
          }
        }
  }
  return out;
}

}  // namespace wl
