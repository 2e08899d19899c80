#include "models/fem/terms/warp_weft_stretch.h"

#include <cmath>
#include <stdexcept>

#include "models/fem/fem_material.h"

namespace wl {
namespace {

// ½k(‖w‖−1)² : gradient and Hessian with respect to w.
//   ∇ = k(l−1)ŵ,  ∇² = k( ŵŵᵀ + (l−1)/l (I − ŵŵᵀ) ).
void stretch_derivatives(double k, const Vec3& w, Eigen::Ref<Vec3> g, Eigen::Ref<Mat3> h) {
  const double l = w.norm();
  if (l < 1e-300) {  // fully collapsed column: direction undefined; no force, stiffness −k/l unbounded → skip
    g.setZero();
    h.setZero();
    return;
  }
  const Vec3 n = w / l;
  g = k * (l - 1.0) * n;
  const Mat3 nn = n * n.transpose();
  h = k * (nn + (l - 1.0) / l * (Mat3::Identity() - nn));
}

}  // namespace

WarpWeftStretchTerm::WarpWeftStretchTerm(const StretchLaw& law) : law_(law) {
  if (law.k_c != 0 && !(law.k_c * law.k_c < law.k_u * law.k_v))
    throw std::invalid_argument("fem-stretch: the warp–weft coupling k_c = " + std::to_string(law.k_c) +
                                " N/m must satisfy k_c² < k_u·k_v (k_u = " + std::to_string(law.k_u) +
                                ", k_v = " + std::to_string(law.k_v) + " N/m) for a convex law");
  if (!(law.q_u >= 0 && law.q_v >= 0 && law.q_a >= 0))
    throw std::invalid_argument("fem-stretch: the quartic stiffening must be ≥ 0");
  // ψ is linear in each parameter: ∂f/∂p is the force of the law with p = 1 and the rest 0.
  auto add_key = [&](const char* key, double StretchLaw::*p) {
    keys_.push_back(key);
    unit_laws_.emplace_back();
    unit_laws_.back().*p = 1.0;
  };
  add_key(kFemWarpStretch, &StretchLaw::k_u);
  add_key(kFemWeftStretch, &StretchLaw::k_v);
  if (law.k_c != 0) add_key(kFemStretchCoupling, &StretchLaw::k_c);
  if (law.q_u != 0) add_key(kFemWarpStretchQuartic, &StretchLaw::q_u);
  if (law.q_v != 0) add_key(kFemWeftStretchQuartic, &StretchLaw::q_v);
  if (law.q_a != 0) add_key(kFemArealStretchQuartic, &StretchLaw::q_a);
}

void WarpWeftStretchTerm::add(const std::array<int, 9>& stencil, const TriangleRest& rest) {
  stencils_.push_back(stencil);
  rest_.push_back(rest);
}

double WarpWeftStretchTerm::energy(int e, const double* q) const {
  const TriangleRest& r = rest_[e];
  const double du = warp_vector(r, q).norm() - 1.0, dv = weft_vector(r, q).norm() - 1.0;
  if (law_.linear()) return r.area * 0.5 * (law_.k_u * du * du + law_.k_v * dv * dv);
  const StretchLaw& l = law_;  // docs/models.md §6.3.1
  return r.area * (0.5 * (l.k_u * du * du + l.k_v * dv * dv) + l.k_c * du * dv +
                   0.25 * (l.q_u * du * du * du * du + l.q_v * dv * dv * dv * dv + l.q_a * std::pow(du + dv, 4)));
}

void WarpWeftStretchTerm::add_law(const StretchLaw& law, int e, const double* q, double* force, double* dfdq) const {
  const TriangleRest& r = rest_[e];
  const Vec3 wu = warp_vector(r, q), wv = weft_vector(r, q);
  // f = −A Cᵀ∇ψ, ∂f/∂x = −A Cᵀ∇²ψ C (deformation_gradient.h).
  if (law.linear()) {  // no u–v coupling
    Vec3 gu, gv;
    Mat3 huu, hvv;
    stretch_derivatives(law.k_u, wu, gu, huu);
    stretch_derivatives(law.k_v, wv, gv, hvv);
    add_column_gradient(r, gu, gv, -r.area, force);
    if (dfdq) add_column_hessian(r, huu, Mat3::Zero(), hvv, -r.area, dfdq);
    return;
  }
  // ψ(ε_u, ε_v), ε = l − 1 (docs/models.md §6.3.1): ∇_{w_u}ψ = ψ_u n_u,
  // ∇²_{uu} = ψ_uu n_u n_uᵀ + ψ_u/l_u (I − n_u n_uᵀ), ∇²_{uv} = ψ_uv n_u n_vᵀ. A collapsed
  // column (l = 0) has no direction: its n is taken as 0 (no force along it, no stiffness).
  const double lu = wu.norm(), lv = wv.norm(), eu = lu - 1.0, ev = lv - 1.0;
  const Vec3 nu = lu < 1e-300 ? Vec3::Zero() : Vec3(wu / lu), nv = lv < 1e-300 ? Vec3::Zero() : Vec3(wv / lv);
  const double su = law.stress_u(eu, ev), sv = law.stress_v(eu, ev);
  add_column_gradient(r, su * nu, sv * nv, -r.area, force);
  if (!dfdq) return;
  const Mat3 I = Mat3::Identity(), Nu = nu * nu.transpose(), Nv = nv * nv.transpose();
  const double a2 = 3.0 * law.q_a * (eu + ev) * (eu + ev);  // ∂²/∂ε² of ¼q_a(ε_u + ε_v)⁴, every block
  const Mat3 huu = (law.k_u + 3.0 * law.q_u * eu * eu + a2) * Nu + (lu < 1e-300 ? 0.0 : su / lu) * (I - Nu);
  const Mat3 hvv = (law.k_v + 3.0 * law.q_v * ev * ev + a2) * Nv + (lv < 1e-300 ? 0.0 : sv / lv) * (I - Nv);
  add_column_hessian(r, huu, (law.k_c + a2) * nu * nv.transpose(), hvv, -r.area, dfdq);
}

void WarpWeftStretchTerm::evaluate(int e, const double* q, const double*, const ElementOutput& out) const {
  add_law(law_, e, q, out.force, out.dfdq);
}

void WarpWeftStretchTerm::parameter_derivative(int e, int k, const double* q, const double*, double* dfdp) const {
  add_law(unit_laws_[k], e, q, dfdp, nullptr);
}

}  // namespace wl
