#include "models/fem/tension_map.h"

#include <algorithm>

namespace wl {

FaceTension face_tension(const Vec3& wu, const Vec3& wv, double rest_lu, double rest_lv, double ks_u, double ks_v) {
  FaceTension r;
  r.lu = wu.norm();
  r.lv = wv.norm();
  const double amp_u = std::max(0.0, (r.lu - rest_lu) * std::min(kOptitexStiffnessClip, ks_u));
  const double amp_v = std::max(0.0, (r.lv - rest_lv) * std::min(kOptitexStiffnessClip, ks_v));
  // SetLength on a zero vector leaves it zero (degenerate faces give 0).
  const Vec3 a = r.lu > 0 ? Vec3(wu * (amp_u / r.lu)) : Vec3::Zero();
  const Vec3 b = r.lv > 0 ? Vec3(wv * (amp_v / r.lv)) : Vec3::Zero();
  r.tension = a.dot(b) < 0 ? (a - b).norm() : (a + b).norm();
  return r;
}

}  // namespace wl
