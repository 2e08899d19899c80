#include "calibration/tile_sampling.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <numbers>
#include <numeric>
#include <random>
#include <sstream>
#include <stdexcept>

#include "calibration/equilibrium.h"

namespace wl {
namespace {

double stiffest_ks(const Scene& scene) {
  double ks = 0.0;
  for (const auto& [name, y] : scene.yarn_types) ks = std::max(ks, y.stretch_modulus_Pa);
  return ks * std::numbers::pi * scene.radius_m * scene.radius_m;
}

std::string pattern_text(const Pattern& p) {
  std::ostringstream s;
  switch (p.kind) {
    case Pattern::Kind::plain: s << "plain"; break;
    case Pattern::Kind::twill: s << "twill " << p.twill_over << "/" << p.twill_under << "/" << p.twill_shift; break;
    case Pattern::Kind::satin: s << "satin " << p.satin_harness << "/" << p.satin_step; break;
  }
  return s.str();
}

}  // namespace

TileSample relax_tile(const Scene& scene, const MacroStrain& theta, const Mat3& rotation) {
  WovenTileModel tile(scene, theta, rotation);
  Vec q = tile.initial_q();
  EquilibriumSolver solver(tile, {});
  EquilibriumOptions options;
  options.atol = kTileTolerance * stiffest_ks(scene);
  // Where Newton stalls (compressed yarns in a bent tile buckle: indefinite
  // stiffness), energy descent from the same start to the same tolerance.
  options.descent_tolerance = options.atol;
  const EquilibriumResult r = solver.solve(q, options);
  TileSample s;
  s.strain = theta;
  s.converged = r.converged;
  s.iterations = r.iterations;
  s.residual_N = r.residual;
  s.message = r.message;
  const double area = tile.rest_area();
  s.energy_density = tile.potential_energy(q) / area;
  const Eigen::Matrix<double, 1, 6> dE = tile.strain_partial(q);
  for (int k = 0; k < 6; ++k) s.stress[k] = dE[k] / area;
  return s;
}

TileRanges default_tile_ranges(const Scene& scene) {
  const double lock = std::numbers::pi / 2 - 2.0 * std::asin(std::min(1.0, scene.radius_m / scene.spacing_m));
  const double kappa = 1.0 / ((std::max(scene.warps, scene.wefts) - 1) * scene.spacing_m);
  TileRanges r;
  r.lo = {-0.005, -0.005, -lock, -kappa, -kappa, -kappa};
  r.hi = {0.02, 0.02, lock, kappa, kappa, kappa};
  return r;
}

void apply_tile_range(TileRanges& ranges, const std::string& item, const std::string& option) {
  auto bad = [&](const std::string& why) { return std::invalid_argument(option + " " + item + ": " + why); };
  const size_t eq = item.find('='), comma = item.find(',', eq == std::string::npos ? 0 : eq);
  if (eq == std::string::npos || comma == std::string::npos) throw bad("expected NAME=LO,HI");
  const std::string name = item.substr(0, eq);
  const auto it = std::find(kMacroStrainNames.begin(), kMacroStrainNames.end(), name);
  if (it == kMacroStrainNames.end())
    throw bad("unknown strain '" + name +
              "' (expected stretch_warp, stretch_weft, shear, curvature_warp, curvature_weft or twist)");
  double lo = 0.0, hi = 0.0;
  try {
    size_t used_lo = 0, used_hi = 0;
    const std::string a = item.substr(eq + 1, comma - eq - 1), b = item.substr(comma + 1);
    lo = std::stod(a, &used_lo);
    hi = std::stod(b, &used_hi);
    if (used_lo != a.size() || used_hi != b.size()) throw std::invalid_argument("trailing text");
  } catch (const std::exception&) {
    throw bad("LO and HI must be numbers");
  }
  if (!std::isfinite(lo) || !std::isfinite(hi) || !(lo < hi)) throw bad("expected finite LO < HI");
  const size_t k = static_cast<size_t>(it - kMacroStrainNames.begin());
  ranges.lo[k] = lo;
  ranges.hi[k] = hi;
}

std::vector<MacroStrain> latin_hypercube(const TileRanges& ranges, int count, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::vector<MacroStrain> points(count);
  std::vector<int> strata(count);
  for (int k = 0; k < 6; ++k) {
    std::iota(strata.begin(), strata.end(), 0);
    std::shuffle(strata.begin(), strata.end(), rng);
    for (int p = 0; p < count; ++p) {
      const double inside = std::generate_canonical<double, 53>(rng);
      points[p][k] = ranges.lo[k] + (ranges.hi[k] - ranges.lo[k]) * (strata[p] + inside) / count;
    }
  }
  return points;
}

std::string tile_fabric_key(const Scene& scene, const TileRanges& ranges, int count, std::uint64_t seed) {
  std::ostringstream s;
  s << std::setprecision(17) << "woven-tile-1 pattern=" << pattern_text(scene.pattern) << " L=" << scene.spacing_m
    << " R=" << scene.radius_m;
  auto yarns = [&](const char* name, const std::vector<std::string>& cycle) {
    s << " " << name << "=";
    for (const std::string& t : cycle)
      s << "[" << scene.yarn_types.at(t).stretch_modulus_Pa << "," << scene.yarn_types.at(t).bending_modulus_Pa << "]";
  };
  yarns("warps", scene.warp_yarn_types);
  yarns("wefts", scene.weft_yarn_types);
  const ContactParams& c = scene.contact;
  s << " shear=" << (c.shear_model == ContactParams::ShearModel::gong ? "gong" : "cirio") << "," << c.shear_modulus_Pa
    << "," << c.lock_exponent << "," << c.lock_sigma << " terms=" << scene.terms.stretch << scene.terms.bending
    << scene.terms.shear << " ranges=";
  for (int k = 0; k < 6; ++k) s << "[" << ranges.lo[k] << "," << ranges.hi[k] << "]";
  s << " samples=" << count << " seed=" << seed;
  return s.str();
}

void write_tile_samples(const std::filesystem::path& file, const std::string& key,
                        const std::vector<TileSample>& samples) {
  const std::filesystem::path partial = file.string() + ".partial";
  {
    std::ofstream out(partial);
    out << "# " << key << "\n";
    for (const char* n : kMacroStrainNames) out << n << ",";
    out << "W_J_per_m2";
    for (const char* n : kMacroStrainNames) out << ",dW_d" << n;
    out << ",converged,iterations,residual_N\n" << std::setprecision(17);
    for (const TileSample& s : samples) {
      for (double v : s.strain) out << v << ",";
      out << s.energy_density;
      for (double v : s.stress) out << "," << v;
      out << "," << s.converged << "," << s.iterations << "," << s.residual_N << "\n";
    }
    if (!out) throw std::runtime_error("could not write " + partial.string());
  }
  std::filesystem::rename(partial, file);  // nothing half-written under the cache's name
}

std::optional<std::vector<TileSample>> read_tile_samples(const std::filesystem::path& file, const std::string& key) {
  std::ifstream in(file);
  std::string line;
  if (!in || !std::getline(in, line) || line != "# " + key || !std::getline(in, line)) return std::nullopt;
  std::vector<TileSample> samples;
  while (std::getline(in, line)) {
    std::istringstream row(line);
    std::vector<double> v;
    std::string cell;
    while (std::getline(row, cell, ',')) v.push_back(std::stod(cell));
    if (v.size() != 16) return std::nullopt;
    TileSample s;
    std::copy(v.begin(), v.begin() + 6, s.strain.begin());
    s.energy_density = v[6];
    std::copy(v.begin() + 7, v.begin() + 13, s.stress.begin());
    s.converged = v[13] != 0.0;
    s.iterations = static_cast<int>(v[14]);
    s.residual_N = v[15];
    samples.push_back(s);
  }
  return samples;
}

}  // namespace wl
