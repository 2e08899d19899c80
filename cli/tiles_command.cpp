// `weavelab tiles SCENE`: the homogenized energy density of the scene's woven
// fabric sampled from its periodic tile, and a continuum law fitted to it
// (docs/calibration.md §9).
#include <cstdio>
#include <filesystem>
#include <memory>

#include "cli/commands.h"
#include "cli/exit_codes.h"
#include "cli/options.h"
#include "driver/run_settings.h"
#include "driver/tiles.h"

namespace wl::cli {
namespace {

struct TilesArgs {
  std::string scene, out;
  int samples = 1024, holdout_every = 5;
  std::uint64_t seed = 1;
  std::vector<std::string> ranges;
  bool no_fit = false;
};

int run(const CLI::App* tiles, const TilesArgs& a) {
  TilesConfig config;
  config.out_dir = output_folder(tiles->count("--out") ? std::optional(a.out) : std::nullopt,
                                 std::filesystem::path("results/tiles") / std::filesystem::path(a.scene).stem());
  const Scene scene = load_scene(a.scene);
  config.samples = a.samples;
  config.seed = a.seed;
  config.holdout_every = a.holdout_every;
  config.fit = !a.no_fit;
  if (!scene.knit) config.ranges = default_tile_ranges(scene);
  for (const std::string& item : a.ranges) apply_tile_range(config.ranges, item, "--range");
  return interruptible("tiles", config.out_dir, [&] {
    return numerical_failure_is_exit_1("tiles", [&] {
      const TilesResult r = run_tiles(scene, config);
      std::fprintf(stderr, "weavelab: tiles: %d of %d samples converged%s", r.converged, r.samples,
                   r.cached ? " (cached)" : "");
      if (config.fit)
        std::fprintf(stderr, "; law on held-out samples: energy %.3g, stress %.3g (relative RMS)", r.held_out.energy,
                     r.held_out.stress_max);
      std::fprintf(stderr, "; results in %s\n", config.out_dir.string().c_str());
      // A sample that does not converge is an outcome on the record (tiles.json, the
      // samples' `converged` column) and stays out of the fit; no sample, or no fit, fails.
      return r.converged > 0 && (!config.fit || r.fit.converged) ? 0 : 1;
    });
  });
}

}  // namespace

Command add_tiles_command(CLI::App& app) {
  auto args = std::make_shared<TilesArgs>();
  CLI::App* command = app.add_subcommand(
      "tiles", "Homogenized energy of the woven fabric's periodic tile over six strains, and a law fitted to it");
  command->add_option("scene", args->scene, "Scene file (TOML), woven cloth")->required();
  command->add_option("--samples", args->samples, "Latin hypercube samples")->capture_default_str();
  command->add_option("--seed", args->seed, "Seed of the Latin hypercube")->capture_default_str();
  command->add_option("--range", args->ranges,
                      "NAME=LO,HI replaces a strain's range (stretch_warp, stretch_weft, shear [rad], "
                      "curvature_warp, curvature_weft, twist [1/m]); repeatable");
  command->add_option("--holdout-every", args->holdout_every, "Hold one sample in this many out of the fit")
      ->capture_default_str();
  command->add_flag("--no-fit", args->no_fit, "Sample only");
  command->add_option("--out", args->out, "Output folder and sample cache (default results/tiles/<scene name>)");
  return {command, [command, args] { return run(command, *args); }};
}

}  // namespace wl::cli
