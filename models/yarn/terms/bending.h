// Yarn bending on three consecutive nodes of one yarn, docs/models.md §3.3
// (Cirio et al. 2016 eqs. (16)–(40); Gong et al. 2022 corrected, docs/models.md §4.6–§4.9).
//   V = k_b θ²/U,  θ = arccos(−d_1·d_2),  U = u1 − u2 > 0,  k_b = B·πR² (N·m²).
// Local stencil (11): x0[3] (centre), x1[3] (next node, +u), x2[3] (previous
// node, −u), u1, u2. The centre's own u does not enter.
//
// Robust form [derived]. With e1 = d_1, e2 = −d_2 (both pointing along +u) and
// c = e1·e2 = cos θ, V = (k_b/U)·Φ(c) with Φ = arccos(c)². Then
//   Φ'(c) = −2α(θ),  α = θ/sin θ,   Φ''(c) = 2β(θ),  β = (1 − θ cot θ)/sin²θ,
// both finite at θ = 0 (α → 1, β → 1/3) and evaluated by series for small θ;
// θ = atan2(‖e1×e2‖, e1·e2) and P_1 e2 = (e1×e2)×e1 avoid cancellation. The
// force −(k_b/U)Φ'∇c and Jacobian −(k_b/U)(Φ''∇c∇cᵀ + Φ'∇²c) are Cirio et al. 2016 eqs. (21)–(40)
// rewritten (equal term by term for θ > 0; checked against eqs. 28–29 in the tests).
// Precondition: θ < π (a yarn folded back onto itself is singular), l_1, l_2 > 0.
#pragma once
#include <array>
#include <vector>

#include "models/core/term.h"

namespace wl {

class BendingTerm : public ProportionalParameterTerm<11> {
 public:
  using Local = Eigen::Matrix<double, 11, 1>;
  using LocalMatrix = Eigen::Matrix<double, 11, 11>;

  // sliding_theta: F_u1 = −F_u2 = k_b θ/U², as the published code computes it (docs/published_code.md
  // row 6), instead of the energy's k_b θ²/U²; the forces on x stay the energy's. That force has no
  // potential (conservative() = false); its Jacobian is its exact derivative.
  explicit BendingTerm(bool sliding_theta = false) : sliding_theta_(sliding_theta) {}

  // kb = B·πR²; must be finite and ≥ 0.
  void add(const std::array<int, 11>& stencil, double kb);
  double stiffness(int e) const { return kb_[e]; }

  std::string name() const override { return "bending"; }
  std::unique_ptr<Term> clone() const override { return std::make_unique<BendingTerm>(*this); }
  bool conservative() const override { return !sliding_theta_; }
  double energy(int e, const double* q) const override;
  void evaluate(int e, const double* q, const double* v, const ElementOutput& out) const override;

  // Reusable element kernels (no allocation, thread-safe). q = (x0, x1, x2, u1, u2).
  static double local_energy(const double* q, double kb);
  // Writes the local force (11) and, if K != nullptr, ∂f/∂q (11×11, column-major).
  static void local_evaluate(const double* q, double kb, double* f, double* K);
  // Local force: (F_x0, F_x1, F_x2, F_u1, F_u2).
  static Local local_force(const Vec3& x0, const Vec3& x1, const Vec3& x2, double u1, double u2, double kb);
  // Bending angle θ ∈ [0, π] of the stencil (0 for a straight yarn).
  static double angle(const Vec3& x0, const Vec3& x1, const Vec3& x2);

 private:
  bool sliding_theta_;
  std::vector<double> kb_;
};

}  // namespace wl
