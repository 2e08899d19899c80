// `weavelab tiles SCENE` (docs/calibration.md §9): the homogenized energy
// density of the scene's woven fabric sampled from its periodic tile over a
// Latin hypercube of the six macroscopic strains, cached per fabric and design
// in the output folder, and a continuum law fitted to the samples with every
// `holdout_every`-th sample held out and measured.
#pragma once
#include <cstdint>
#include <filesystem>
#include <string>

#include "calibration/tile_law.h"
#include "calibration/tile_sampling.h"
#include "models/scene/scene.h"

namespace wl {

struct TilesConfig {
  int samples = 1024;
  std::uint64_t seed = 1;
  TileRanges ranges;      // default_tile_ranges(scene) unless set
  int holdout_every = 5;  // ≥ 2; the samples p with p % holdout_every == holdout_every − 1
  bool fit = true;
  std::filesystem::path out_dir;
};

struct TilesResult {
  int samples = 0, converged = 0;
  bool cached = false;  // the samples were read from the cache
  double sampling_wall_s = 0.0, sampling_cpu_s = 0.0;
  std::filesystem::path samples_file;
  TileLawFit fit;
  TileLawErrors fitted, held_out;
};

// The law as the continuum reads it ([fem] tile_law, models/fem/tile_law_file.h): W₀, the
// scales, the sampled box and the coefficients by monomial, "name,value" rows (tile_law.csv).
std::string tile_law_csv(const TileLaw& law, const TileRanges& ranges);
// The cache file of a sample set: tile_samples_<text_hash(key)>.csv.
std::string tile_cache_name(const std::string& key);
// Checks the options (std::invalid_argument naming the option: exit 2), then
// samples (or reads the cache), fits and writes tile_samples_*.csv, tile_law.csv
// and tiles.json into out_dir. A SIGINT or SIGTERM ends the sampling before its next
// sample (no cache written) or the fit: tiles.json with outcome interrupted
// (driver/interrupted_record.h), then Interrupted.
TilesResult run_tiles(const Scene& scene, const TilesConfig& config);

}  // namespace wl
