#include "models/fem/terms/warp_weft_stretch.h"

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

void WarpWeftStretchTerm::add(const std::array<int, 9>& stencil, const TriangleRest& rest) {
  stencils_.push_back(stencil);
  rest_.push_back(rest);
}

double WarpWeftStretchTerm::energy(int e, const double* q) const {
  const TriangleRest& r = rest_[e];
  const double du = warp_vector(r, q).norm() - 1.0, dv = weft_vector(r, q).norm() - 1.0;
  return r.area * 0.5 * (k_u_ * du * du + k_v_ * dv * dv);
}

void WarpWeftStretchTerm::evaluate(int e, const double* q, const double*, const ElementOutput& out) const {
  const TriangleRest& r = rest_[e];
  Vec3 gu, gv;
  Mat3 huu, hvv;
  stretch_derivatives(k_u_, warp_vector(r, q), gu, huu);
  stretch_derivatives(k_v_, weft_vector(r, q), gv, hvv);
  // f = −A Cᵀ∇ψ, ∂f/∂x = −A Cᵀ∇²ψ C (deformation_gradient.h); no u–v coupling.
  add_column_gradient(r, gu, gv, -r.area, out.force);
  if (out.dfdq) add_column_hessian(r, huu, Mat3::Zero(), hvv, -r.area, out.dfdq);
}

std::vector<std::string> WarpWeftStretchTerm::parameter_keys() const { return {kFemWarpStretch, kFemWeftStretch}; }

void WarpWeftStretchTerm::parameter_derivative(int e, int k, const double* q, const double*, double* dfdp) const {
  const TriangleRest& r = rest_[e];
  Vec3 g;
  Mat3 h;
  stretch_derivatives(1.0, k == 0 ? warp_vector(r, q) : weft_vector(r, q), g, h);
  add_column_gradient(r, k == 0 ? g : Vec3::Zero(), k == 0 ? Vec3::Zero() : g, -r.area, dfdp);
}

}  // namespace wl
