// Gong's shear with shear lock (one quadrant of a crossing), docs/models.md §3.4.3,
// Gong et al. 2022 eqs. (5), (51)–(54):
//   V = ½ k_sh(φ) L (φ − φ̄)²,  φ̄ = π/2,  φ = arccos(d1·d3)
//   k_sh = ½(F_n+1) SπR² ((1+γ^c) + (1−γ^c) tanh g(φ))   (interlacing quadrants, lock)
//   k_sh = (F_n+1) SπR²                                   (otherwise)
//   γ = (√2 L − 2L sin(φ/2))/R,  g = φ̄⁵(φ−φ_l) / ((φ(φ−φ_l)(φ−φ̄))² + φ̄⁴σ²),  φ_l = 2 arcsin(R/L).
// Corrections used: π in the stiffness (docs/models.md §4.10); γ and g are evaluated at the
// mirrored angle φ* = φ̄ − |φ − φ̄| so that k_sh stays positive for φ > φ̄ (§4.12);
// the clean V(φ), V′, V″ form with the generic angle Hessian instead of the
// paper's Jacobians, whose diagonal blocks lack a cross term (§4.13).
//
// F_n of the crossing is a FROZEN input: prepare() copies it from the model's
// table (EvalContext::normal_force) at each evaluation; it is treated as a constant, so ∂F_n/∂x is not part of the
// Jacobian (as in the paper, docs/models.md §5.4) and energy() is the energy at that frozen F_n.
//
// Local stencil (x0, x1, x3): x0 the crossing, x1 a warp neighbour, x3 a weft
// neighbour; the model adds all four quadrants. No force on u, v.
#pragma once
#include <array>
#include <vector>

#include "models/core/term.h"
#include "models/yarn/frozen_input_reader.h"

namespace wl {

struct CrossingAngle;

class GongShearTerm : public ProportionalParameterTerm<9>, public FrozenInputReader {
 public:
  // L segment rest length (m), R yarn radius (m), c lock exponent (paper: 3),
  // sigma lock sharpness (paper: 0.6; smaller = sharper, docs/models.md §4.11).
  // The published code's lock (docs/published_code.md): actual_angle evaluates γ and g at φ itself
  // (row 9); chain_slip writes ∂k/∂x with 1 − f²·g′∇φ in place of (1 − f²)g′∇φ (row 8), which adds
  //   ΔF_xi = h·(1, 1, 1)ᵀ − h g′ ∇_iφ  (i = 1, 3),  ΔF_x0 = −(ΔF_x1 + ΔF_x3),  h = −½ L a² C (1 − γ^c)
  // to the forces (C = ½(F_n+1)SπR², a = φ − φ̄): a force with no potential (conservative() = false).
  struct Published {
    bool actual_angle;
    bool chain_slip;
  };
  GongShearTerm(double L, double R, double c, double sigma, Published published = {false, false});
  std::unique_ptr<Term> clone() const override { return std::make_unique<GongShearTerm>(*this); }

  // node: id of the crossing x0 in the normal-force table. S_pi_R2 = SπR² (N) for
  // this quadrant. lock: use the smooth lock model (interlacing quadrants).
  void add(const std::array<int, 9>& stencil, int node, double S_pi_R2, bool lock);

  std::string name() const override { return "shear"; }
  bool conservative() const override { return !published_.chain_slip; }
  void prepare(const EvalContext& ctx) override;
  double energy(int e, const double* q) const override;
  void evaluate(int e, const double* q, const double* v, const ElementOutput& out) const override;

  // k_sh of element e at angle φ with the current F_n, and its φ-derivatives.
  struct Stiffness {
    double k = 0.0, dk = 0.0, d2k = 0.0;
    // Lock elements: C(1 − γ^c) and g with their φ-derivatives (for the published ∂k/∂x).
    double lock = 0.0, dlock = 0.0, dg = 0.0, d2g = 0.0;
  };
  Stiffness stiffness(int e, double phi) const;
  // k_sh ∝ (F_n + 1) in both laws, so ∂f/∂F_n = f/(F_n + 1) (docs/models.md §3.6.1).
  int normal_force_node(int e) const override { return node_[e]; }
  void frozen_input_derivatives(int e, const double* q, const double* v, double* dfdFn, double* dfdFu) const override;
  double lock_angle() const { return phi_l_; }  // φ_l = 2 arcsin(R/L)

 private:
  // Adds the published chain slip's ΔF (see the constructor) and its exact Jacobian.
  void add_chain_slip(const Stiffness& s, const CrossingAngle& a, const ElementOutput& out) const;

  double L_, R_, c_, sigma_, phi_l_;
  Published published_;
  std::vector<int> node_;
  std::vector<double> S_pi_R2_;
  std::vector<char> lock_;
  std::vector<double> Fn_;  // per element, frozen by prepare()
};

}  // namespace wl
