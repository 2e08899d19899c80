// `weavelab modes SCENE`: the lowest vibration modes of the yarn level and the continuum, matched by shape.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <memory>

#include "cli/commands.h"
#include "cli/exit_codes.h"
#include "cli/options.h"
#include "driver/modes.h"
#include "driver/run_settings.h"

namespace wl::cli {
namespace {

struct ModesArgs {
  ModesConfig config;
  std::string scene, fem_params, out;
  bool quiet = false;
};

void add_options(CLI::App* modes, ModesArgs& a) {
  ModesConfig& modc = a.config;
  modes->add_option("scene", a.scene, "Scene file (TOML)")->required();
  modes->add_option("--fem-params", a.fem_params,
                    "Continuum parameter file (default: the scene's, or the first guess)");
  modes->add_option("--count", modc.count, "Modes per model")->capture_default_str();
  modes
      ->add_option("--lean", modc.lean_m,
                   "Out-of-plane lean [m] at the bottom row from which a cloth whose planar hang is unstable "
                   "settles (0: keep the planar hang)")
      ->capture_default_str();
  modes->add_flag("--fd-check", modc.fd_check,
                  "Also form K by central differences of the full force (frozen contact forces recomputed) and "
                  "report its asymmetry, its distance from the assembled K and its lowest frequencies");
  modes->add_option("--out", a.out, "Output folder (default results/modes/<scene name>)");
  modes->add_flag("--quiet", a.quiet, "No progress on stderr");
}

int run(const CLI::App* modes, const ModesArgs& a) {
  ModesConfig modc = a.config;
  modc.scene_path = a.scene;
  modc.scene = load_scene(a.scene);
  check_comparison_memory(modc.scene);  // before any allocation: exit 2
  if (!a.fem_params.empty()) modc.fem_params = a.fem_params;
  modc.out_dir = output_folder(modes->count("--out") ? std::optional(a.out) : std::nullopt,
                               std::filesystem::path("results/modes") / std::filesystem::path(a.scene).stem());
  modc.progress = !a.quiet;
  return interruptible("modes", modc.out_dir, [&] {
    return numerical_failure_is_exit_1("modes", [&] {
      const ModesResult r = run_modes(modc);
      double lowest_mac = 1.0;
      for (const ModePair& p : r.pairs) lowest_mac = std::min(lowest_mac, p.mac);
      std::fprintf(stderr,
                   "weavelab: modes: equilibria %.3g mm apart (RMS over the crossings); lowest %.4g Hz (yarn), "
                   "%.4g Hz (continuum); %zu pairs, lowest MAC %.3g; results in %s\n",
                   1e3 * r.equilibrium_rms_m, frequency_hz(r.yarn.modes.eigenvalues.front()),
                   frequency_hz(r.fem.modes.eigenvalues.front()), r.pairs.size(), lowest_mac,
                   modc.out_dir.string().c_str());
      return 0;
    });
  });
}

}  // namespace

Command add_modes_command(CLI::App& app) {
  auto args = std::make_shared<ModesArgs>();
  CLI::App* command = app.add_subcommand(
      "modes",
      "Lowest vibration modes of the yarn level and the continuum about the same hanging equilibrium (wind "
      "off), matched by shape (MAC): frequencies, MAC matrix, mode shapes (VTU)");
  add_options(command, *args);
  return {command, [command, args] { return run(command, *args); }};
}

}  // namespace wl::cli
