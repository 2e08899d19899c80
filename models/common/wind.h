// Wind and air drag on one triangle, docs/models.md §3.9, Gong et al. 2022 eqs. (68)–(69)
// as corrected in docs/models.md §4.19 (relative wind, area on the drag term):
//   v_rel = v_w − (ẋ0 + ẋ1 + ẋ2)/3,  v_n = n_f·v_rel,  v_t = v_rel − v_n n_f
//   F_w = ρ_w a |v_n| v_n n_f + d_w a v_t,   each node gets F_w / 3.
// a is the triangle area and n_f its unit normal; F_w does not depend on the
// orientation of n_f. Non-conservative: energy() is 0. Both ∂F/∂x (through a
// and n_f) and ∂F/∂ẋ are provided. A degenerate (zero-area) triangle gets no
// force. Shared by the yarn model (two triangles per grid cell) and the FEM model.
//
// Local stencil (x0, x1, x2).
#pragma once
#include <array>

#include "models/core/term.h"

namespace wl {

class WindTerm : public StencilTerm<9> {
 public:
  // wind_velocity v_w (m/s), air_density ρ_w (kg/m³; the paper uses 2), drag d_w
  // (N·s/m³, tangential drag per area; the paper uses 0.5).
  WindTerm(const Vec3& wind_velocity, double air_density, double drag);

  void add(const std::array<int, 9>& stencil);

  std::string name() const override { return "wind"; }
  std::unique_ptr<Term> clone() const override { return std::make_unique<WindTerm>(*this); }
  bool imex_explicit() const override { return true; }  // non-stiff external load
  bool conservative() const override { return false; }
  bool has_velocity_jacobian() const override { return true; }
  double energy(int, const double*) const override { return 0.0; }
  void evaluate(int e, const double* q, const double* v, const ElementOutput& out) const override;

  const Vec3& wind_velocity() const { return wind_; }

 private:
  Vec3 wind_;
  double rho_, drag_;
};

}  // namespace wl
