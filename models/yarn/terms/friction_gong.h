// Gong's differentiable sliding friction on one Eulerian DoF of one crossing,
// docs/models.md §3.7.2, Gong et al. 2022 eq. (4) = (48):
//   F = −( (k_f δu − K(δu) μF_n)/2 · K(μF_n − |F_u|) + (k_f δu + K(δu) μF_n)/2 ) − d_f u̇,
//   δu = u − ū,  K(x) = tanh(p x).
// |F_u| instead of F_u so that a pull in either direction can reach the kinetic
// regime (docs/models.md §4.15); derivatives as corrected in §4.16.
//
// F_u (the stage-0 generalized force on this DoF, "all other forces", docs/models.md §4.17) and
// F_n (contact normal force of the crossing) are FROZEN inputs: read in
// prepare() and held constant for the element, so ∂F/∂u = ∂F/∂δu only and
// ∂F/∂u̇ = −d_f. The anchor ū moves in accept_step (docs/models.md §5.5):
//   ū += sigmoid(10⁴ (|F_u| − μF_n)) · u̇ · h.
//
// Local stencil (u0): one sliding DoF; the model adds one element for u and one
// for v of every sliding crossing.
#pragma once
#include <vector>

#include "models/yarn/terms/friction.h"

namespace wl {

// The friction law without damping at frozen F_u, F_n, with its partial
// derivatives (for chaining ∂F_u/∂q, ∂F_n/∂q if a model wants them; docs/models.md §3.7.2).
struct GongFrictionResponse {
  double force = 0.0;    // F_Slide + d_f u̇
  double d_delta = 0.0;  // ∂/∂δu
  double d_Fu = 0.0;     // ∂/∂F_u
  double d_Fn = 0.0;     // ∂/∂F_n
  double d_mu = 0.0;     // ∂/∂μ
};
GongFrictionResponse gong_friction_law(double delta_u, double F_u, double F_n, double mu, double kf, double p);

class GongFrictionTerm : public FrictionTerm {
 public:
  static constexpr double kSlideSharpness = 1e4;  // 1/N, slide indicator (docs/models.md §5.1)

  GongFrictionTerm(double mu, double kf, double df, double p)
      : FrictionTerm("GongFrictionTerm", mu, kf, df, p, false) {}
  std::unique_ptr<Term> clone() const override { return std::make_unique<GongFrictionTerm>(*this); }

  void accept_step(const EvalContext& ctx, double h) override;
  void evaluate(int e, const double* q, const double* v, const ElementOutput& out) const override;
  void parameter_derivative(int e, int k, const double* q, const double* v, double* dfdp) const override;
  void frozen_input_derivatives(int e, const double* q, const double* v, double* dfdFn, double* dfdFu) const override;
  // The anchor's rate σ = sigmoid(10⁴(|F_u| − μF_n)) of element e at the last
  // prepared inputs, with its derivatives (for the anchor's sensitivity,
  // docs/models.md §9.2).
  struct AnchorRate {
    double sigma = 0.0, d_Fu = 0.0, d_Fn = 0.0, d_mu = 0.0;
  };
  AnchorRate anchor_rate(int e) const;
  // sigmoid(10⁴(|F_u| − μF_n)) at the last prepared inputs.
  std::vector<double> sliding_state() const override;

 private:
  double slide_indicator(double Fu, double Fn) const;
};

}  // namespace wl
