// A continuum law fitted to the periodic tile's samples (docs/calibration.md §9.3):
// in the normalized strains t_k = θ_k / s_k (s_k the half-width of the sampled range),
//   W(θ) = W₀ Σ_i c_i φ_i(t),
// with the basis φ of monomials Π t_k^{e_k} of total degree 2 … 8: every
// component's powers (to degree 8), the pairs' couplings t_k^a t_l^b (to
// degree 6) and the couplings of three or more strains (to degree 4), such
// as γ κ_u κ_uv (a sheared cloth's bend–twist coupling).
// No constant or linear term: the woven tile at rest is stress-free. The
// stress is ∂W/∂θ_k = (W₀ / s_k) Σ_i c_i ∂φ_i/∂t_k. Ceres fits c to the
// samples' energies and stresses: per sample the residuals
//   (W_law − W)/W₀,  (∂W_law/∂θ_k − ∂W/∂θ_k)/S_k,
// W₀ and S_k the RMS over the fitted samples of W and of ∂W/∂θ_k.
#pragma once
#include <array>
#include <string>
#include <vector>

#include "calibration/tile_sampling.h"

namespace wl {

inline constexpr int kTileLawDegree = 8, kTileLawCouplingDegree = 6, kTileLawMixedDegree = 4;
// 6·7 powers, 15 pairs × 15 couplings, and the 95 monomials of 3 or 4 strains to degree 4.
inline constexpr int kTileLawBasisSize = 6 * 7 + 15 * 15 + 95;

struct TileLaw {
  std::array<double, 6> scale{1, 1, 1, 1, 1, 1};  // s_k
  double energy_scale = 1.0;                      // W₀ [J/m²]
  std::vector<double> coefficients = std::vector<double>(kTileLawBasisSize, 0.0);
  double energy(const MacroStrain& theta) const;
  std::array<double, 6> stress(const MacroStrain& theta) const;
  // "stretch_warp^2" or "shear^2*twist" for basis function i.
  static std::string basis_name(int i);
};

// φ_i(t) and ∂φ_i/∂t_k (6 per i), for the kTileLawBasisSize functions.
void tile_law_basis(const std::array<double, 6>& t, double* phi, double* dphi);

struct TileLawFit {
  TileLaw law;
  bool converged = false;
  int iterations = 0;
  double final_cost = 0.0;
  std::string message;
};
// Fits the law to `samples` (only converged ones), with the strain scales `scale`.
TileLawFit fit_tile_law(const std::vector<TileSample>& samples, const std::array<double, 6>& scale);

// Relative RMS errors of the law on `samples`: energy sqrt(Σ ΔW²/Σ W²), per
// stress component sqrt(Σ Δσ_k²/Σ σ_k²), and the largest of those six.
struct TileLawErrors {
  int samples = 0;
  double energy = 0.0, stress_max = 0.0;
  std::array<double, 6> stress{};
};
TileLawErrors tile_law_errors(const TileLaw& law, const std::vector<TileSample>& samples);

}  // namespace wl
