#include "models/knit/terms/stitch_compression.h"

#include <Eigen/Geometry>
#include <cmath>
#include <stdexcept>

#include "models/knit/terms/autodiff_jacobian.h"

namespace wl {
namespace {

// h = n·(x_b − x_a) and, when `grad` is set, ∇h (24) in any scalar type
// (docs/models.md §11.6).
template <typename T>
T through_height(const Eigen::Matrix<T, 24, 1>& q, double side, Eigen::Matrix<T, 24, 1>* grad) {
  using V3 = Eigen::Matrix<T, 3, 1>;
  auto x = [&](int k) { return V3(q.template segment<3>(3 * k)); };
  const V3 e = x(1) - x(0);
  const V3 c = T(0.5 * side) * (x(2) + x(3) - x(0) - x(1));
  const V3 w = T(0.5) * (x(6) + x(7) - x(4) - x(5));
  const V3 v = c.cross(w);
  const T lv = v.norm();
  const V3 n = v / lv;
  const T h = n.dot(e);
  if (!grad) return h;
  const V3 gv = (e - n * h) / lv;  // ∂h/∂v = (I − n nᵀ) e / ‖v‖
  const V3 gc = w.cross(gv), gw = gv.cross(c);
  const V3 hc = T(0.5 * side) * gc, hw = T(0.5) * gw;
  grad->template segment<3>(0) = -n - hc;
  grad->template segment<3>(3) = n - hc;
  grad->template segment<3>(6) = hc;
  grad->template segment<3>(9) = hc;
  grad->template segment<3>(12) = -hw;
  grad->template segment<3>(15) = -hw;
  grad->template segment<3>(18) = hw;
  grad->template segment<3>(21) = hw;
  return h;
}

}  // namespace

void StitchCompressionTerm::add(const std::array<int, 24>& stencil, double kappa, double contact_distance,
                                int side_sign, int stitch_sign, double stack_share) {
  if (!(std::isfinite(kappa) && kappa >= 0.0 && std::isfinite(contact_distance) && contact_distance > 0.0 &&
        std::abs(side_sign) == 1 && std::abs(stitch_sign) == 1 && stack_share > 0.0 && stack_share <= 1.0))
    throw std::invalid_argument(
        "StitchCompressionTerm::add: expected κ ≥ 0, a contact distance > 0, signs ±1 and a stack share in (0, 1]");
  stencils_.push_back(stencil);
  kappa_.push_back(kappa);
  contact_distance_.push_back(contact_distance);
  stack_share_.push_back(stack_share);
  side_.push_back(side_sign);
  stitch_.push_back(stitch_sign);
}

double StitchCompressionTerm::stack_height(int e, const double* q) const {
  return stitch_[e] * through_height<double>(Eigen::Map<const Eigen::Matrix<double, 24, 1>>(q), side_[e], nullptr);
}

double StitchCompressionTerm::energy(int e, const double* q) const {
  const double gap = std::max(contact_distance_[e] - stack_share_[e] * stack_height(e, q), 0.0);
  return 0.5 * kappa_[e] * gap * gap;  // V = ½ κ (D − φσh)²
}

void StitchCompressionTerm::evaluate(int e, const double* q, const double*, const ElementOutput& out) const {
  // φσ: the pair's distance per unit h (φ = 1 and σ = ±1 for a two-yarn stitch: exact).
  const double D = contact_distance_[e], k = kappa_[e], sigma = stack_share_[e] * stitch_[e];
  if (stack_share_[e] * stack_height(e, q) >= D) return;  // inactive: no force, no stiffness
  Eigen::Map<Eigen::Matrix<double, 24, 1>> f(out.force);
  if (!out.dfdq) {
    Eigen::Matrix<double, 24, 1> g;
    const double h = through_height<double>(Eigen::Map<const Eigen::Matrix<double, 24, 1>>(q), side_[e], &g);
    f = k * (D - sigma * h) * sigma * g;  // F = κ (D − φσh) φσ ∇h
    return;
  }
  using AD = AutoDiff<24>;
  force_and_jacobian_by_autodiff<24>(
      q,
      [&](const Eigen::Matrix<AD, 24, 1>& x) {
        Eigen::Matrix<AD, 24, 1> g;
        const AD h = through_height<AD>(x, side_[e], &g);
        return Eigen::Matrix<AD, 24, 1>(k * (D - sigma * h) * sigma * g);
      },
      out.force, out.dfdq);
}

}  // namespace wl
