#include "calibration/tile_law.h"

#include <ceres/ceres.h>

#include <cmath>
#include <memory>

namespace wl {
namespace {

std::array<double, 6> normalized(const MacroStrain& theta, const std::array<double, 6>& scale) {
  std::array<double, 6> t{};
  for (int k = 0; k < 6; ++k) t[k] = theta[k] / scale[k];
  return t;
}

// The (k, l) pair of coupling slot p (k < l), in the order of the basis.
std::pair<int, int> pair_of(int p) {
  for (int k = 0, n = 0; k < 6; ++k)
    for (int l = k + 1; l < 6; ++l, ++n)
      if (n == p) return {k, l};
  return {-1, -1};
}

// The residuals of one sample: energy and six stresses, linear in c.
class TileSampleCost final : public ceres::CostFunction {
 public:
  TileSampleCost(const TileSample& s, const TileLaw& law, const std::array<double, 6>& stress_scale)
      : sample_(s), law_(law), stress_scale_(stress_scale) {
    set_num_residuals(7);
    mutable_parameter_block_sizes()->push_back(kTileLawBasisSize);
    tile_law_basis(normalized(s.strain, law.scale), phi_.data(), dphi_.data());
  }
  bool Evaluate(double const* const* parameters, double* residuals, double** jacobians) const override {
    const double* c = parameters[0];
    // r_0 = (W₀ Σ c_i φ_i − W)/W₀; r_k = ((W₀/s_k) Σ c_i ∂_k φ_i − σ_k)/S_k.
    residuals[0] = -sample_.energy_density / law_.energy_scale;
    for (int k = 0; k < 6; ++k) residuals[1 + k] = -sample_.stress[k] / stress_scale_[k];
    for (int i = 0; i < kTileLawBasisSize; ++i) {
      residuals[0] += c[i] * phi_[i];
      for (int k = 0; k < 6; ++k) residuals[1 + k] += c[i] * stress_factor(k) * dphi_[6 * i + k];
    }
    if (jacobians && jacobians[0])
      for (int i = 0; i < kTileLawBasisSize; ++i) {
        jacobians[0][i] = phi_[i];
        for (int k = 0; k < 6; ++k) jacobians[0][(1 + k) * kTileLawBasisSize + i] = stress_factor(k) * dphi_[6 * i + k];
      }
    return true;
  }

