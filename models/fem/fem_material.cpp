#include "models/fem/fem_material.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>
#include <utility>
#include <vector>

#include "models/scene/toml_include.h"

#include "models/fem/knit_contact_mesh.h"
#include "models/fem/tile_law_file.h"

namespace wl {
namespace {

template <double FemMaterial::*F>
double& field(FemMaterial& m) {
  return m.*F;
}
template <int I>
double& knot(FemMaterial& m) {
  return m.shear_knot_N_per_m[I];
}
template <int... I>
void add_knots(std::vector<FemParameterKey>& keys, std::integer_sequence<int, I...>) {
  (keys.push_back(
       {shear_knot_key(I), "a number > 0 (N/m), with as many knots in the scene's [fem] shear_knots_rad", &knot<I>}),
   ...);
}

[[noreturn]] void fail(const std::string& file, int line, const std::string& key, const std::string& value,
                       const std::string& expected) {
  throw FemParameterError(file + ":" + std::to_string(line) + ": key '" + key + "': got " + value + ", expected " +
                          expected);
}

// The stiffnesses a knit's continuum must be given (docs/models.md §11.9).
struct CalibratedKey {
  const char* name;
  double FemMaterial::*field;
};
constexpr CalibratedKey kKnitCalibratedKeys[] = {{"warp_stretch_N_per_m", &FemMaterial::warp_stretch_N_per_m},
                                                 {"weft_stretch_N_per_m", &FemMaterial::weft_stretch_N_per_m},
                                                 {"shear_N_per_m", &FemMaterial::shear_N_per_m},
                                                 {"warp_bending_N_m", &FemMaterial::warp_bending_N_m},
                                                 {"weft_bending_N_m", &FemMaterial::weft_bending_N_m}};

}  // namespace

const std::vector<FemParameterKey>& fem_parameter_keys() {
  static const std::vector<FemParameterKey> keys = [] {
    std::vector<FemParameterKey> k{
        {"areal_density_kg_per_m2", "a number > 0 (kg/m²)", &field<&FemMaterial::areal_density_kg_per_m2>},
        {"warp_stretch_N_per_m", "a number > 0 (N/m)", &field<&FemMaterial::warp_stretch_N_per_m>},
        {"weft_stretch_N_per_m", "a number > 0 (N/m)", &field<&FemMaterial::weft_stretch_N_per_m>},
        {"shear_N_per_m", "a number > 0 (N/m)", &field<&FemMaterial::shear_N_per_m>},
        {"shear_lock_angle_rad", "a number > 0 (rad)", &field<&FemMaterial::shear_lock_angle_rad>},
        {"shear_lock_exponent", "a number > 0", &field<&FemMaterial::shear_lock_exponent>},
        {"warp_bending_N_m", "a number > 0 (N·m)", &field<&FemMaterial::warp_bending_N_m>},
        {"weft_bending_N_m", "a number > 0 (N·m)", &field<&FemMaterial::weft_bending_N_m>},
        {"diagonal_bending_N_m", "a number > 0 (N·m)", &field<&FemMaterial::diagonal_bending_N_m>},
        {"stretch_coupling_N_per_m", "a number > 0 (N/m) below √(warp·weft stretch)",
         &field<&FemMaterial::stretch_coupling_N_per_m>},
        {"warp_stretch_quartic_N_per_m", "a number > 0 (N/m)", &field<&FemMaterial::warp_stretch_quartic_N_per_m>},
        {"weft_stretch_quartic_N_per_m", "a number > 0 (N/m)", &field<&FemMaterial::weft_stretch_quartic_N_per_m>},
        {"areal_stretch_quartic_N_per_m", "a number > 0 (N/m)", &field<&FemMaterial::areal_stretch_quartic_N_per_m>},
    };
    add_knots(k, std::make_integer_sequence<int, FemSettings::kMaxShearKnots>());
    return k;
  }();
  return keys;
}

FemMaterial default_fem_material(const Scene& s) {
  const double L = s.spacing_m, R = s.radius_m, area = std::numbers::pi * R * R;
  double warp_ks = 0, warp_kb = 0, warp_rho = 0, weft_ks = 0, weft_kb = 0, weft_rho = 0;
  for (int j = 0; j < s.warps; ++j) {
    const YarnType& y = s.warp_type(j);
    warp_ks += y.stretch_modulus_Pa * area / s.warps;
    warp_kb += y.bending_modulus_Pa * area / s.warps;
    warp_rho += y.density_kg_per_m / s.warps;
  }
  for (int i = 0; i < s.wefts; ++i) {
    const YarnType& y = s.weft_type(i);
    weft_ks += y.stretch_modulus_Pa * area / s.wefts;
    weft_kb += y.bending_modulus_Pa * area / s.wefts;
    weft_rho += y.density_kg_per_m / s.wefts;
  }
  FemMaterial m;
  m.warp_stretch_N_per_m = warp_ks / L;
  m.weft_stretch_N_per_m = weft_ks / L;
  m.warp_bending_N_m = warp_kb / L;
  m.weft_bending_N_m = weft_kb / L;
  m.areal_density_kg_per_m2 = (warp_rho + weft_rho) / L;
  m.shear_N_per_m = s.contact.shear_modulus_Pa * area / L;
  if (R / L < std::numbers::sqrt2 / 2) {
    m.shear_lock_angle_rad = std::numbers::pi / 2 - 2 * std::asin(R / L);
    m.shear_lock_exponent = s.contact.lock_exponent;
  }
  return m;
}

FemMaterial parse_fem_parameters(const std::string& text, const std::string& source, FemMaterial m) {
  toml::table root;
  try {
    root = toml::parse(text, source);
  } catch (const toml::parse_error& e) {
    fail(source, static_cast<int>(e.source().begin.line), "(syntax)", "'" + std::string(e.description()) + "'",
         "valid TOML");
  }
  for (auto&& [k, node] : root) {
    const std::string key(k.str());
    const int line = static_cast<int>(node.source().begin.line);
    if (key == "provenance") {
      if (!node.is_table()) fail(source, line, key, "a non-table", "a table of free-form notes");
      continue;
    }
    const FemParameterKey* spec = nullptr;
    int index = 0;
    for (const FemParameterKey& c : fem_parameter_keys()) {
      if (key == c.name) spec = &c;
      if (!spec) ++index;
    }
    if (!spec) {
      std::string known;
      for (const FemParameterKey& c : fem_parameter_keys()) known += (known.empty() ? "" : ", ") + c.name;
      fail(source, line, key, "an unknown key", "one of " + known + " or [provenance]");
    }
    const auto v = node.value<double>();
    std::ostringstream written;
    node.visit([&](auto&& n) { written << n; });
    if (!v || !std::isfinite(*v) || *v <= 0) fail(source, line, key, written.str(), spec->expected);
    if (key == "shear_lock_angle_rad" && *v >= std::numbers::pi / 2)
      fail(source, line, key, written.str(), "a shear angle in (0, π/2) rad");
    const int knot_index = index - (static_cast<int>(fem_parameter_keys().size()) - FemSettings::kMaxShearKnots);
    if (knot_index >= static_cast<int>(m.shear_knots_rad.size()))
      fail(source, line, key, written.str(),
           "no such key: the scene's shear law has " + std::to_string(m.shear_knots_rad.size()) +
               " knots (set [fem] shear_law = \"spline\" and shear_knots_rad in the scene)");
    spec->value(m) = *v;
    if (key == "stretch_coupling_N_per_m") m.stretch_coupling_source = source + ":" + std::to_string(line);
  }
  return m;
}

StretchLaw stretch_law(const FemMaterial& m) {
  return {m.warp_stretch_N_per_m,         m.weft_stretch_N_per_m,         m.stretch_coupling_N_per_m,
          m.warp_stretch_quartic_N_per_m, m.weft_stretch_quartic_N_per_m, m.areal_stretch_quartic_N_per_m};
}

bool stretch_law_admissible(const FemMaterial& m) {
  const double k = m.stretch_coupling_N_per_m;
  return k <= 0 || k * k < m.warp_stretch_N_per_m * m.weft_stretch_N_per_m;
}

FemMaterial read_fem_parameter_file(const std::string& path, FemMaterial base) {
  std::ifstream in(path, std::ios::binary);
  if (!in) fail(path, 0, "parameter_file", "'" + path + "'", "a readable FEM parameter file");
  std::ostringstream ss;
  ss << in.rdbuf();
  return parse_fem_parameters(ss.str(), path, base);
}

void write_fem_parameter_file(const std::string& path, const FemMaterial& m,
                              const std::vector<std::pair<std::string, std::string>>& provenance) {
  std::ostringstream out;
  out.precision(17);
  out << "# weavelab FEM parameters (models/fem/fem_material.h)\n";
  FemMaterial copy = m;
  for (const FemParameterKey& k : fem_parameter_keys())
    if (k.value(copy) > 0) out << k.name << " = " << k.value(copy) << "\n";
  if (!provenance.empty()) {
    out << "\n[provenance]\n";
    for (const auto& [key, text] : provenance) out << key << " = " << toml::value<std::string>(text) << "\n";
  }
  const std::string tmp = path + ".tmp";
  {
    std::ofstream f(tmp, std::ios::binary);
    if (!f) throw std::runtime_error("cannot write " + tmp);
    f << out.str();
    if (!f) throw std::runtime_error("cannot write " + tmp);
  }
  std::filesystem::rename(tmp, path);
}

FemMaterial fem_material(const Scene& s) {
  FemMaterial m = default_fem_material(s);
  const FemSettings& f = s.fem;
  if (s.knit)  // nothing derives a knit's membrane stiffnesses from its yarn (docs/models.md §11.9)
    for (const CalibratedKey& k : kKnitCalibratedKeys) m.*k.field = 0.0;
  m.shear_knots_rad = f.shear_knots_rad;  // the law first: the parameter file's knot values must fit it
  if (const std::string law_path = tile_law_path(f); !law_path.empty()) {
    // The tile law's bending at rest, the yarn level's mass (docs/models.md §6.9).
    const TileLawFile law = read_tile_law_file(law_path);
    m.warp_bending_N_m = law.warp_bending_N_m();
    m.weft_bending_N_m = law.weft_bending_N_m();
    if (!s.knit) m.areal_density_kg_per_m2 = yarn_matched_areal_density(s);
  }
  if (!f.parameter_file.empty() && !is_tile_law_file(f.parameter_file))
    m = read_fem_parameter_file(f.parameter_file, m);
  auto set = [](double& out, const std::optional<double>& v) {
    if (v) out = *v;
  };
  set(m.areal_density_kg_per_m2, f.areal_density_kg_per_m2);
  set(m.warp_stretch_N_per_m, f.warp_stretch_N_per_m);
  set(m.weft_stretch_N_per_m, f.weft_stretch_N_per_m);
  set(m.shear_N_per_m, f.shear_N_per_m);
  set(m.shear_lock_angle_rad, f.shear_lock_angle_rad);
  set(m.shear_lock_exponent, f.shear_lock_exponent);
  set(m.warp_bending_N_m, f.warp_bending_N_m);
  set(m.weft_bending_N_m, f.weft_bending_N_m);
  set(m.diagonal_bending_N_m, f.diagonal_bending_N_m);
  set(m.stretch_coupling_N_per_m, f.stretch_coupling_N_per_m);
  set(m.warp_stretch_quartic_N_per_m, f.warp_stretch_quartic_N_per_m);
  set(m.weft_stretch_quartic_N_per_m, f.weft_stretch_quartic_N_per_m);
  set(m.areal_stretch_quartic_N_per_m, f.areal_stretch_quartic_N_per_m);
  if (f.stretch_coupling_N_per_m) m.stretch_coupling_source = s.source + ":" + std::to_string(f.stretch_coupling_line);
  if (s.knit) {  // before the coupling bound, which needs these stiffnesses
    // The yarn level's mass per area, whatever patch a parameter file was calibrated on.
    if (!f.areal_density_kg_per_m2) m.areal_density_kg_per_m2 = knit_areal_density(s);
    for (const CalibratedKey& k : kKnitCalibratedKeys)
      if (!(m.*k.field > 0)) {
        auto line = s.key_lines.find("fem");  // else the [cloth] table that makes it a knit
        if (line == s.key_lines.end()) line = s.key_lines.find("cloth");
        throw SceneError(
            s.source, line != s.key_lines.end() ? line->second : 1, std::string("fem.") + k.name, "none",
            "a calibrated value > 0: a knit's continuum takes its stiffnesses from `weavelab calibrate` "
            "(--fem-params FILE or [fem] parameter_file) or from [fem]; nothing derives them from the yarn "
            "(docs/models.md §11.9)");
      }
  }
  if (!stretch_law_admissible(m)) {  // docs/models.md §6.3.1: ψ convex in the strains
    const std::string& at = m.stretch_coupling_source;
    const size_t colon = at.rfind(':');
    std::ostringstream v, bound;
    v.precision(17);
    v << m.stretch_coupling_N_per_m;
    bound << "a coupling below √(k_u·k_v) = " << std::sqrt(m.warp_stretch_N_per_m * m.weft_stretch_N_per_m)
          << " N/m (warp_stretch_N_per_m = " << m.warp_stretch_N_per_m
          << ", weft_stretch_N_per_m = " << m.weft_stretch_N_per_m << "), for a stretch law convex in the strains";
    fail(colon == std::string::npos ? "[fem]" : at.substr(0, colon),
         colon == std::string::npos ? 0 : std::stoi(at.substr(colon + 1)), "stretch_coupling_N_per_m", v.str(),
         bound.str());
  }
  for (int i = 0; i < FemSettings::kMaxShearKnots; ++i) set(m.shear_knot_N_per_m[i], f.shear_knot_N_per_m[i]);
  for (size_t i = 0; i < m.shear_knots_rad.size(); ++i)  // an absent knot value: the stiffness at 0
    if (m.shear_knot_N_per_m[i] <= 0) m.shear_knot_N_per_m[i] = m.shear_N_per_m;
  return m;
}

}  // namespace wl
