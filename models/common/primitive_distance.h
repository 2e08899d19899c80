// Distance between two primitives of the cloth surface (docs/models.md §3.11.7):
// a point and a triangle, or two edges, given as 4 nodes x₀ … x₃ (point–triangle:
// x₀ the point, x₁ x₂ x₃ the triangle; edge–edge: x₀x₁ and x₂x₃). Both are
//   d = ‖r‖,  r = Σᵢ λᵢ xᵢ,
// with λ the closest points' barycentric weights, those of the first primitive
// ≥ 0 summing to 1 and those of the second ≤ 0 summing to −1. The closest points
// lie in the relative interior of one face of each primitive (a vertex, an edge,
// the triangle): the support, the nodes with non-zero weight. Within a support,
// λ is the affine projection r = r₀ + E y, EᵀE y = −Eᵀr₀ (y: at most 2 free
// weights), a smooth function of x that the AD scalar differentiates; by the
// envelope theorem ∂d/∂xᵢ = λᵢ r/d.
#pragma once
#include <array>

#include "models/core/types.h"

namespace wl {

enum class PairKind { point_triangle, edge_edge };

// Nodes (bits 0–3) carrying the weight of the first and of the second primitive.
struct PairSupport {
  unsigned first = 0, second = 0;
};

template <class T>
using Point3 = Eigen::Matrix<T, 3, 1>;

// λ for the given support at x (0 outside it); the support's affine system
// must be regular (closest_support checks it).
template <class T>
std::array<T, 4> support_weights(const std::array<Point3<T>, 4>& x, PairSupport s) {
  int a[3], b[3], na = 0, nb = 0;
  for (int i = 0; i < 4; ++i) {
    if (s.first >> i & 1u) a[na++] = i;
    if (s.second >> i & 1u) b[nb++] = i;
  }
  // Free directions: first primitive's x_{a_k} − x_{a_0}, second's −(x_{b_k} − x_{b_0}).
  Point3<T> e[2];
  int k = 0;
  for (int i = 1; i < na; ++i) e[k++] = x[a[i]] - x[a[0]];
  for (int i = 1; i < nb; ++i) e[k++] = x[b[0]] - x[b[i]];
  const Point3<T> r0 = x[a[0]] - x[b[0]];
  T y[2] = {T(0.0), T(0.0)};
  if (k == 1) {
    y[0] = -e[0].dot(r0) / e[0].squaredNorm();
  } else if (k == 2) {
    const T g00 = e[0].squaredNorm(), g01 = e[0].dot(e[1]), g11 = e[1].squaredNorm();
    const T c0 = -e[0].dot(r0), c1 = -e[1].dot(r0), det = g00 * g11 - g01 * g01;
    y[0] = (g11 * c0 - g01 * c1) / det;
    y[1] = (g00 * c1 - g01 * c0) / det;
  }
  std::array<T, 4> w = {T(0.0), T(0.0), T(0.0), T(0.0)};
  k = 0;
  w[a[0]] = T(1.0);
  for (int i = 1; i < na; ++i) {
    w[a[i]] = y[k];
    w[a[0]] -= y[k++];
  }
  w[b[0]] = T(-1.0);
  for (int i = 1; i < nb; ++i) {
    w[b[i]] = -y[k];
    w[b[0]] += y[k++];
  }
  return w;
}

// The closest points of the pair: its support and weights, and d. Every face
// pair is tried; a support whose affine system is near singular (parallel
// edges: det(EᵀE) ≤ 10⁻¹⁰ g₀₀g₁₁) is skipped, the minimum then lying at an
// endpoint, which a smaller support gives (docs/models.md §3.11.7).
struct ClosestPoints {
  PairSupport support;
  std::array<double, 4> weight{};
  double distance = 0.0;
};
ClosestPoints closest_support(PairKind kind, const std::array<Vec3, 4>& x);

}  // namespace wl
