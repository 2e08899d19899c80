// The subcommands of `weavelab`, one file each (cli/<name>_command.cpp): each
// registers its options on the app and returns what runs it once parsed.
#pragma once
#include <CLI/CLI.hpp>
#include <functional>

namespace wl::cli {

struct Command {
  CLI::App* app = nullptr;   // the subcommand, true when it was chosen
  std::function<int()> run;  // its work; the exit code (exceptions: exit_codes.h)
};

Command add_run_command(CLI::App& app);             // run SCENE
Command add_info_command(CLI::App& app);            // info SCENE
Command add_work_precision_command(CLI::App& app);  // work-precision SCENE
Command add_stability_command(CLI::App& app);       // stability SCENE
Command add_calibrate_command(CLI::App& app);       // calibrate SCENE
Command add_fidelity_command(CLI::App& app);        // fidelity SCENE
Command add_fit_command(CLI::App& app);             // fit SCENE --target RUN_DIR
Command add_diagnose_command(CLI::App& app);        // diagnose SCENE
Command add_modes_command(CLI::App& app);           // modes SCENE
Command add_pull_command(CLI::App& app);            // pull SCENE
Command add_tiles_command(CLI::App& app);           // tiles SCENE

}  // namespace wl::cli
