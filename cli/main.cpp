// weavelab command line: `weavelab run SCENE`, `weavelab info SCENE`,
// `weavelab work-precision SCENE`, `weavelab stability SCENE`,
// `weavelab calibrate SCENE`, `weavelab fidelity SCENE`, `weavelab fit SCENE --target RUN_DIR`,
// `weavelab diagnose SCENE`, `weavelab modes SCENE`, `weavelab pull SCENE`, `weavelab tiles SCENE`.
// Each subcommand is its own file (cli/<name>_command.cpp); the exit codes are
// cli/exit_codes.h's: 0 success, 1 numerical failure (outcome in the summary),
// 2 bad scene, input file or arguments, or an output folder in use,
// 3 output could not be written, 130 / 143 interrupted by SIGINT / SIGTERM.
#include <CLI/CLI.hpp>
#include <vector>

#include "cli/commands.h"
#include "cli/exit_codes.h"
#include "driver/determinism.h"

int main(int argc, char** argv) {
  wl::hold_blas_threads();  // bitwise reproducible runs (README: reproducibility)
  CLI::App app{"weavelab: yarn-level and continuum cloth under pluggable integrators"};
  app.require_subcommand(1);
  using namespace wl::cli;
  const std::vector<Command> commands{
      add_run_command(app),       add_info_command(app),      add_work_precision_command(app),
      add_stability_command(app), add_calibrate_command(app), add_fidelity_command(app),
      add_fit_command(app),       add_diagnose_command(app),  add_modes_command(app),
      add_pull_command(app),      add_tiles_command(app)};

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? 0 : 2;
  }
  for (const Command& command : commands)
    if (*command.app) return exit_code_of(command.run);
  return 2;  // unreachable: require_subcommand(1)
}
