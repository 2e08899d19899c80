#include "models/fem/terms/tile_membrane.h"

#include <cmath>

namespace wl {
namespace {

// The membrane strains of a triangle and their first and second derivatives in (w_u, w_v).
struct MembraneStrains {
  std::array<double, 3> m{};   // ε_u, ε_v, γ
  std::array<Vec3, 3> gu, gv;  // ∂m_k/∂w_u, ∂m_k/∂w_v
  // ∂²m_k: the u–u, u–v and v–v blocks.
  std::array<Mat3, 3> huu, huv, hvv;
  bool valid = false;  // false for a collapsed column or a folded angle (|s| = 1)
};

MembraneStrains membrane_strains(const Vec3& wu, const Vec3& wv, bool second) {
  MembraneStrains r;
  const double lu = wu.norm(), lv = wv.norm();
  if (lu < 1e-300 || lv < 1e-300) return r;
  const Vec3 p = wu / lu, n = wv / lv;
  const double s = p.dot(n), c2 = 1.0 - s * s;
  if (!(c2 > 1e-24)) return r;
  const double c = std::sqrt(c2);
  r.valid = true;
  r.m = {lu - 1.0, lv - 1.0, std::asin(s)};
  const Vec3 dsu = (n - s * p) / lu, dsv = (p - s * n) / lv;  // ∂s/∂w_u, ∂s/∂w_v
  r.gu = {p, Vec3::Zero(), Vec3(dsu / c)};
  r.gv = {Vec3::Zero(), n, Vec3(dsv / c)};
  if (!second) return r;
  const Mat3 I = Mat3::Identity(), Pu = I - p * p.transpose(), Pv = I - n * n.transpose();
  // ∂²s (in_plane_shear.cpp): H_uu = −(p g_uᵀ + g_u pᵀ)/l_u − s P_u/l_u², H_uv = (P_v/l_v − p g_vᵀ)/l_u.
  const Mat3 suu = -(p * dsu.transpose() + dsu * p.transpose()) / lu - s * Pu / (lu * lu);
  const Mat3 svv = -(n * dsv.transpose() + dsv * n.transpose()) / lv - s * Pv / (lv * lv);
  const Mat3 suv = (Pv / lv - p * dsv.transpose()) / lu;
  const double k3 = s / (c2 * c);  // ∇²γ = ∇²s/c + (s/c³)∇s∇sᵀ
  r.huu = {Pu / lu, Mat3::Zero(), Mat3(suu / c + k3 * dsu * dsu.transpose())};
  r.huv = {Mat3::Zero(), Mat3::Zero(), Mat3(suv / c + k3 * dsu * dsv.transpose())};
  r.hvv = {Mat3::Zero(), Pv / lv, Mat3(svv / c + k3 * dsv * dsv.transpose())};
  return r;
}

}  // namespace

TileMembraneTerm::TileMembraneTerm(std::shared_ptr<const TileMembraneLaw> law) : law_(std::move(law)) {}

void TileMembraneTerm::add(const std::array<int, 9>& stencil, const TriangleRest& rest) {
  stencils_.push_back(stencil);
  rest_.push_back(rest);
}

double TileMembraneTerm::energy(int e, const double* q) const {
  const TriangleRest& r = rest_[e];
  const MembraneStrains st = membrane_strains(warp_vector(r, q), weft_vector(r, q), false);
  if (!st.valid) return 0.0;
  double w;
  law_->evaluate(st.m, &w, nullptr, nullptr);
  return r.area * w;
}

void TileMembraneTerm::evaluate(int e, const double* q, const double*, const ElementOutput& out) const {
  const TriangleRest& r = rest_[e];
  const MembraneStrains st = membrane_strains(warp_vector(r, q), weft_vector(r, q), out.dfdq != nullptr);
  if (!st.valid) return;  // collapsed or folded: the strains are undefined, no force
  double w;
  std::array<double, 3> g;
  std::array<double, 9> h;
  law_->evaluate(st.m, &w, &g, out.dfdq ? &h : nullptr);
  Vec3 fu = Vec3::Zero(), fv = Vec3::Zero();
  for (int k = 0; k < 3; ++k) {
    fu += g[k] * st.gu[k];
    fv += g[k] * st.gv[k];
  }
  add_column_gradient(r, fu, fv, -r.area, out.force);
  if (!out.dfdq) return;
  Mat3 huu = Mat3::Zero(), huv = Mat3::Zero(), hvv = Mat3::Zero();
  for (int k = 0; k < 3; ++k) {
    huu += g[k] * st.huu[k];
    huv += g[k] * st.huv[k];
    hvv += g[k] * st.hvv[k];
    for (int l = 0; l < 3; ++l) {
      const double hkl = h[3 * k + l];
      huu += hkl * st.gu[k] * st.gu[l].transpose();
      huv += hkl * st.gu[k] * st.gv[l].transpose();
      hvv += hkl * st.gv[k] * st.gv[l].transpose();
    }
  }
  add_column_hessian(r, huu, huv, hvv, -r.area, out.dfdq);
}

std::vector<std::string> TileMembraneTerm::parameter_keys() const {
  std::vector<std::string> keys;
  for (int i = 0; i < law_->size(); ++i) keys.push_back("fem.tile_law." + law_->name(i));
  return keys;
}

void TileMembraneTerm::parameter_derivative(int e, int k, const double* q, const double*, double* dfdp) const {
  const TriangleRest& r = rest_[e];
  const MembraneStrains st = membrane_strains(warp_vector(r, q), weft_vector(r, q), false);
  if (!st.valid) return;
  double w;
  std::array<double, 3> g;
  law_->evaluate_unit(k, st.m, &w, &g);
  Vec3 fu = Vec3::Zero(), fv = Vec3::Zero();
  for (int j = 0; j < 3; ++j) {
    fu += g[j] * st.gu[j];
    fv += g[j] * st.gv[j];
  }
  add_column_gradient(r, fu, fv, -r.area, dfdp);
}

}  // namespace wl