 private:
  double stress_factor(int k) const { return law_.energy_scale / (law_.scale[k] * stress_scale_[k]); }
  TileSample sample_;
  const TileLaw& law_;
  std::array<double, 6> stress_scale_;
  std::array<double, kTileLawBasisSize> phi_{};
  std::array<double, 6 * kTileLawBasisSize> dphi_{};
};

}  // namespace

void tile_law_basis(const std::array<double, 6>& t, double* phi, double* dphi) {
  std::fill(dphi, dphi + 6 * kTileLawBasisSize, 0.0);
  int i = 0;
  for (int k = 0; k < 6; ++k)
    for (int d = 2; d <= kTileLawDegree; ++d, ++i) {
      phi[i] = std::pow(t[k], d);
      dphi[6 * i + k] = d * std::pow(t[k], d - 1);
    }
  for (int p = 0; p < 15; ++p) {
    const auto [k, l] = pair_of(p);
    const double a = t[k], b = t[l];
    // t_k t_l, t_k² t_l, t_k t_l², t_k² t_l²
    const std::array<std::array<double, 3>, 4> f{{{a * b, b, a},
                                                  {a * a * b, 2 * a * b, a * a},
                                                  {a * b * b, b * b, 2 * a * b},
                                                  {a * a * b * b, 2 * a * b * b, 2 * a * a * b}}};
    for (const auto& [value, dk, dl] : f) {
      phi[i] = value;
      dphi[6 * i + k] = dk;
      dphi[6 * i + l] = dl;
      ++i;
    }
  }
}

double TileLaw::energy(const MacroStrain& theta) const {
  std::array<double, kTileLawBasisSize> phi{};
  std::array<double, 6 * kTileLawBasisSize> dphi{};
  tile_law_basis(normalized(theta, scale), phi.data(), dphi.data());
  double w = 0.0;
  for (int i = 0; i < kTileLawBasisSize; ++i) w += coefficients[i] * phi[i];
  return energy_scale * w;
}

std::array<double, 6> TileLaw::stress(const MacroStrain& theta) const {
  std::array<double, kTileLawBasisSize> phi{};
  std::array<double, 6 * kTileLawBasisSize> dphi{};
  tile_law_basis(normalized(theta, scale), phi.data(), dphi.data());
  std::array<double, 6> s{};
  for (int i = 0; i < kTileLawBasisSize; ++i)
    for (int k = 0; k < 6; ++k) s[k] += coefficients[i] * dphi[6 * i + k];
  for (int k = 0; k < 6; ++k) s[k] *= energy_scale / scale[k];
  return s;
}

std::string TileLaw::basis_name(int i) {
  const int powers = 6 * (kTileLawDegree - 1);
  if (i < powers)
    return std::string("power:") + kMacroStrainNames[i / (kTileLawDegree - 1)] + "^" +
           std::to_string(2 + i % (kTileLawDegree - 1));
  const auto [k, l] = pair_of((i - powers) / 4);
  const std::array<const char*, 4> ek{"", "^2", "", "^2"}, el{"", "", "^2", "^2"};
  const int form = (i - powers) % 4;
  return std::string("coupling:") + kMacroStrainNames[k] + ek[form] + "*" + kMacroStrainNames[l] + el[form];
}

TileLawFit fit_tile_law(const std::vector<TileSample>& samples, const std::array<double, 6>& scale) {
  TileLawFit fit;
  fit.law.scale = scale;
  std::vector<const TileSample*> used;
  double w2 = 0.0;
  std::array<double, 6> s2{};
  for (const TileSample& s : samples) {
    if (!s.converged) continue;
    used.push_back(&s);
    w2 += s.energy_density * s.energy_density;
    for (int k = 0; k < 6; ++k) s2[k] += s.stress[k] * s.stress[k];
  }
  if (used.empty() || !(w2 > 0.0)) {
    fit.message = "no converged sample with a non-zero energy";
    return fit;
  }
  fit.law.energy_scale = std::sqrt(w2 / used.size());
  std::array<double, 6> stress_scale{};
  for (int k = 0; k < 6; ++k) stress_scale[k] = s2[k] > 0.0 ? std::sqrt(s2[k] / used.size()) : 1.0;
  ceres::Problem problem;
  for (const TileSample* s : used)
    problem.AddResidualBlock(new TileSampleCost(*s, fit.law, stress_scale), nullptr, fit.law.coefficients.data());
  ceres::Solver::Options options;
  options.linear_solver_type = ceres::DENSE_QR;
  options.max_num_iterations = 50;
  // The law is linear in c: solve to round-off, not to Ceres' default relative decrease.
  options.function_tolerance = 1e-15;
  options.gradient_tolerance = 1e-16;
  options.parameter_tolerance = 1e-14;
  options.num_threads = 1;
  options.logging_type = ceres::SILENT;
  ceres::Solver::Summary summary;
  ceres::Solve(options, &problem, &summary);
  fit.converged = summary.termination_type == ceres::CONVERGENCE;
  fit.iterations = static_cast<int>(summary.iterations.size());
  fit.final_cost = summary.final_cost;
  fit.message = summary.message;
  return fit;
}

TileLawErrors tile_law_errors(const TileLaw& law, const std::vector<TileSample>& samples) {
  TileLawErrors e;
  double dw2 = 0.0, w2 = 0.0;
  std::array<double, 6> ds2{}, s2{};
  for (const TileSample& s : samples) {
    if (!s.converged) continue;
    ++e.samples;
    const double dw = law.energy(s.strain) - s.energy_density;
    dw2 += dw * dw;
    w2 += s.energy_density * s.energy_density;
    const std::array<double, 6> stress = law.stress(s.strain);
    for (int k = 0; k < 6; ++k) {
      ds2[k] += (stress[k] - s.stress[k]) * (stress[k] - s.stress[k]);
      s2[k] += s.stress[k] * s.stress[k];
    }
  }
  e.energy = w2 > 0.0 ? std::sqrt(dw2 / w2) : 0.0;
  for (int k = 0; k < 6; ++k) {
    e.stress[k] = s2[k] > 0.0 ? std::sqrt(ds2[k] / s2[k]) : 0.0;
    e.stress_max = std::max(e.stress_max, e.stress[k]);
  }
  return e;
}

}  // namespace wl
