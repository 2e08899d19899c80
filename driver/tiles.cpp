#include "driver/tiles.h"

#include <chrono>
#include <ctime>
#include <sstream>
#include <stdexcept>

#include "driver/experiment_meta.h"
#include "driver/interrupted_record.h"
#include "output/atomic_file.h"
#include "output/json_writer.h"

namespace wl {
namespace {

void check_tiles_config(const Scene& scene, const TilesConfig& config) {
  if (scene.knit)
    throw std::invalid_argument("tiles: the scene is knitted; the periodic tile sampler is for woven cloth");
  if (config.samples < 2)
    throw std::invalid_argument("tiles: --samples " + std::to_string(config.samples) + ": expected at least 2");
  if (config.fit && config.holdout_every < 2)
    throw std::invalid_argument("tiles: --holdout-every " + std::to_string(config.holdout_every) +
                                ": expected at least 2 (one sample in that many held out of the fit)");
  // One fitted sample per coefficient at least: the samples not held out.
  const int fitted = config.samples - config.samples / std::max(config.holdout_every, 1);
  if (config.fit && fitted < kTileLawBasisSize)
    throw std::invalid_argument("tiles: --samples " + std::to_string(config.samples) + ": the law's " +
                                std::to_string(kTileLawBasisSize) + " coefficients need at least as many fitted " +
                                "samples, " + std::to_string(fitted) + " are fitted (more samples, or --no-fit)");
}

// The samples of the design: from the cache when it holds them, else relaxed and cached
// (r.samples counts them as they go). A signal ends the sampling before its next sample:
// Interrupted, no cache written.
std::vector<TileSample> sample_tiles(const Scene& scene, const TilesConfig& config, TilesResult& r) {
  const std::string key = tile_fabric_key(scene, config.ranges, config.samples, config.seed);
  const std::filesystem::path file = config.out_dir / tile_cache_name(key);
  if (auto cached = read_tile_samples(file, key)) {
    r.cached = true;
    r.samples_file = file;
    return *cached;
  }
  const auto wall0 = std::chrono::steady_clock::now();
  const std::clock_t cpu0 = std::clock();
  std::vector<TileSample> samples;
  for (const MacroStrain& theta : latin_hypercube(config.ranges, config.samples, config.seed)) {
    throw_if_interrupted();
    samples.push_back(relax_tile(scene, theta));
    r.samples = static_cast<int>(samples.size());
    r.converged += samples.back().converged;
  }
  r.sampling_cpu_s = static_cast<double>(std::clock() - cpu0) / CLOCKS_PER_SEC;
  r.sampling_wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  write_tile_samples(file, key, samples);
  r.samples_file = file;
  return samples;
}

Json errors_json(const TileLawErrors& e) {
  Json j = Json::object();
  j.set("samples", e.samples);
  j.set("energy_relative_rms", e.energy);
  Json s = Json::object();
  for (int k = 0; k < 6; ++k) s.set(kMacroStrainNames[k], e.stress[k]);
  j.set("stress_relative_rms", s);
  j.set("stress_relative_rms_max", e.stress_max);
  return j;
}

// tiles.json; with `interrupted_in`, of the samples a signal left (driver/interrupted_record.h).
std::string tiles_json(const Scene& scene, const TilesConfig& config, const TilesResult& r,
                       const std::string& interrupted_in = "") {
  Json j = Json::object();
  if (!interrupted_in.empty()) mark_interrupted(j, interrupted_in);
  j.set("scene", scene.source);
  const WovenTileSize size = woven_tile_size(scene);
  j.set("tile", std::to_string(size.nu) + " x " + std::to_string(size.nv));
  Json ranges = Json::object();
  for (int k = 0; k < 6; ++k)
    ranges.set(kMacroStrainNames[k], std::vector<double>{config.ranges.lo[k], config.ranges.hi[k]});
  j.set("ranges", ranges);
  j.set("design", "latin hypercube");
  j.set("seed", static_cast<std::int64_t>(config.seed));
  j.set("samples", r.samples);
  j.set("converged", r.converged);
  if (!r.samples_file.empty()) {  // the samples are whole (a signal may end the sampling)
    j.set("samples_file", r.samples_file.filename().string());
    j.set("cached", r.cached);
  }
  if (!r.samples_file.empty() && !r.cached) {
    j.set("sampling_wall_s", r.sampling_wall_s);
    j.set("sampling_cpu_s", r.sampling_cpu_s);
  }
  if (config.fit && interrupted_in.empty()) {
    Json fit = Json::object();
    fit.set("basis_size", kTileLawBasisSize);
    fit.set("holdout_every", config.holdout_every);
    fit.set("converged", r.fit.converged);
    fit.set("iterations", r.fit.iterations);
    fit.set("message", r.fit.message);
    fit.set("fitted", errors_json(r.fitted));
    fit.set("held_out", errors_json(r.held_out));
    j.set("law", fit);
  }
  add_provenance(j);
  return j.dump();
}

// The held-out samples beside the law: strains, W and the stresses, each with the law's.
std::string held_out_csv(const TileLaw& law, const std::vector<TileSample>& held_out) {
  std::ostringstream s;
  s.precision(17);
  for (const char* n : kMacroStrainNames) s << n << ",";
  s << "W_J_per_m2,law_W_J_per_m2";
  for (const char* n : kMacroStrainNames) s << ",dW_d" << n << ",law_dW_d" << n;
  s << "\n";
  for (const TileSample& t : held_out) {
    if (!t.converged) continue;
    for (double v : t.strain) s << v << ",";
    s << t.energy_density << "," << law.energy(t.strain);
    const std::array<double, 6> stress = law.stress(t.strain);
    for (int k = 0; k < 6; ++k) s << "," << t.stress[k] << "," << stress[k];
    s << "\n";
  }
  return s.str();
}

// The law fitted to the samples not held out, measured on both sets, and its files.
// A signal during the fit: Interrupted, no law written.
void fit_law(const TilesConfig& config, const std::vector<TileSample>& samples, TilesResult& r) {
  if (!config.fit) return;
  std::vector<TileSample> fitted, held_out;
  for (size_t p = 0; p < samples.size(); ++p)
    (static_cast<int>(p % config.holdout_every) == config.holdout_every - 1 ? held_out : fitted).push_back(samples[p]);
  std::array<double, 6> scale{};
  for (int k = 0; k < 6; ++k) scale[k] = std::max(std::abs(config.ranges.lo[k]), std::abs(config.ranges.hi[k]));
  r.fit = fit_tile_law(fitted, scale);
  throw_if_interrupted();
  r.fitted = tile_law_errors(r.fit.law, fitted);
  r.held_out = tile_law_errors(r.fit.law, held_out);
  write_file_atomically(config.out_dir / "tile_law.csv", tile_law_csv(r.fit.law, config.ranges));
  write_file_atomically(config.out_dir / "held_out.csv", held_out_csv(r.fit.law, held_out));
}

}  // namespace

std::string tile_law_csv(const TileLaw& law, const TileRanges& ranges) {
  std::ostringstream s;
  s.precision(17);
  s << "name,value\nenergy_scale_J_per_m2," << law.energy_scale << "\n";
  for (int k = 0; k < 6; ++k) s << "scale:" << kMacroStrainNames[k] << "," << law.scale[k] << "\n";
  for (int k = 0; k < 6; ++k) s << "lo:" << kMacroStrainNames[k] << "," << ranges.lo[k] << "\n";
  for (int k = 0; k < 6; ++k) s << "hi:" << kMacroStrainNames[k] << "," << ranges.hi[k] << "\n";
  for (int i = 0; i < kTileLawBasisSize; ++i) s << TileLaw::basis_name(i) << "," << law.coefficients[i] << "\n";
  return s.str();
}

std::string tile_cache_name(const std::string& key) { return "tile_samples_" + text_hash(key) + ".csv"; }

TilesResult run_tiles(const Scene& scene, const TilesConfig& config) {
  check_tiles_config(scene, config);
  std::filesystem::create_directories(config.out_dir);
  TilesResult r;
  std::string stage = "the tile samples";
  try {
    const std::vector<TileSample> samples = sample_tiles(scene, config, r);
    r.samples = static_cast<int>(samples.size());
    r.converged = 0;
    for (const TileSample& s : samples) r.converged += s.converged;
    stage = "the law's fit";
    fit_law(config, samples, r);
  } catch (const Interrupted&) {
    write_file_atomically(config.out_dir / "tiles.json", tiles_json(scene, config, r, stage));
    throw Interrupted{stage};
  }
  write_file_atomically(config.out_dir / "tiles.json", tiles_json(scene, config, r));
  return r;
}

}  // namespace wl
