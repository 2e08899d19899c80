// What both sliding-friction laws share (docs/models.md §3.7.1): one element per
// sliding DoF of a crossing (local stencil (u0)), evaluated in stage 1 with the
// crossing's contact normal force F_n and the stage-0 force on the DoF, F_u
// ("all other forces", docs/models.md §4.17), read in prepare() and held FROZEN for the
// element; an anchor ū per element; damping −d_f u̇.
#pragma once
#include <string>
#include <vector>

#include "models/core/term.h"
#include "models/scene/parameter_keys.h"
#include "models/yarn/frozen_input_reader.h"

namespace wl {

class FrictionTerm : public StencilTerm<1>, public FrozenInputReader {
 public:
  // dof: the sliding coordinate (u or v) of the crossing; node: its id in the
  // normal-force table (EvalContext::normal_force); anchor0: the rest value of the coordinate.
  void add(int dof, int node, double anchor0);

  std::string name() const override { return "friction"; }
  bool conservative() const override { return false; }
  bool has_velocity_jacobian() const override { return true; }
  int stage() const override { return 1; }
  double energy(int, const double*) const override { return 0.0; }
  void prepare(const EvalContext& ctx) override;

  // Per element, 0 = stick … 1 = slide (for output).
  virtual std::vector<double> sliding_state() const = 0;
  double anchor(int e) const { return anchor_[e]; }
  double tangential_force(int e) const { return Fu_[e]; }  // frozen F_u
  double contact_force(int e) const { return Fn_[e]; }     // frozen F_n
  int normal_force_node(int e) const override { return node_[e]; }
  // ∂F/∂μ at frozen F_u, F_n and anchor (docs/models.md §9.1).
  std::vector<std::string> parameter_keys() const override { return {kFrictionCoefficientKey}; }

 protected:
  // mu friction coefficient; kf spring [N/m] (> 0 when `kf_positive`); df damping
  // [N·s/m]; p tanh sharpness (the papers give none; docs/models.md §5.1).
  FrictionTerm(const char* who, double mu, double kf, double df, double p, bool kf_positive);

  const char* who_;
  double mu_, kf_, df_, p_;
  std::vector<int> node_;
  std::vector<double> anchor_, Fu_, Fn_;
};

}  // namespace wl
