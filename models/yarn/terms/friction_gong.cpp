#include "models/yarn/terms/friction_gong.h"

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace wl {

// A = k_f δu − K_δ μF_n, B = k_f δu + K_δ μF_n, K_δ = tanh(p δu), K₂ = tanh(p(μF_n − |F_u|));
// F = −(A K₂ + B)/2 and, docs/models.md §3.7.2 with §4.16 (p restored, sign of the
// F_u term flipped) and §4.15 (|F_u|):
//   ∂F/∂δu  = −½(k_f − p(1−K_δ²)μF_n) K₂ − ½(k_f + p(1−K_δ²)μF_n)
//   ∂F/∂F_u = +½ A p (1−K₂²) sign(F_u)
//   ∂F/∂F_n = ½ K_δ μ K₂ − ½ A p (1−K₂²) μ − ½ K_δ μ
//   ∂F/∂μ   = ½ K_δ F_n K₂ − ½ A p (1−K₂²) F_n − ½ K_δ F_n   (μ and F_n enter only as μF_n)
GongFrictionResponse gong_friction_law(double delta_u, double F_u, double F_n, double mu, double kf, double p) {
  const double Kd = std::tanh(p * delta_u);
  const double K2 = std::tanh(p * (mu * F_n - std::abs(F_u)));
  const double A = kf * delta_u - Kd * mu * F_n;
  const double B = kf * delta_u + Kd * mu * F_n;
  const double dKd = p * (1.0 - Kd * Kd), dK2 = p * (1.0 - K2 * K2);
  const double sgn = F_u > 0.0 ? 1.0 : (F_u < 0.0 ? -1.0 : 0.0);
  GongFrictionResponse r;
  r.force = -0.5 * (A * K2 + B);
  r.d_delta = -0.5 * (kf - dKd * mu * F_n) * K2 - 0.5 * (kf + dKd * mu * F_n);
  r.d_Fu = 0.5 * A * dK2 * sgn;
  r.d_Fn = 0.5 * Kd * mu * K2 - 0.5 * A * dK2 * mu - 0.5 * Kd * mu;
  r.d_mu = 0.5 * Kd * F_n * K2 - 0.5 * A * dK2 * F_n - 0.5 * Kd * F_n;
  return r;
}

double GongFrictionTerm::slide_indicator(double Fu, double Fn) const {
  return 1.0 / (1.0 + std::exp(-kSlideSharpness * (std::abs(Fu) - mu_ * Fn)));
}

// ū += sigmoid(10⁴(|F_u| − μF_n)) u̇ h (docs/models.md §5.5). F_u is taken from the
// context when the caller provides the stage-0 force of the accepted state,
// otherwise from the last prepare(); F_n is the current table value.
void GongFrictionTerm::accept_step(const EvalContext& ctx, double h) {
  for (int e = 0; e < num_elements(); ++e) {
    const int dof = stencils_[e][0];
    if (!is_dof(dof) || !ctx.v) continue;
    const double Fu = ctx.force_so_far ? (*ctx.force_so_far)[dof] : Fu_[e];
    const double Fn = Fn_[e];
    anchor_[e] += slide_indicator(Fu, Fn) * (*ctx.v)[dof] * h;
  }
}

void GongFrictionTerm::evaluate(int e, const double* q, const double* v, const ElementOutput& out) const {
  const GongFrictionResponse r = gong_friction_law(q[0] - anchor_[e], Fu_[e], Fn_[e], mu_, kf_, p_);
  out.force[0] = r.force - df_ * v[0];
  if (out.dfdq) out.dfdq[0] = r.d_delta;
  if (out.dfdv) out.dfdv[0] = -df_;
}

void GongFrictionTerm::parameter_derivative(int e, int, const double* q, const double*, double* dfdp) const {
  dfdp[0] += gong_friction_law(q[0] - anchor_[e], Fu_[e], Fn_[e], mu_, kf_, p_).d_mu;
}

void GongFrictionTerm::frozen_input_derivatives(int e, const double* q, const double*, double* dfdFn,
                                                double* dfdFu) const {
  const GongFrictionResponse r = gong_friction_law(q[0] - anchor_[e], Fu_[e], Fn_[e], mu_, kf_, p_);
  dfdFn[0] += r.d_Fn;
  dfdFu[0] += r.d_Fu;
}

// σ′ = 10⁴ σ(1 − σ): ∂σ/∂F_u = σ′ sign(F_u), ∂σ/∂F_n = −σ′μ, ∂σ/∂μ = −σ′F_n.
GongFrictionTerm::AnchorRate GongFrictionTerm::anchor_rate(int e) const {
  AnchorRate r;
  r.sigma = slide_indicator(Fu_[e], Fn_[e]);
  const double ds = kSlideSharpness * r.sigma * (1.0 - r.sigma);
  r.d_Fu = Fu_[e] > 0.0 ? ds : (Fu_[e] < 0.0 ? -ds : 0.0);
  r.d_Fn = -ds * mu_;
  r.d_mu = -ds * Fn_[e];
  return r;
}

std::vector<double> GongFrictionTerm::sliding_state() const {
  std::vector<double> s(num_elements());
  for (int e = 0; e < num_elements(); ++e) s[e] = slide_indicator(Fu_[e], Fn_[e]);
  return s;
}

}  // namespace wl
