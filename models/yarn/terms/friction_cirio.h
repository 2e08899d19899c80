// Cirio's stick/slip sliding friction on one Eulerian DoF of one crossing,
// docs/models.md §3.7.3 (after Cirio et al. 2016 as retold by the yarn-cloth blog summary §3.4):
//   stick: F = −k_f (u − ū) − d_f u̇
//   slip:  F = −sign(u − ū) μF_n − d_f u̇
//
// The switch (not stated in the sources, docs/models.md §5.5) is a return mapping done in
// accept_step on the accepted state: if k_f|u − ū| > μF_n the crossing slips,
// the anchor is moved so that k_f|u − ū| = μF_n and the slip direction
// sign(u − ū) is stored; otherwise it sticks. The mode (stick, slip+ or slip−)
// is then HELD FIXED for the whole next step, so evaluate() is linear (stick)
// or constant (slip) in u: smooth within a step, with ∂F/∂u = −k_f or 0 and
// ∂F/∂u̇ = −d_f. Consequences: a switch lags by at most one step (a sticking
// spring can exceed μF_n during the step in which it breaks loose), and the
// force is continuous at a stick→slip switch because the moved anchor gives
// exactly k_f|u − ū| = μF_n. A slipping crossing whose motion reverses is
// found back inside the cone at the next accept_step and sticks again.
//
// F_n is a FROZEN input read in prepare() (∂F_n/∂u is ignored). The term runs
// in stage 1 like Gong's friction; it does not use F_u.
//
// Local stencil (u0): one sliding DoF; the model adds one element for u and one
// for v of every sliding crossing.
#pragma once
#include <vector>

#include "models/yarn/terms/friction.h"

namespace wl {

class CirioFrictionTerm : public FrictionTerm {
 public:
  // Same parameters as GongFrictionTerm; p (tanh sharpness) is validated but
  // unused: the stick/slip switch here is discrete, between steps.
  CirioFrictionTerm(double mu, double kf, double df, double p)
      : FrictionTerm("CirioFrictionTerm", mu, kf, df, p, true) {}
  std::unique_ptr<Term> clone() const override { return std::make_unique<CirioFrictionTerm>(*this); }

  void accept_step(const EvalContext& ctx, double h) override;
  void evaluate(int e, const double* q, const double* v, const ElementOutput& out) const override;
  void parameter_derivative(int e, int k, const double* q, const double* v, double* dfdp) const override;
  // ∂F/∂F_n = −sign(u − ū) μ while slipping, 0 while sticking; F_u is not read.
  void frozen_input_derivatives(int e, const double* q, const double* v, double* dfdFn, double* dfdFu) const override;
  // 0 = stick, 1 = slip (the mode held for the current step).
  std::vector<double> sliding_state() const override;
  int slip_direction(int e) const { return e < static_cast<int>(mode_.size()) ? mode_[e] : 0; }  // 0, ±1

 private:
  std::vector<int> mode_;  // per element, sized at the first accept_step
};

}  // namespace wl
