#include "models/fem/terms/shear_stiffness_spline.h"

#include <cmath>
#include <stdexcept>

namespace wl {

ShearStiffnessSpline::ShearStiffnessSpline(std::vector<double> knots_s) {
  for (double a : knots_s) {
    if (!(a > a_.back()) || !(a < 1.0))
      throw std::invalid_argument("shear spline: knots must increase within (0, 1) in sin γ");
    a_.push_back(a);
  }
}

void ShearStiffnessSpline::evaluate(double s, const double* k, double* e, double* de, double* dde) const {
  const double a = std::abs(s), sign = s < 0 ? -1.0 : 1.0;
  const int n = static_cast<int>(a_.size()) - 1;
  double sigma = 0.0, energy = 0.0;  // σ(a_i), E(a_i)
  for (int i = 0; i < n; ++i) {
    const double w = a_[i + 1] - a_[i], d = k[i + 1] - k[i];
    if (a < a_[i + 1]) {
      const double t = (a - a_[i]) / w, t2 = t * t;
      *dde = k[i] + d * t2 * (3.0 - 2.0 * t);
      *de = sign * (sigma + w * (k[i] * t + d * t2 * t * (1.0 - 0.5 * t)));
      *e = energy + sigma * (a - a_[i]) + w * w * (0.5 * k[i] * t2 + d * t2 * t2 * (0.25 - 0.1 * t));
      return;
    }
    energy += sigma * w + w * w * (0.5 * k[i] + 0.15 * d);
    sigma += w * (k[i] + 0.5 * d);
  }
  const double x = a - a_[n];  // beyond the last knot: κ = k_n
  *dde = k[n];
  *de = sign * (sigma + k[n] * x);
  *e = energy + sigma * x + 0.5 * k[n] * x * x;
}

}  // namespace wl
