// The tile law's membrane strains of a triangle (docs/models.md §6.9):
//   ε_u = ‖w_u‖ − 1,  ε_v = ‖w_v‖ − 1,  γ = asin s,  s = w_u·w_v/(‖w_u‖‖w_v‖),
// with ∇ε_u = (n_u, 0), ∇²ε_u = (I − n_u n_uᵀ)/‖w_u‖ in the u block, ∇γ = ∇s/c,
// ∇²γ = ∇²s/c + (s/c³)∇s∇sᵀ, c = √(1 − s²), ∇s and ∇²s as in in_plane_shear.h;
// shared by the law's membrane and bending terms.
#pragma once
#include <array>

#include "models/core/types.h"

namespace wl {

// The membrane strains of a triangle and their first and second derivatives in (w_u, w_v).
struct MembraneStrains {
  std::array<double, 3> m{};   // ε_u, ε_v, γ
  std::array<Vec3, 3> gu, gv;  // ∂m_k/∂w_u, ∂m_k/∂w_v
  // ∂²m_k: the u–u, u–v and v–v blocks.
  std::array<Mat3, 3> huu, huv, hvv;
  bool valid = false;  // false for a collapsed column or a folded angle (|s| = 1)
};

// The strains at the columns (w_u, w_v); their second derivatives only when `second`.
MembraneStrains membrane_strains(const Vec3& wu, const Vec3& wv, bool second);

}  // namespace wl
