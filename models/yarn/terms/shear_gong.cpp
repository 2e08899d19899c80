#include "models/yarn/terms/shear_gong.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>
#include <stdexcept>

#include "models/yarn/terms/crossing_angle.h"
#include "models/yarn/terms/frozen_normal_force.h"

namespace wl {
namespace {

constexpr double kRest = std::numbers::pi / 2;  // φ̄

// γ^e for γ ≥ 0; γ = 0 only at φ* = φ̄, where the terms it multiplies vanish.
double safe_pow(double gamma, double e) { return gamma > 0.0 ? std::pow(gamma, e) : (e == 0.0 ? 1.0 : 0.0); }

}  // namespace

GongShearTerm::GongShearTerm(double L, double R, double c, double sigma, Published published)
    : L_(L), R_(R), c_(c), sigma_(sigma), published_(published) {
  std::ostringstream bad;
  if (!(L > 0.0)) bad << "L = " << L << " (expected > 0)";
  else if (!(R > 0.0 && R * std::sqrt(2.0) < L))  // φ_l = 2 arcsin(R/L) < π/2
    bad << "R = " << R << " (expected 0 < R < L/√2 = " << L / std::sqrt(2.0) << ", lock angle below π/2)";
  else if (!(c > 0.0)) bad << "c = " << c << " (expected > 0)";
  else if (!(sigma > 0.0)) bad << "sigma = " << sigma << " (expected > 0)";
  else if (published.actual_angle && !(c >= 2.0 && c == std::floor(c)))  // γ < 0 beyond φ̄: integer powers only
    bad << "c = " << c << " (expected an integer >= 2 with the lock at the actual angle)";
  if (!bad.str().empty()) throw std::invalid_argument("GongShearTerm: " + bad.str());
  phi_l_ = 2.0 * std::asin(R / L);
}

void GongShearTerm::add(const std::array<int, 9>& stencil, int node, double S_pi_R2, bool lock) {
  if (!(S_pi_R2 >= 0.0)) {
    std::ostringstream msg;
    msg << "GongShearTerm: S pi R^2 = " << S_pi_R2 << " (expected >= 0)";
    throw std::invalid_argument(msg.str());
  }
  stencils_.push_back(stencil);
  node_.push_back(node);
  S_pi_R2_.push_back(S_pi_R2);
  lock_.push_back(lock ? 1 : 0);
  Fn_.push_back(0.0);
}

void GongShearTerm::prepare(const EvalContext& ctx) { freeze_normal_force(ctx, node_, Fn_, "GongShearTerm"); }

// k_sh(φ) and its derivatives, docs/models.md §3.4.3, with γ
// and g at the mirrored angle φ* = φ̄ − |φ − φ̄| (docs/models.md §4.12): k(φ) = K(φ*),
// k′ = K′(φ*) dφ*/dφ with dφ*/dφ = ±1, k″ = K″(φ*).
GongShearTerm::Stiffness GongShearTerm::stiffness(int e, double phi) const {
  const double Fn = Fn_[e];
  Stiffness s;
  if (!lock_[e]) {
    s.k = (Fn + 1.0) * S_pi_R2_[e];  // k_sh = (1+F_n) SπR², Gong et al. 2022 §3.3
    return s;
  }
  const double C = 0.5 * (Fn + 1.0) * S_pi_R2_[e];
  const bool actual = published_.actual_angle;  // docs/published_code.md row 9
  const double ps = actual ? phi : kRest - std::abs(phi - kRest);
  const double dps = actual || phi <= kRest ? 1.0 : -1.0;
  const double L = L_, R = R_, c = c_, pb = kRest, pl = phi_l_;

  const double gamma_raw = (std::sqrt(2.0) * L - 2.0 * L * std::sin(ps / 2)) / R;
  const double gamma = actual ? gamma_raw : std::max(0.0, gamma_raw);
  const auto power = [actual](double base, double exponent) {
    return actual ? std::pow(base, exponent) : safe_pow(base, exponent);
  };
  const double dgamma = -L / R * std::cos(ps / 2);
  const double d2gamma = L / (2.0 * R) * std::sin(ps / 2);

  const double pb4 = pb * pb * pb * pb, pb5 = pb4 * pb;
  const double N = pb5 * (ps - pl);
  const double P = ps * (ps - pl) * (ps - pb);
  const double dP = 3.0 * ps * ps - 2.0 * (pl + pb) * ps + pl * pb;
  const double d2P = 6.0 * ps - 2.0 * (pl + pb);
  const double D = P * P + pb4 * sigma_ * sigma_;
  const double dD = 2.0 * P * dP, d2D = 2.0 * (dP * dP + P * d2P);
  const double g = N / D;
  const double dg = (pb5 * D - N * dD) / (D * D);
  const double d2g = -N * d2D / (D * D) - 2.0 * dD * dg / D;

  const double f = std::tanh(g);
  const double df = (1.0 - f * f) * dg;
  const double d2f = (1.0 - f * f) * (d2g - 2.0 * f * dg * dg);

  const double gc = power(gamma, c), gc1 = power(gamma, c - 1.0), gc2 = power(gamma, c - 2.0);
  const double K = C * ((1.0 + gc) + (1.0 - gc) * f);
  const double dK = C * (c * gc1 * dgamma * (1.0 - f) + (1.0 - gc) * df);
  const double d2K = C * (c * (c - 1.0) * gc2 * dgamma * dgamma * (1.0 - f) + c * gc1 * d2gamma * (1.0 - f) -
                          2.0 * c * gc1 * dgamma * df + (1.0 - gc) * d2f);
  s.k = K;
  s.dk = dK * dps;
  s.d2k = d2K;
  s.lock = C * (1.0 - gc);
  s.dlock = -C * c * gc1 * dgamma * dps;
  s.dg = dg * dps;
  s.d2g = d2g;
  return s;
}

// V = ½ k_sh(φ) L (φ − φ̄)², Gong et al. 2022 eq. (51), docs/models.md §3.4.3.
double GongShearTerm::energy(int e, const double* q) const {
  const CrossingAngle a(q);
  const double d = a.phi - kRest;
  return 0.5 * stiffness(e, a.phi).k * L_ * d * d;
}

// V′ = ½k′La² + kLa, V″ = ½k″La² + 2k′La + kL with a = φ − φ̄; then
// F = −V′∇φ, ∂F/∂x = −(V″∇φ∇φᵀ + V′H) (docs/models.md §3.4.1, §3.4.3).
// A degenerate crossing (φ → 0, π) gets zero force: ∇φ has no direction there.
void GongShearTerm::evaluate(int e, const double* q, const double*, const ElementOutput& out) const {
  const CrossingAngle a(q);
  if (a.degenerate) return;
  const Stiffness s = stiffness(e, a.phi);
  const double d = a.phi - kRest;
  const double dV = 0.5 * s.dk * L_ * d * d + s.k * L_ * d;
  const double d2V = 0.5 * s.d2k * L_ * d * d + 2.0 * s.dk * L_ * d + s.k * L_;
  a.write(dV, d2V, out);
  if (published_.chain_slip && lock_[e]) add_chain_slip(s, a, out);
}

// ΔF_xi = h·1 − m ∇_iφ (i = 1, 3; m = h g′), ΔF_x0 = −(ΔF_x1 + ΔF_x3), h = −½ L a² C(1 − γ^c), so
//   ∂ΔF_xi/∂x_j = 1 h′ ∇_jφᵀ − m′ ∇_iφ ∇_jφᵀ − m H_ij,  h′ = −L a C(1 − γ^c) − ½ L a² (C(1 − γ^c))′,
//   m′ = h′ g′ + h g″   (docs/published_code.md row 8).
void GongShearTerm::add_chain_slip(const Stiffness& s, const CrossingAngle& a, const ElementOutput& out) const {
  using Vec9 = CrossingAngle::Vec9;
  using Mat9 = CrossingAngle::Mat9;
  const double d = a.phi - kRest;
  const double h = -0.5 * L_ * d * d * s.lock;
  const double dh = -L_ * d * s.lock - 0.5 * L_ * d * d * s.dlock;
  const double m = h * s.dg, dm = dh * s.dg + h * s.d2g;
  // 1 on the rows of x1 and x3, −2 on those of x0 (translation invariance).
  Vec9 ones;
  ones << -2.0, -2.0, -2.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0;
  Eigen::Map<Vec9> f(out.force);
  f += h * ones - m * a.grad;
  if (!out.dfdq) return;
  Eigen::Map<Mat9> K(out.dfdq);
  K += dh * ones * a.grad.transpose() - dm * a.grad * a.grad.transpose() - m * a.hessian();
}

void GongShearTerm::frozen_input_derivatives(int e, const double* q, const double* v, double* dfdFn, double*) const {
  LVec f = LVec::Zero();
  evaluate(e, q, v, ElementOutput{f.data()});
  for (int a = 0; a < 9; ++a) dfdFn[a] += f[a] / (Fn_[e] + 1.0);
}

}  // namespace wl
