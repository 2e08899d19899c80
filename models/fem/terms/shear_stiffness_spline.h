// The tangent shear stiffness of the spline shear law [not in the sources; docs/models.md §6.4.1],
// a function of a = |s|, s = sin γ the cosine of the warp/weft angle:
//   κ(a) = k_i + (k_{i+1} − k_i)·h(t),  t = (a − a_i)/(a_{i+1} − a_i),  h(t) = 3t² − 2t³,
// on each interval between knots 0 = a_0 < a_1 < … < a_n, and κ = k_n beyond a_n: a cubic Hermite
// interpolant with zero slopes at the knots, monotone on every interval and so between its knot
// values (κ > 0 when every k_i > 0), C¹, with κ'(0) = 0. Its integrals are closed-form,
//   σ(a) = ∫₀ᵃ κ,  E(a) = ∫₀ᵃ σ   (∫₀ᵗ h = t³ − t⁴/2, ∫₀ᵗ∫₀ʳ h = t⁴/4 − t⁵/10),
// and E(|s|) is the law's energy per area before the lock: even in s, convex, ½k_0 s² near 0.
// Everything is linear in the knot values, so ∂/∂k_j is the same curve with k = e_j.
#pragma once
#include <vector>

namespace wl {

class ShearStiffnessSpline {
 public:
  ShearStiffnessSpline() = default;
  // knots_s: a_1 < … < a_n, all in (0, 1).
  explicit ShearStiffnessSpline(std::vector<double> knots_s);
  int num_values() const { return static_cast<int>(a_.size()); }  // n + 1: k_0 … k_n
  // E(|s|) and its first two derivatives in s at knot values k[0 … n].
  void evaluate(double s, const double* k, double* e, double* de, double* dde) const;

 private:
  std::vector<double> a_{0.0};  // a_0 = 0, a_1, …, a_n
};

}  // namespace wl
