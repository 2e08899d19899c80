#include "models/fem/tile_law_file.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <optional>
#include <set>
#include <sstream>

#include "models/fem/fem_material.h"

namespace wl {
namespace {

[[noreturn]] void fail(const std::string& source, int line, const std::string& what, const std::string& expected) {
  throw FemParameterError(source + ":" + std::to_string(line) + ": " + what + ", expected " + expected);
}

int strain_index(const std::string& name) {
  for (int k = 0; k < 6; ++k)
    if (name == kTileLawStrainNames[k]) return k;
  return -1;
}

// "stretch_warp^2*shear" → exponents; nullopt when a factor is not NAME or NAME^P (P ≥ 1) or repeats.
std::optional<std::array<int, 6>> parse_monomial(const std::string& name) {
  std::array<int, 6> e{};
  std::stringstream s(name);
  std::string factor;
  while (std::getline(s, factor, '*')) {
    const size_t caret = factor.find('^');
    const int k = strain_index(factor.substr(0, caret));
    if (k < 0 || e[k] != 0) return std::nullopt;
    e[k] = 1;
    if (caret == std::string::npos) continue;
    const std::string power = factor.substr(caret + 1);
    if (power.empty() || power.size() > 2 || !std::all_of(power.begin(), power.end(), ::isdigit)) return std::nullopt;
    e[k] = std::stoi(power);
    if (e[k] < 1) return std::nullopt;
  }
  if (name.empty() || name.back() == '*') return std::nullopt;
  return e;
}

std::optional<double> parse_number(const std::string& text) {
  try {
    size_t used = 0;
    const double x = std::stod(text, &used);
    if (used != text.size() || !std::isfinite(x)) return std::nullopt;
    return x;
  } catch (const std::exception&) {
    return std::nullopt;
  }
}

constexpr const char* kMonomialExpected =
    "a strain of the law (stretch_warp, stretch_weft, shear, curvature_warp, curvature_weft, twist), "
    "'energy_scale_J_per_m2', 'scale:', 'lo:' or 'hi:' and a strain, or a product of strains NAME^P "
    "joined by '*' of total degree 2 … 12, each strain once";

// One "name,value" row into `law`; `seen` holds the names so far.
void read_row(const std::string& name, double value, int line, TileLawFile& law, std::set<std::string>& seen) {
  const std::string& src = law.source;
  if (!seen.insert(name).second) fail(src, line, "row '" + name + "' again", "each name once");
  const size_t colon = name.find(':');
  if (name == "energy_scale_J_per_m2") {
    if (!(value > 0)) fail(src, line, "energy_scale_J_per_m2 " + std::to_string(value), "a number > 0 (J/m²)");
    law.energy_scale = value;
    return;
  }
  if (colon != std::string::npos) {
    const std::string kind = name.substr(0, colon);
    const int k = strain_index(name.substr(colon + 1));
    if (k < 0 || (kind != "scale" && kind != "lo" && kind != "hi"))
      fail(src, line, "row '" + name + "'", kMonomialExpected);
    if (kind == "scale" && !(value > 0)) fail(src, line, name + " " + std::to_string(value), "a number > 0");
    // The rest state lies in the sampled box, which is not flat: lo ≤ 0 ≤ hi, lo < hi.
    if (kind == "lo" && !(value <= 0)) fail(src, line, name + " " + std::to_string(value), "a number ≤ 0");
    if (kind == "hi" && !(value >= 0 && value > law.lo[k]))
      fail(src, line, name + " " + std::to_string(value),
           "a number ≥ 0 above lo:" + std::string(kTileLawStrainNames[k]));
    (kind == "scale" ? law.scale : kind == "lo" ? law.lo : law.hi)[k] = value;
    return;
  }
  const std::optional<std::array<int, 6>> e = parse_monomial(name);
  int degree = 0;
  if (e)
    for (int x : *e) degree += x;
  if (!e || degree < 2 || degree > 12) fail(src, line, "row '" + name + "'", kMonomialExpected);
  law.terms.push_back({*e, value, line});
}

}  // namespace

double TileLawFile::warp_bending_N_m() const {
  for (const TileLawMonomial& t : terms)
    if (t.exponent == std::array<int, 6>{0, 0, 0, 2, 0, 0})
      return 2.0 * energy_scale * t.coefficient / (scale[3] * scale[3]);
  return 0.0;
}

double TileLawFile::weft_bending_N_m() const {
  for (const TileLawMonomial& t : terms)
    if (t.exponent == std::array<int, 6>{0, 0, 0, 0, 2, 0})
      return 2.0 * energy_scale * t.coefficient / (scale[4] * scale[4]);
  return 0.0;
}

TileLawFile parse_tile_law(const std::string& text, const std::string& source) {
  TileLawFile law;
  law.source = source;
  std::istringstream in(text);
  std::string row;
  int line = 0;
  std::set<std::string> seen;
  while (std::getline(in, row)) {
    ++line;
    if (!row.empty() && row.back() == '\r') row.pop_back();
    if (line == 1) {
      if (row != "name,value") fail(source, 1, "header '" + row + "'", "'name,value' (a tile law of `weavelab tiles`)");
      continue;
    }
    if (row.empty()) continue;
    const size_t comma = row.find(',');
    if (comma == std::string::npos || row.find(',', comma + 1) != std::string::npos)
      fail(source, line, "row '" + row + "'", "two fields NAME,VALUE");
    const std::optional<double> value = parse_number(row.substr(comma + 1));
    if (!value) fail(source, line, "value '" + row.substr(comma + 1) + "'", "a finite number");
    read_row(row.substr(0, comma), *value, line, law, seen);
  }
  if (line == 0) fail(source, 0, "an empty file", "a tile law of `weavelab tiles` (header 'name,value')");
  std::vector<std::string> missing;
  if (!seen.count("energy_scale_J_per_m2")) missing.push_back("energy_scale_J_per_m2");
  for (const char* kind : {"scale:", "lo:", "hi:"})
    for (const char* n : kTileLawStrainNames)
      if (!seen.count(std::string(kind) + n)) missing.push_back(std::string(kind) + n);
  if (!missing.empty()) {
    std::string list;
    for (const std::string& m : missing) list += (list.empty() ? "" : ", ") + m;
    fail(source, line, "no row " + list, "every row of the law's header (energy_scale_J_per_m2, scale:, lo:, hi:)");
  }
  if (law.terms.empty()) fail(source, line, "no monomial row", "the law's coefficients");
  for (auto [value, name] :
       {std::pair{law.warp_bending_N_m(), "curvature_warp^2"}, std::pair{law.weft_bending_N_m(), "curvature_weft^2"}})
    if (!(value > 0))
      fail(
          source, line, "bending at rest " + std::to_string(value) + " N·m",
          "a row " + std::string(name) + " with a positive coefficient (the continuum's bending, docs/models.md §6.9)");
  return law;
}

double yarn_matched_areal_density(const Scene& s) {
  double mass = 0.0;
  for (int j = 0; j < s.warps; ++j) mass += s.warp_type(j).density_kg_per_m * (s.wefts - 1) * s.spacing_m;
  for (int i = 0; i < s.wefts; ++i) mass += s.weft_type(i).density_kg_per_m * (s.warps - 1) * s.spacing_m;
  return mass / ((s.wefts - 1) * (s.warps - 1) * s.spacing_m * s.spacing_m);
}

bool is_tile_law_file(const std::string& path) {
  if (path.empty()) return false;
  std::ifstream in(path, std::ios::binary);
  std::string first;
  if (!in || !std::getline(in, first)) return false;
  if (!first.empty() && first.back() == '\r') first.pop_back();
  return first == "name,value";
}

std::string tile_law_path(const FemSettings& fem) {
  if (!fem.tile_law.empty()) return fem.tile_law;
  return is_tile_law_file(fem.parameter_file) ? fem.parameter_file : std::string();
}

TileLawFile read_tile_law_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) fail(path, 0, "the file cannot be read", "a tile law written by `weavelab tiles` (tile_law.csv)");
  std::ostringstream s;
  s << in.rdbuf();
  return parse_tile_law(s.str(), path);
}

