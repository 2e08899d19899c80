// The exit codes of every subcommand (README, "Exit codes"), in one place:
//   0    success
//   1    numerical failure (the outcome is in the command's summary)
//   2    bad scene, input file or arguments, or an output folder in use
//   3    output could not be written
//   130 / 143 interrupted by SIGINT / SIGTERM (`run`, `fit` and `calibrate` return
//             these themselves; the other studies through interruptible)
#pragma once
#include <filesystem>
#include <functional>
#include <string>

namespace wl::cli {

// Runs a subcommand and turns what it throws into its exit code and a one-line
// message on stderr: SceneError "bad scene", RunReadError "bad target run",
// FemParameterError "bad FEM parameters" and any other std::invalid_argument
// exit 2; any other std::exception exit 3. Returns `command`'s own code otherwise.
int exit_code_of(const std::function<int()>& command);

// The computation of a study, once its inputs are checked: a std::runtime_error
// from it is a numerical failure, "weavelab: NAME: message" and exit 1; a
// std::filesystem::filesystem_error stays an output error (exit 3, exit_code_of)
// and a SceneError bad input (exit 2).
int numerical_failure_is_exit_1(const std::string& name, const std::function<int()>& computation);

// A study that honours SIGINT and SIGTERM (driver/interrupted_record.h), once its
// inputs are checked: installs the handlers, then runs `computation`. An
// Interrupted from it (its record written in `out`) is "weavelab: NAME:
// interrupted by SIGTERM in STAGE; the record so far in OUT" and exit 128 + the
// signal; anything else passes on.
int interruptible(const std::string& name, const std::filesystem::path& out, const std::function<int()>& computation);

}  // namespace wl::cli
