// Helpers for the output tests: a scratch folder and running /usr/bin/python3
// (a declared dependency, with numpy, meshio and matplotlib) on a script.
#pragma once
#include <gtest/gtest.h>
#include <stdlib.h>
#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include "models/core/frame.h"

namespace wl::test {

// The quads of an n×n grid of points numbered i + n·j.
inline CellBlock quad_grid_cells(int n) {
  CellBlock quads{CellType::quad, {}};
  for (int j = 0; j + 1 < n; ++j)
    for (int i = 0; i + 1 < n; ++i)
      quads.connectivity.insert(quads.connectivity.end(),
                                {i + n * j, i + 1 + n * j, i + 1 + n * (j + 1), i + n * (j + 1)});
  return quads;
}

// A fresh folder under the system temp dir, removed with everything in it.
class ScratchDir {
 public:
  ScratchDir() {
    std::string pattern = (std::filesystem::temp_directory_path() / "weavelab-test-XXXXXX").string();
    if (!::mkdtemp(pattern.data())) throw std::runtime_error("mkdtemp failed for " + pattern);
    path_ = pattern;
  }
  ~ScratchDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  ScratchDir(const ScratchDir&) = delete;
  ScratchDir& operator=(const ScratchDir&) = delete;
  const std::filesystem::path& path() const { return path_; }
  std::filesystem::path operator/(const std::string& name) const { return path_ / name; }

 private:
  std::filesystem::path path_;
};

struct CommandResult {
  int exit_code = -1;
  std::string output;  // stdout and stderr together
};

inline CommandResult run_command(const std::string& command) {
  CommandResult r;
  std::FILE* pipe = ::popen((command + " 2>&1").c_str(), "r");
  if (!pipe) return r;
  std::array<char, 4096> buffer;
  size_t n;
  while ((n = std::fread(buffer.data(), 1, buffer.size(), pipe)) > 0) r.output.append(buffer.data(), n);
  const int status = ::pclose(pipe);
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

inline std::string shell_quote(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += (c == '\'') ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

inline const char* python() { return "/usr/bin/python3"; }

// Succeeds when /usr/bin/python3 exists and imports the given modules.
inline ::testing::AssertionResult python_with(const std::string& modules) {
  if (!std::filesystem::exists(python()))
    return ::testing::AssertionFailure() << python() << " is missing; it is a declared dependency (Debian python3)";
  const CommandResult r = run_command(std::string(python()) + " -c " + shell_quote("import " + modules));
  if (r.exit_code != 0)
    return ::testing::AssertionFailure() << python() << " cannot import " << modules
                                         << " (declared dependencies: python3-numpy, python3-meshio, "
                                            "python3-matplotlib):\n"
                                         << r.output;
  return ::testing::AssertionSuccess();
}

// Writes `script` into `dir` and runs it with /usr/bin/python3 and `args`.
inline CommandResult run_python_script(const std::filesystem::path& dir, const std::string& script,
                                       const std::string& args = "") {
  const auto file = dir / "check.py";
  std::ofstream(file) << script;
  return run_command(std::string(python()) + " " + shell_quote(file.string()) + " " + args);
}

inline std::string read_text(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

inline int count_entries(const std::filesystem::path& dir) {
  int n = 0;
  for ([[maybe_unused]] const auto& e : std::filesystem::directory_iterator(dir)) ++n;
  return n;
}

}  // namespace wl::test