TileMembraneLaw::TileMembraneLaw(const TileLawFile& law)
    : box_(tile_law_box<3>(law.energy_scale, law.scale, law.lo, law.hi)) {
  for (const TileLawMonomial& t : law.terms) {
    if (t.exponent[3] || t.exponent[4] || t.exponent[5]) continue;  // a curvature: not in the membrane
    exponent_.push_back({t.exponent[0], t.exponent[1], t.exponent[2]});
    coefficient_.push_back(t.coefficient);
  }
  // h_k = ∂²P/∂t_k²(0) = 2 c[t_k²].
  for (int k = 0; k < 3; ++k) {
    for (size_t i = 0; i < exponent_.size(); ++i)
      if (exponent_[i][k] == 2 && exponent_[i][(k + 1) % 3] == 0 && exponent_[i][(k + 2) % 3] == 0)
        rest_curvature_[k] = 2.0 * coefficient_[i];
    if (!(rest_curvature_[k] > 0))
      fail(law.source, 0,
           std::string("the membrane law's stiffness at rest along ") + kTileLawStrainNames[k] + " " +
               std::to_string(rest_curvature_[k] * box_.energy_scale / (box_.scale[k] * box_.scale[k])),
           "> 0 (a row " + std::string(kTileLawStrainNames[k]) + "^2 with a positive coefficient)");
  }
}

