// The exit codes of every subcommand (README, "Exit codes"), in one place:
//   0    success
//   1    numerical failure (the outcome is in the command's summary)
//   2    bad scene, input file or arguments, or an output folder in use
//   3    output could not be written
//   130 / 143 interrupted by SIGINT / SIGTERM (`run` returns these itself)
#pragma once
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

}  // namespace wl::cli
