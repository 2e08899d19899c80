// Gravity on a yarn segment with sliding end coordinates (docs/models.md §3.8,
// Gong et al. 2022 eqs. (59)–(67)). Local stencil (x0[3], x1[3], u0, u1). g is the
// acceleration vector (pointing down, e.g. (0, 0, −9.81) m/s²); the paper's g
// points up, so here V = −ρ Δu gᵀ(x0 + x1)/2, the exact ∫ −ρ gᵀx(u) du.
#pragma once
#include <array>
#include <string>
#include <vector>

#include "models/core/term.h"

namespace wl {

class GravityTerm : public ProportionalParameterTerm<8> {
 public:
  explicit GravityTerm(const Vec3& g_m_per_s2);
  // One segment; rho is the linear density in kg/m (> 0).
  void add(const std::array<int, 8>& stencil, double rho);

  std::string name() const override { return "gravity"; }
  std::unique_ptr<Term> clone() const override { return std::make_unique<GravityTerm>(*this); }
  bool imex_explicit() const override { return true; }  // non-stiff external load
  double energy(int e, const double* q) const override;
  void evaluate(int e, const double* q, const double* v, const ElementOutput& out) const override;

 private:
  Vec3 g_;
  std::vector<double> rho_;
};

}  // namespace wl
