#include "models/common/primitive_distance.h"

#include <bit>
#include <limits>
#include <vector>

namespace wl {

namespace {

// Whether the support's affine system EᵀE y = −Eᵀr₀ is regular: every free
// direction of non-zero length and, with two, not near parallel.
bool support_regular(const std::array<Vec3, 4>& x, PairSupport s) {
  std::vector<Vec3> e;
  for (unsigned side : {s.first, s.second}) {
    const int a0 = std::countr_zero(side);
    for (int i = a0 + 1; i < 4; ++i)
      if (side >> i & 1u) e.push_back(x[i] - x[a0]);
  }
  for (const Vec3& d : e)
    if (!(d.squaredNorm() > 0.0)) return false;
  if (e.size() < 2) return true;
  const double g00 = e[0].squaredNorm(), g11 = e[1].squaredNorm(), g01 = e[0].dot(e[1]);
  return g00 * g11 - g01 * g01 > 1e-10 * g00 * g11;
}

}  // namespace

ClosestPoints closest_support(PairKind kind, const std::array<Vec3, 4>& x) {
  // Candidate supports, fewer nodes first (ties keep the smaller support).
  std::vector<PairSupport> supports;
  const std::vector<unsigned> first = kind == PairKind::point_triangle
                                          ? std::vector<unsigned>{0b0001u}
                                          : std::vector<unsigned>{0b0001u, 0b0010u, 0b0011u};
  const std::vector<unsigned> second =
      kind == PairKind::point_triangle
          ? std::vector<unsigned>{0b0010u, 0b0100u, 0b1000u, 0b0110u, 0b1100u, 0b1010u, 0b1110u}
          : std::vector<unsigned>{0b0100u, 0b1000u, 0b1100u};
  for (int n = 2; n <= 4; ++n)
    for (unsigned a : first)
      for (unsigned b : second)
        if (std::popcount(a) + std::popcount(b) == n) supports.push_back({a, b});
  ClosestPoints best;
  best.distance = std::numeric_limits<double>::infinity();
  constexpr double tol = 1e-12;
  for (const PairSupport& s : supports) {
    if (!support_regular(x, s)) continue;
    const std::array<double, 4> w = support_weights<double>(x, s);
    bool inside = true;
    for (int i = 0; i < 4; ++i) {
      if (s.first >> i & 1u) inside = inside && w[i] >= -tol;
      if (s.second >> i & 1u) inside = inside && w[i] <= tol;
    }
    if (!inside) continue;
    const double d = (w[0] * x[0] + w[1] * x[1] + w[2] * x[2] + w[3] * x[3]).norm();
    if (d < best.distance) best = {s, w, d};
  }
  return best;
}

}  // namespace wl