void TileMembraneLaw::polynomial(const double* c, const std::array<double, 3>& t, double* p, double* g, double* h,
                                 double* third) const {
  double powers[3][kTileLawMaxPower + 1];
  for (int k = 0; k < 3; ++k) {
    powers[k][0] = 1.0;
    for (int n = 1; n <= kTileLawMaxPower; ++n) powers[k][n] = powers[k][n - 1] * t[k];
  }
  *p = 0.0;
  std::fill(g, g + 3, 0.0);
  if (h) std::fill(h, h + 9, 0.0);
  if (third) std::fill(third, third + 27, 0.0);
  for (size_t i = 0; i < exponent_.size(); ++i) {
    if (c[i] == 0.0) continue;
    const std::array<int, 3>& e = exponent_[i];
    // ∂^α t^e = Π_k power_derivative(t_k, e_k, α_k), α the count of each variable among the derivative's indices.
    auto derivative = [&](const std::array<int, 3>& alpha) {
      return power_derivative(powers[0], e[0], alpha[0]) * power_derivative(powers[1], e[1], alpha[1]) *
             power_derivative(powers[2], e[2], alpha[2]);
    };
    *p += c[i] * derivative({0, 0, 0});
    for (int j = 0; j < 3; ++j) {
      std::array<int, 3> a{};
      ++a[j];
      g[j] += c[i] * derivative(a);
      if (!h) continue;
      for (int l = 0; l < 3; ++l) {
        std::array<int, 3> b = a;
        ++b[l];
        h[3 * j + l] += c[i] * derivative(b);
        if (!third) continue;
        for (int m = 0; m < 3; ++m) {
          std::array<int, 3> d = b;
          ++d[m];
          third[9 * j + 3 * l + m] += c[i] * derivative(d);
        }
      }
    }
  }
}

void TileMembraneLaw::extend(const double* c, const std::array<double, 3>& curvature, const std::array<double, 3>& m,
                             double* w, std::array<double, 3>* g, std::array<double, 9>* h) const {
  auto p = [&](const std::array<double, 3>& t, double* v, double* gt, double* ht, double* third) {
    polynomial(c, t, v, gt, ht, third);
  };
  continue_tile_law<3>(box_, p, curvature, m, w, g, h);
}

void TileMembraneLaw::evaluate(const std::array<double, 3>& m, double* w, std::array<double, 3>* g,
                               std::array<double, 9>* h) const {
  extend(coefficient_.data(), rest_curvature_, m, w, g, h);
}

void TileMembraneLaw::evaluate_unit(int i, const std::array<double, 3>& m, double* w, std::array<double, 3>* g) const {
  std::vector<double> unit(coefficient_.size(), 0.0);
  unit[i] = 1.0;
  // The extension's h_k = 2c[t_k²] is linear in c too: 2 for the unit law of t_k², else 0.
  std::array<double, 3> curvature{};
  for (int k = 0; k < 3; ++k)
    if (exponent_[i][k] == 2 && exponent_[i][(k + 1) % 3] == 0 && exponent_[i][(k + 2) % 3] == 0) curvature[k] = 2.0;
  extend(unit.data(), curvature, m, w, g, nullptr);
}

TileMembraneLaw TileMembraneLaw::restricted(const std::array<bool, 6>& strains) const {
  TileMembraneLaw part = *this;
  for (size_t i = 0; i < exponent_.size(); ++i)
    for (int k = 0; k < 3; ++k)
      if (exponent_[i][k] > 0 && !strains[k]) part.coefficient_[i] = 0.0;
  for (int k = 0; k < 3; ++k)
    if (!strains[k]) part.rest_curvature_[k] = 0.0;  // h_k = 2c[t_k²], with t_k² dropped
  return part;
}

std::string TileMembraneLaw::name(int i) const {
  std::string n;
  for (int k = 0; k < 3; ++k) {
    if (exponent_[i][k] == 0) continue;
    if (!n.empty()) n += '*';
    n += kTileLawStrainNames[k];
    if (exponent_[i][k] > 1) n += '^' + std::to_string(exponent_[i][k]);
  }
  return n;
}

}  // namespace wl
