// The continuation of a tile law's polynomial beyond its sampled box
// (docs/models.md §6.9), shared by the membrane law over N = 3 strains
// (tile_law_file.h) and the curvature part over N = 6 (tile_bending_law.h).
#pragma once
#include <algorithm>
#include <array>

namespace wl {

// The sampled box of a law over N strains: W(θ) = W₀ P(t), t_k = θ_k / s_k, box lo ≤ t ≤ hi.
template <int N>
struct TileLawBox {
  double energy_scale = 0.0;         // W₀
  std::array<double, N> scale{};     // s_k
  std::array<double, N> lo{}, hi{};  // in t
};

// The box of the first N strains of a law's file: W₀, the scales s_k and the sampled range of θ.
template <int N>
TileLawBox<N> tile_law_box(double energy_scale, const std::array<double, 6>& scale, const std::array<double, 6>& lo,
                           const std::array<double, 6>& hi) {
  TileLawBox<N> box;
  box.energy_scale = energy_scale;
  for (int k = 0; k < N; ++k) {
    box.scale[k] = scale[k];
    box.lo[k] = lo[k] / scale[k];
    box.hi[k] = hi[k] / scale[k];
  }
  return box;
}

// In t, with p the nearest point of the box and d = t − p (docs/models.md §6.9):
//   E = P(p) + ∇P(p)·d + ½ Σ_k h_k d_k²,
//   ∂E/∂t_j = ∇P_j(p) + h_j d_j (j clamped),  ∇P_j(p) + Σ_k ∇²P_jk(p) d_k (j inside);
//   ∂²E/∂t_i∂t_j = h_i δ_ij (both clamped), ∇²P_ij(p) (one clamped),
//                  ∇²P_ij(p) + Σ_k ∂³P_ijk(p) d_k (both inside).
// W = W₀ E and its gradient and Hessian in θ (row-major N × N); g, h may be null.
// `polynomial(t, &P, G, H, T)` gives P and its derivatives at t (H, T null when not needed).
template <int N, class Polynomial>
void continue_tile_law(const TileLawBox<N>& box, const Polynomial& polynomial, const std::array<double, N>& rest,
                       const std::array<double, N>& theta, double* w, std::array<double, N>* g,
                       std::array<double, N * N>* h) {
  std::array<double, N> t{}, p{}, d{};
  std::array<bool, N> clamped{};
  bool outside = false;
  for (int k = 0; k < N; ++k) {
    t[k] = theta[k] / box.scale[k];
    p[k] = std::clamp(t[k], box.lo[k], box.hi[k]);
    d[k] = t[k] - p[k];
    clamped[k] = d[k] != 0.0;
    outside = outside || clamped[k];
  }
  double P, G[N], H[N * N]{}, T[N * N * N];
  polynomial(p, &P, G, outside || h ? H : nullptr, outside && h ? T : nullptr);
  double e = P;
  std::array<double, N> ge{};
  for (int j = 0; j < N; ++j) {
    ge[j] = G[j];
    if (clamped[j]) {
      e += G[j] * d[j] + 0.5 * rest[j] * d[j] * d[j];
      ge[j] += rest[j] * d[j];
    } else if (outside) {
      for (int k = 0; k < N; ++k) ge[j] += H[N * j + k] * d[k];
    }
  }
  *w = box.energy_scale * e;
  if (g)
    for (int j = 0; j < N; ++j) (*g)[j] = box.energy_scale * ge[j] / box.scale[j];
  if (!h) return;
  for (int i = 0; i < N; ++i)
    for (int j = 0; j < N; ++j) {
      double x;
      if (clamped[i] && clamped[j]) x = i == j ? rest[i] : 0.0;
      else if (clamped[i] || clamped[j]) x = H[N * i + j];
      else {
        x = H[N * i + j];
        if (outside)
          for (int k = 0; k < N; ++k) x += T[N * N * i + N * j + k] * d[k];
      }
      (*h)[N * i + j] = box.energy_scale * x / (box.scale[i] * box.scale[j]);
    }
}

}  // namespace wl
