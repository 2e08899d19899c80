#include "calibration/tile_law.h"

#include <ceres/ceres.h>

#include <cmath>
#include <functional>
#include <memory>
#include <stdexcept>
#include <vector>

namespace wl {
namespace {

std::array<double, 6> normalized(const MacroStrain& theta, const std::array<double, 6>& scale) {
  std::array<double, 6> t{};
  for (int k = 0; k < 6; ++k) t[k] = theta[k] / scale[k];
  return t;
}

// The exponents of every basis function, in the order of the header.
const std::vector<std::array<int, 6>>& basis_exponents() {
  static const std::vector<std::array<int, 6>> exponents = [] {
    std::vector<std::array<int, 6>> e;
    // Every exponent vector of total degree 2 … kTileLawDegree, in lexicographic order, kept by its class.
    std::array<int, 6> x{};
    auto keep = [](const std::array<int, 6>& v) {
      int degree = 0, variables = 0;
      for (int k = 0; k < 6; ++k) degree += v[k], variables += v[k] > 0;
      if (degree < 2) return false;
      if (variables == 1) return true;
      return degree <= (variables == 2 ? kTileLawCouplingDegree : kTileLawMixedDegree);
    };
    std::function<void(int, int)> walk = [&](int k, int left) {
      if (k == 6) {
        if (keep(x)) e.push_back(x);
        return;
      }
      for (int d = 0; d <= left; ++d) {
        x[k] = d;
        walk(k + 1, left - d);
      }
      x[k] = 0;
    };
    walk(0, kTileLawDegree);
    if (static_cast<int>(e.size()) != kTileLawBasisSize) throw std::logic_error("tile law: basis size");
    return e;
  }();
  return exponents;
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
  const std::vector<std::array<int, 6>>& exponents = basis_exponents();
  for (int i = 0; i < kTileLawBasisSize; ++i) {
    const std::array<int, 6>& e = exponents[i];
    std::array<double, 6> power{};  // t_k^{e_k}
    for (int k = 0; k < 6; ++k) power[k] = std::pow(t[k], e[k]);
    phi[i] = 1.0;
    for (int k = 0; k < 6; ++k) phi[i] *= power[k];
    for (int k = 0; k < 6; ++k) {
      double d = e[k] == 0 ? 0.0 : e[k] * std::pow(t[k], e[k] - 1);
      for (int l = 0; l < 6; ++l)
        if (l != k) d *= power[l];
      dphi[6 * i + k] = d;
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
  std::string name;
  for (int k = 0; k < 6; ++k) {
    const int e = basis_exponents()[i][k];
    if (e == 0) continue;
    // Appends (GCC 12's -Wrestrict false positive on operator+ under -Werror).
    if (!name.empty()) name += '*';
    name += kMacroStrainNames[k];
    if (e > 1) name += '^' + std::to_string(e);
  }
  return name;
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
  options.initial_trust_region_radius = 1e16;  // linear in c: the first step is the least-squares solution
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
