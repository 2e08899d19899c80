// `weavelab fidelity SCENE`: the scene at a ladder of model fidelities, each measured against
// the full yarn-level model.
#include <cstdio>
#include <filesystem>
#include <memory>

#include "cli/commands.h"
#include "cli/exit_codes.h"
#include "cli/options.h"
#include "driver/fidelity.h"
#include "driver/fidelity_reference.h"
#include "driver/run_settings.h"

namespace wl::cli {
namespace {

struct FidelityArgs {
  FidelityConfig config;
  std::string scene, variants, fem_params, out, reference_from;
  double tolerance = 0, duration = 0;
  TimeStepsArgs time_steps;
  bool quiet = false, no_estimate = false, list = false;
};

void add_options(CLI::App* fidelity, FidelityArgs& a) {
  FidelityConfig& fid = a.config;
  fidelity->add_option("scene", a.scene, "Scene file (TOML)")->required();
  fidelity->add_option("--tolerance", a.tolerance,
                       "Worst-frame RMS distance a variant may have to count as good enough [m] (default 1 % of the "
                       "cloth size)");
  fidelity->add_option("--variants", a.variants,
                       "Comma-separated variants (default: all the scene allows): " + joined(fidelity_variant_names()));
  fidelity->add_option("--reference", fid.reference, "Yarn-level variant the others are measured against")
      ->capture_default_str();
  fidelity->add_option("--fem-params", a.fem_params,
                       "Calibrated FEM parameter file (from `calibrate`); without it (or a scene parameter_file) the "
                       "calibrated continuum variants are left out");
  fidelity->add_option("--repeats", fid.repeats, "Runs per variant; CPU and wall time are their medians")
      ->capture_default_str();
  fidelity->add_option("--duration", a.duration, "Simulated time [s] (overrides the scene)");
  add_time_steps_options(fidelity, a.time_steps, "controlled", kTimeStepsHelp + " (the reference and the model rungs)");
  fidelity->add_flag("--no-error-estimate", a.no_estimate,
                     "Do not estimate each run's time error (halves the cost; no time-error column)");
  fidelity->add_option("--out", a.out, "Output folder (default results/fidelity/<scene name>)");
  fidelity->add_flag("--quiet", a.quiet, "No progress on stderr");
  fidelity->add_flag("--reference-only", fid.reference_only,
                     "Run only the reference, and keep it in OUT/reference.bin for --reference-from");
  fidelity->add_option("--reference-from", a.reference_from,
                       "Folder of a --reference-only run with the same scene and options: its reference is read, "
                       "not run again (the ladder as separate jobs, experiments/fidelity/Snakefile)");
  fidelity->add_flag("--list-variants", a.list,
                     "Print the variants the ladder would run, one per line, and exit (nothing is run or written)");
}

// The configuration from the parsed options; std::invalid_argument (or SceneError) for a bad value.
FidelityConfig config_of(const CLI::App* fidelity, const FidelityArgs& a) {
  FidelityConfig fid = a.config;
  fid.scene_path = a.scene;
  fid.scene = load_scene(a.scene);
  check_comparison_memory(fid.scene);  // before any allocation: exit 2
  if (fidelity->count("--duration")) apply_duration_override(fid.scene, a.duration, fid.overrides);
  check_run_settings(fid.scene, fid.overrides);
  if (fidelity->count("--tolerance")) fid.tolerance_m = positive_option("--tolerance", a.tolerance);
  fid.variants = split_list(a.variants);
  if (fidelity->count("--variants") && fid.variants.empty()) throw std::invalid_argument("--variants: empty list");
  if (!a.fem_params.empty()) fid.fem_params = a.fem_params;
  fid.time_steps = time_steps_of(a.time_steps);
  fid.error_estimate = !a.no_estimate;
  fid.out_dir = output_folder(fidelity->count("--out") ? std::optional(a.out) : std::nullopt,
                              std::filesystem::path("results/fidelity") / std::filesystem::path(a.scene).stem());
  fid.progress = !a.quiet;
  if (!a.reference_from.empty()) fid.reference_from = a.reference_from;
  if (fid.reference_only && (fid.reference_from || fidelity->count("--variants")))
    throw std::invalid_argument(
        "--reference-only: runs no variant; --variants and --reference-from "
        "do not go with it");
  return fid;
}

// The ladder's verdict on stderr: the cheapest variant within the tolerance, if any.
void print_choice(const FidelityConfig& fid, const FidelityPlan& plan, const FidelityResult& r) {
  const FidelityChoice& c = r.within_tolerance;
  if (c.variant.empty()) {
    std::fprintf(stderr,
                 "weavelab: fidelity: no variant is within %.3g mm (%.3g %% of the %.3g mm cloth) with its own "
                 "time error; results in %s\n",
                 1e3 * c.tolerance_m, 100 * c.tolerance_m / plan.cloth_size_m, 1e3 * plan.cloth_size_m,
                 fid.out_dir.string().c_str());
    return;
  }
  std::fprintf(stderr,
               "weavelab: fidelity: cheapest within %.3g mm (%.3g %% of the %.3g mm cloth): %s, %.3g x "
               "faster than %s (CPU %.3g s against %.3g s); results in %s\n",
               1e3 * c.tolerance_m, 100 * c.tolerance_m / plan.cloth_size_m, 1e3 * plan.cloth_size_m, c.variant.c_str(),
               c.speedup, plan.reference.name.c_str(), c.cpu_s, r.rows.front().cpu_s, fid.out_dir.string().c_str());
}

int run(const CLI::App* fidelity, const FidelityArgs& a) {
  const FidelityConfig fid = config_of(fidelity, a);
  const FidelityPlan plan = plan_fidelity(fid);  // every input checked; nothing written yet
  if (a.list) {
    for (const PlannedVariant& v : plan.variants) std::printf("%s\n", v.name.c_str());
    return 0;
  }
  // a missing or mismatched reference file is bad input: exit 2 before anything is written
  if (fid.reference_from) read_fidelity_reference(*fid.reference_from, fidelity_reference_key(fid));
  return interruptible("fidelity", fid.out_dir, [&] {
    return numerical_failure_is_exit_1("fidelity", [&] {
      print_choice(fid, plan, run_fidelity(fid, plan));
      return 0;
    });
  });
}

}  // namespace

Command add_fidelity_command(CLI::App& app) {
  auto args = std::make_shared<FidelityArgs>();
  CLI::App* command = app.add_subcommand(
      "fidelity",
      "Run the scene at a ladder of model fidelities (yarn without one term, frozen sliding, continuum "
      "at strides 1, 2, 4) and measure each against the full yarn model; writes fidelity.csv and .json");
  add_options(command, *args);
  return {command, [command, args] { return run(command, *args); }};
}

}  // namespace wl::cli
