// The output folder of one run. Opening it creates the folder and takes an
// exclusive lock on DIR/.weavelab.lock (flock: held until the RunFolder is
// destroyed or the process ends, even by kill -9), so a second run into the
// same folder is refused instead of interleaving its files with the first.
// Then it removes the files an earlier run left there that `owned` claims, so
// the folder holds no file of an old run beside the new series. Other files
// are left alone.
#pragma once
#include <filesystem>
#include <functional>
#include <stdexcept>

namespace wl {

// The folder is in use by another run, or is not a folder; nothing was written.
class OutputFolderRefused : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

class RunFolder {
 public:
  // `owned(relative path)`: whether a file below the folder belongs to a run's
  // output (and so is removed when found at the start). Throws
  // OutputFolderRefused, or std::runtime_error when the folder or the lock
  // file cannot be created.
  RunFolder(std::filesystem::path dir, const std::function<bool(const std::filesystem::path&)>& owned);
  ~RunFolder();
  RunFolder(const RunFolder&) = delete;
  RunFolder& operator=(const RunFolder&) = delete;

  const std::filesystem::path& dir() const { return dir_; }
  static constexpr const char* kLockName = ".weavelab.lock";

 private:
  std::filesystem::path dir_;
  int lock_fd_ = -1;
};

}  // namespace wl
