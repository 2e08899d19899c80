// The homogenized energy density of a woven fabric sampled from its periodic
// tile (docs/calibration.md §9): each sample relaxes the tile's crossings at a
// prescribed macroscopic strain θ (woven_tile.h) and reads
//   W(θ) = E*(θ)/A  (energy per rest area, A = nu·nv·L²),
//   ∂W/∂θ = (1/A) ∂E/∂θ at the relaxed q (the implicit-function theorem: the
//           internal DoFs are at equilibrium, ∂E/∂q = 0),
// over a Latin hypercube of the six strains, cached per fabric in a CSV.
#pragma once
#include <array>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "calibration/woven_tile.h"

namespace wl {

// Converged when ‖f_f‖∞ ≤ kTileTolerance·k_s of the stiffest yarn.
inline constexpr double kTileTolerance = 1e-12;

struct TileSample {
  MacroStrain strain{};
  double energy_density = 0.0;  // W [J/m²]
  // ∂W/∂θ_k: N/m per unit strain or per radian of shear, N for the curvatures.
  std::array<double, 6> stress{};
  bool converged = false;
  int iterations = 0;
  double residual_N = 0.0;
  std::string message;  // why it did not converge
};

// The tile relaxed at θ from the affine state, turned by `rotation`.
TileSample relax_tile(const Scene& scene, const MacroStrain& theta, const Mat3& rotation = Mat3::Identity());

struct TileRanges {
  std::array<double, 6> lo{}, hi{};
};
// Stretch −0.5 % … 2 % (the stretch ladder's top, docs/calibration.md §2), shear
// to the lock angle ±(π/2 − 2 arcsin(R/L)), curvatures and twist ±1/((N − 1)L):
// one radian of turning over the scene's cloth (the bending ladder's top).
TileRanges default_tile_ranges(const Scene& scene);
// Applies "NAME=LO,HI" (NAME of kMacroStrainNames, LO < HI, finite); the
// std::invalid_argument names `option`, the item and what was expected.
void apply_tile_range(TileRanges& ranges, const std::string& item, const std::string& option);

// A Latin hypercube of `count` points: on every axis one point in each of
// `count` equal strata (at a uniform place inside it), the strata of the axes
// paired by independent random permutations (std::mt19937_64 seeded by `seed`).
std::vector<MacroStrain> latin_hypercube(const TileRanges& ranges, int count, std::uint64_t seed);

// The fabric and design a sample set belongs to, as one line of text (pattern,
// L, R, every yarn type's Y and B in warp and weft order, the shear law and its
// parameters, the terms, the ranges, count and seed): the first line of its cache file.
std::string tile_fabric_key(const Scene& scene, const TileRanges& ranges, int count, std::uint64_t seed);

void write_tile_samples(const std::filesystem::path& file, const std::string& key,
                        const std::vector<TileSample>& samples);
// The samples of `file` when it exists and its first line names `key`; nullopt otherwise.
std::optional<std::vector<TileSample>> read_tile_samples(const std::filesystem::path& file, const std::string& key);

}  // namespace wl
