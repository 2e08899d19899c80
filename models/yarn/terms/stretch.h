// Yarn stretch on one segment [x0, x1] of a warp or weft, docs/models.md §3.2
// (Cirio et al. 2016 eqs. (9)–(15); Gong et al. 2022 eq. (24) corrected,
// docs/models.md §4.5).
//   V = ½ k_s Δu (‖w‖−1)²,  w = (x1−x0)/Δu,  Δu = u1−u0 > 0,  k_s = Y·πR² (N).
// Local stencil (8): x0[3], x1[3], u0, u1, where u is the sliding (arc-length)
// coordinate along the segment's own yarn (v for a weft). Frozen u entries are
// encoded constants (types.h). Precondition: u1 > u0 and x1 ≠ x0.
#pragma once
#include <array>
#include <vector>

#include "models/core/term.h"

namespace wl {

class StretchTerm : public ProportionalParameterTerm<8> {
 public:
  using Local = Eigen::Matrix<double, 8, 1>;
  using LocalMatrix = Eigen::Matrix<double, 8, 8>;

  // ks = Y·πR² in N; must be finite and ≥ 0.
  void add(const std::array<int, 8>& stencil, double ks);
  double stiffness(int e) const { return ks_[e]; }

  std::string name() const override { return "stretch"; }
  std::unique_ptr<Term> clone() const override { return std::make_unique<StretchTerm>(*this); }
  double energy(int e, const double* q) const override;
  void evaluate(int e, const double* q, const double* v, const ElementOutput& out) const override;
  // The step matrix takes the element's stiffness projected to its positive
  // semi-definite part, which drops a compressed segment's negative geometric
  // stiffness (docs/models.md §3.2; [terms] stretch_step_hessian).
  void set_projected_step_stiffness(bool on) { projected_ = on; }
  bool projects_step_stiffness() const override { return projected_; }

  // Reusable element kernels (no allocation, thread-safe). q = (x0, x1, u0, u1).
  static double local_energy(const double* q, double ks);
  // Writes the local force (8) and, if K != nullptr, ∂f/∂q (8×8, column-major).
  static void local_evaluate(const double* q, double ks, double* f, double* K);
  // Local force of one segment: (F_x0, F_x1, F_u0, F_u1).
  static Local local_force(const Vec3& x0, const Vec3& x1, double u0, double u1, double ks);

 private:
  std::vector<double> ks_;
  bool projected_ = false;
};

}  // namespace wl
