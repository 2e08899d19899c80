// The Optitex tension map of one face (docs/models.md §6.8, the Optitex note):
//   l_u = ‖w_u‖, l_v = ‖w_v‖ (stretch ratios), rest values rl_u, rl_v from the
//   initial positions; amp_U = max(0, (l_u − rl_u)·min(5·10⁴, K_sX)) and likewise
//   amp_V (compression ignored); w_u ← amp_U ŵ_u, w_v ← amp_V ŵ_v;
//   tension = ‖w_u − w_v‖ if w_u·w_v < 0, else ‖w_u + w_v‖.
// K_sX, K_sY are the warp/weft stretch stiffnesses per unit width [N/m], so
// the tension is a membrane force per unit width [N/m] (002 leaves units open).
#pragma once
#include "models/core/types.h"

namespace wl {

struct FaceTension {
  double lu = 0.0, lv = 0.0, tension = 0.0;
};

constexpr double kOptitexStiffnessClip = 5e4;  // min(5e4, K_s), the Optitex note

FaceTension face_tension(const Vec3& wu, const Vec3& wv, double rest_lu, double rest_lv, double ks_u, double ks_v);

}  // namespace wl
