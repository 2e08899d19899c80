#include "models/fem/terms/border_stretch.h"

#include "models/fem/fem_material.h"

namespace wl {

void BorderStretchTerm::add(const std::array<int, 6>& stencil, double rest_length_m, bool along_u) {
  stencils_.push_back(stencil);
  rest_.push_back(rest_length_m);
  family_.push_back(along_u ? 0 : 1);
}

double BorderStretchTerm::energy(int e, const double* q) const {
  const double l0 = rest_[e];
  const double l = (Eigen::Map<const Vec3>(q + 3) - Eigen::Map<const Vec3>(q)).norm();
  return 0.5 * k_[family_[e]] * width_ * l0 * (l / l0 - 1) * (l / l0 - 1);
}

void BorderStretchTerm::evaluate(int e, const double* q, const double*, const ElementOutput& out) const {
  const double l0 = rest_[e], K = k_[family_[e]] * width_;
  const Vec3 d = Eigen::Map<const Vec3>(q + 3) - Eigen::Map<const Vec3>(q);
  const double l = d.norm();
  if (l < 1e-300) return;
  const Vec3 n = d / l;
  const Vec3 f1 = -K * (l / l0 - 1) * n;
  Eigen::Map<Vec3>(out.force) += -f1;
  Eigen::Map<Vec3>(out.force + 3) += f1;
  if (!out.dfdq) return;
  const Mat3 nn = n * n.transpose();
  const Mat3 k11 = -K / l0 * nn - K * (1 / l0 - 1 / l) * (Mat3::Identity() - nn);
  MatMap J(out.dfdq);
  J.block<3, 3>(0, 0) += k11;
  J.block<3, 3>(3, 3) += k11;
  J.block<3, 3>(0, 3) -= k11;
  J.block<3, 3>(3, 0) -= k11;
}

std::vector<std::string> BorderStretchTerm::parameter_keys() const { return {kFemWarpStretch, kFemWeftStretch}; }

void BorderStretchTerm::parameter_derivative(int e, int k, const double* q, const double*, double* dfdp) const {
  // V is linear in the stiffness of its own family: ∂f/∂k = f/k.
  if (family_[e] != k || k_[k] == 0.0) return;
  double f[6] = {};
  evaluate(e, q, nullptr, ElementOutput{f});
  for (int a = 0; a < 6; ++a) dfdp[a] += f[a] / k_[k];
}

}  // namespace wl
