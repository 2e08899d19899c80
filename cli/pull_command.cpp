// `weavelab pull SCENE`: a uniaxial strip test of a flat cloth at yarn level.
#include <cstdio>
#include <filesystem>
#include <memory>

#include "cli/commands.h"
#include "cli/exit_codes.h"
#include "cli/options.h"
#include "driver/run_settings.h"
#include "driver/uniaxial_pull.h"

namespace wl::cli {
namespace {

struct PullArgs {
  std::string scene, strains = "0.01,0.02,0.05,0.1", direction = "y", out;
  bool hold_z = false;
};

int run(const CLI::App* pull, const PullArgs& a) {
  PullConfig pc;
  pc.strains = split_numbers(a.strains, "--strains");
  pc.direction = a.direction[0];
  pc.hold_z = a.hold_z;
  pc.out_dir = output_folder(pull->count("--out") ? std::optional(a.out) : std::nullopt,
                             std::filesystem::path("results/pull") / std::filesystem::path(a.scene).stem());
  const Scene scene = load_scene(a.scene);
  return interruptible("pull", pc.out_dir, [&] {
    const PullResult r = pull_command(scene, pc);
    std::fprintf(stderr, "weavelab: pull: %zu of %zu rungs, yarn length per area %.6g 1/m; results in %s%s%s\n",
                 r.points.size(), pc.strains.size() + 1, r.yarn_length_per_area_per_m, pc.out_dir.string().c_str(),
                 r.complete ? "" : "; stopped: ", r.message.c_str());
    return r.complete ? 0 : 1;
  });
}

}  // namespace

Command add_pull_command(CLI::App& app) {
  auto args = std::make_shared<PullArgs>();
  CLI::App* command =
      app.add_subcommand("pull", "Uniaxial strip test of a flat cloth at yarn level: pull.csv, pull.json");
  command->add_option("scene", args->scene, "Scene file (TOML), flat pose")->required();
  command->add_option("--strains", args->strains, "Increasing strain ladder")->capture_default_str();
  command->add_option("--direction", args->direction, "Pull along x (knit: course-wise) or y (knit: wale-wise)")
      ->check(CLI::IsMember({"x", "y"}))
      ->capture_default_str();
  command->add_option("--out", args->out, "Output folder (default results/pull/<scene name>)");
  command->add_flag("--hold-z", args->hold_z, "Hold every node's z at rest: an in-plane test (no buckling or curl)");
  return {command, [command, args] { return run(command, *args); }};
}

}  // namespace wl::cli
