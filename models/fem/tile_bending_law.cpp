#include "models/fem/tile_bending_law.h"

#include <algorithm>

#include "models/fem/fem_material.h"

namespace wl {
namespace {

bool is_curvature(const std::array<int, 6>& e) { return e[3] > 0 || e[4] > 0 || e[5] > 0; }

}  // namespace

TileBendingLaw::TileBendingLaw(const TileLawFile& law)
    : box_(tile_law_box<6>(law.energy_scale, law.scale, law.lo, law.hi)) {
  for (const TileLawMonomial& t : law.terms) {
    if (!is_curvature(t.exponent)) continue;
    Monomial m;
    m.exponent = t.exponent;
    for (int k = 0; k < 6; ++k)
      if (t.exponent[k] > 0) m.active[m.num_active++] = k;
    exponent_.push_back(m);
    coefficient_.push_back(t.coefficient);
    // h_k = ∂²P/∂t_k²(0) = 2c[t_k²] along each curvature; the file's reader asks for κ_u², κ_v² > 0.
    if (m.num_active != 1 || t.exponent[m.active[0]] != 2) continue;
    rest_curvature_[m.active[0]] = 2.0 * t.coefficient;
    if (t.coefficient < 0)
      throw FemParameterError(law.source + ":" + std::to_string(t.line) + ": the bending stiffness at rest along " +
                              kTileLawStrainNames[m.active[0]] + " " +
                              std::to_string(rest_curvature_[m.active[0]] * box_.energy_scale /
                                             (box_.scale[m.active[0]] * box_.scale[m.active[0]])) +
                              " N·m, expected ≥ 0 (the law's continuation beyond the sampled box, "
                              "docs/models.md §6.9)");
  }
}

void TileBendingLaw::polynomial(const double* c, const std::array<double, 6>& t, double* p, double* g, double* h,
                                double* third) const {
  double powers[6][kTileLawMaxPower + 1];
  for (int k = 0; k < 6; ++k) {
    powers[k][0] = 1.0;
    for (int n = 1; n <= kTileLawMaxPower; ++n) powers[k][n] = powers[k][n - 1] * t[k];
  }
  *p = 0.0;
  std::fill(g, g + 6, 0.0);
  if (h) std::fill(h, h + 36, 0.0);
  if (third) std::fill(third, third + 216, 0.0);
  for (size_t i = 0; i < exponent_.size(); ++i) {
    if (c[i] == 0.0) continue;
    const Monomial& mo = exponent_[i];
    const int n = mo.num_active;
    // d[j][r] = ∂^r t_k^{e_k} for the j-th active strain k; ∂^α t^e = c Π_j d[j][α_j].
    double d[6][4];
    for (int j = 0; j < n; ++j)
      for (int r = 0; r < 4; ++r) d[j][r] = power_derivative(powers[mo.active[j]], mo.exponent[mo.active[j]], r);
    int alpha[6] = {};
    auto derivative = [&] {
      double x = c[i];
      for (int j = 0; j < n; ++j) x *= d[j][alpha[j]];
      return x;
    };
    *p += derivative();
    for (int a = 0; a < n; ++a) {
      const int ka = mo.active[a];
      ++alpha[a];
      g[ka] += derivative();
      for (int b = 0; h && b < n; ++b) {
        const int kb = mo.active[b];
        ++alpha[b];
        h[6 * ka + kb] += derivative();
        for (int e = 0; third && e < n; ++e) {
          ++alpha[e];
          third[36 * ka + 6 * kb + mo.active[e]] += derivative();
          --alpha[e];
        }
        --alpha[b];
      }
      --alpha[a];
    }
  }
}

void TileBendingLaw::extend(const double* c, const std::array<double, 6>& rest, const std::array<double, 6>& theta,
                            double* w, std::array<double, 6>* g, std::array<double, 36>* h) const {
  auto p = [&](const std::array<double, 6>& t, double* v, double* gt, double* ht, double* third) {
    polynomial(c, t, v, gt, ht, third);
  };
  continue_tile_law<6>(box_, p, rest, theta, w, g, h);
}

void TileBendingLaw::evaluate(const std::array<double, 6>& theta, double* w, std::array<double, 6>* g,
                              std::array<double, 36>* h) const {
  extend(coefficient_.data(), rest_curvature_, theta, w, g, h);
}

void TileBendingLaw::evaluate_unit(int i, const std::array<double, 6>& theta, double* w,
                                   std::array<double, 6>* g) const {
  std::vector<double> unit(coefficient_.size(), 0.0);
  unit[i] = 1.0;
  std::array<double, 6> rest{};  // h_k = 2c[t_k²]: 2 for the unit law of a curvature squared
  const Monomial& m = exponent_[i];
  if (m.num_active == 1 && m.exponent[m.active[0]] == 2) rest[m.active[0]] = 2.0;
  extend(unit.data(), rest, theta, w, g, nullptr);
}

TileBendingLaw TileBendingLaw::restricted(const std::array<bool, 6>& strains) const {
  TileBendingLaw part = *this;
  for (size_t i = 0; i < exponent_.size(); ++i)
    for (int j = 0; j < exponent_[i].num_active; ++j)
      if (!strains[exponent_[i].active[j]]) part.coefficient_[i] = 0.0;
  for (int k = 0; k < 6; ++k)
    if (!strains[k]) part.rest_curvature_[k] = 0.0;  // h_k = 2c[t_k²], with t_k² dropped
  return part;
}

std::string TileBendingLaw::name(int i) const {
  std::string n;
  for (int k = 0; k < 6; ++k) {
    const int e = exponent_[i].exponent[k];
    if (e == 0) continue;
    if (!n.empty()) n += '*';
    n += kTileLawStrainNames[k];
    if (e > 1) n += '^' + std::to_string(e);
  }
  return n;
}

}  // namespace wl
