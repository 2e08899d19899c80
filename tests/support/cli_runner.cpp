#include "tests/support/cli_runner.h"

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <fstream>
#include <sstream>

namespace wl::test {

CliResult run_cli(const std::string& args, const std::filesystem::path& scratch) {
  const std::filesystem::path log = scratch / "cli.log";
  const std::string cmd = std::string(WEAVELAB_CLI) + " " + args + " > '" + log.string() + "' 2>&1";
  const int status = std::system(cmd.c_str());
  std::ifstream in(log);
  std::stringstream ss;
  ss << in.rdbuf();
  std::filesystem::remove(log);
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, ss.str()};
}

TestFolder::TestFolder() {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  path = std::filesystem::temp_directory_path() /
         ("weavelab_" + std::to_string(::getpid()) + "_" + info->test_suite_name() + "_" + info->name());
  std::filesystem::remove_all(path);
  std::filesystem::create_directories(path);
}

TestFolder::~TestFolder() { std::filesystem::remove_all(path); }

}  // namespace wl::test
