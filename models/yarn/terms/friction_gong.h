// Gong's differentiable sliding friction on one Eulerian DoF of one crossing,
// physics.md §3.7(b), seed 003 (4)=(48):
//   F = −( (k_f δu − K(δu) μF_n)/2 · K(μF_n − |F_u|) + (k_f δu + K(δu) μF_n)/2 ) − d_f u̇,
//   δu = u − ū,  K(x) = tanh(p x).
// |F_u| instead of F_u so that a pull in either direction can reach the kinetic
// regime (I-28); derivatives as corrected in I-27.
//
// F_u (the stage-0 generalized force on this DoF, "all other forces", I-50) and
// F_n (contact normal force of the crossing) are FROZEN inputs: read in
// prepare() and held constant for the element, so ∂F/∂u = ∂F/∂δu only and
// ∂F/∂u̇ = −d_f. The anchor ū moves in accept_step (Appendix A):
//   ū += sigmoid(10⁴ (|F_u| − μF_n)) · u̇ · h.
//
// Local stencil (u0): one sliding DoF; the model adds one element for u and one
// for v of every sliding crossing.
#pragma once
#include <vector>

#include "models/core/term.h"

namespace wl {

// The friction law without damping at frozen F_u, F_n, with its partial
// derivatives (for chaining ∂F_u/∂q, ∂F_n/∂q if a model wants them; I-27).
struct GongFrictionResponse {
  double force = 0.0;    // F_Slide + d_f u̇
  double d_delta = 0.0;  // ∂/∂δu
  double d_Fu = 0.0;     // ∂/∂F_u
  double d_Fn = 0.0;     // ∂/∂F_n
};
GongFrictionResponse gong_friction_law(double delta_u, double F_u, double F_n, double mu, double kf, double p);

class GongFrictionTerm : public StencilTerm<1> {
 public:
  static constexpr double kSlideSharpness = 1e4;  // 1/N, slide indicator (Appendix A)

  // normal_force: per-node F_n (N), owned by the model (null: F_n = 0). mu
  // friction coefficient, kf spring (N/m), df damping (N·s/m), p tanh
  // sharpness (1/m and 1/N; the seeds give none, the authors' code uses 10).
  GongFrictionTerm(const std::vector<double>* normal_force, double mu, double kf, double df, double p);

  // dof: the sliding coordinate (u or v) of the crossing; node: its index into
  // *normal_force; anchor0: the rest value of the coordinate.
  void add(int dof, int node, double anchor0);

  std::string name() const override { return "friction"; }
  bool conservative() const override { return false; }
  bool has_velocity_jacobian() const override { return true; }
  int stage() const override { return 1; }
  void prepare(const EvalContext& ctx) override;
  void accept_step(const EvalContext& ctx, double h) override;
  double energy(int, const double*) const override { return 0.0; }
  void evaluate(int e, const double* q, const double* v, const ElementOutput& out) const override;

  // Per element: sigmoid(10⁴(|F_u| − μF_n)) at the last prepared inputs, 0 = stick … 1 = slide.
  std::vector<double> sliding_state() const;
  double anchor(int e) const { return anchor_[e]; }
  double tangential_force(int e) const { return Fu_[e]; }  // frozen F_u
  double contact_force(int e) const { return Fn_[e]; }     // frozen F_n

 private:
  double slide_indicator(double Fu, double Fn) const;

  const std::vector<double>* normal_force_;
  double mu_, kf_, df_, p_;
  std::vector<int> node_;
  std::vector<double> anchor_, Fu_, Fn_;
};

}  // namespace wl
