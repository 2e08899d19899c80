// Runs the built command line (WEAVELAB_CLI) with arguments in a shell and
// captures its exit code and combined output, for the CLI tests.
#pragma once
#include <filesystem>
#include <string>

namespace wl::test {

struct CliResult {
  int code;            // exit status (-1 when killed by a signal)
  std::string output;  // stdout and stderr
};

// `args` are pasted into the command line as given (quote paths yourself);
// `scratch` is a folder for the captured output.
CliResult run_cli(const std::string& args, const std::filesystem::path& scratch);

// A fresh folder under the system temp folder named after the running test, removed by the destructor.
struct TestFolder {
  TestFolder();
  ~TestFolder();
  std::filesystem::path path;
};

}  // namespace wl::test
