#include "output/run_folder.h"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <string>
#include <vector>

namespace wl {

RunFolder::RunFolder(std::filesystem::path dir, const std::function<bool(const std::filesystem::path&)>& owned)
    : dir_(std::move(dir)) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (fs::exists(dir_, ec) && !fs::is_directory(dir_, ec))
    throw OutputFolderRefused("output folder '" + dir_.string() + "' exists and is not a folder");
  fs::create_directories(dir_, ec);
  if (ec) throw std::runtime_error("cannot create output folder '" + dir_.string() + "': " + ec.message());
  const fs::path lock = dir_ / kLockName;
  lock_fd_ = ::open(lock.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (lock_fd_ < 0)
    throw std::runtime_error("cannot create lock file '" + lock.string() + "': " + std::strerror(errno));
  if (::flock(lock_fd_, LOCK_EX | LOCK_NB) != 0) {
    const int err = errno;
    char pid[32] = {};
    const ssize_t n = ::pread(lock_fd_, pid, sizeof pid - 1, 0);
    ::close(lock_fd_);
    lock_fd_ = -1;
    if (err != EWOULDBLOCK)
      throw std::runtime_error("cannot lock output folder '" + dir_.string() + "': " + std::strerror(err));
    const std::string holder = n > 0 ? " (pid " + std::string(pid, static_cast<size_t>(n)) + ")" : "";
    throw OutputFolderRefused("output folder '" + dir_.string() + "' is in use by another run" + holder +
                              "; wait for it to end or choose another --out");
  }
  const std::string me = std::to_string(::getpid());
  if (::ftruncate(lock_fd_, 0) != 0 || ::pwrite(lock_fd_, me.data(), me.size(), 0) < 0) {
    // The pid is only for the message of a refused run; the lock holds without it.
  }
  std::vector<fs::path> old;
  for (auto it = fs::recursive_directory_iterator(dir_, ec); !ec && it != fs::recursive_directory_iterator();
       it.increment(ec))
    if (it->is_regular_file(ec) && owned(fs::relative(it->path(), dir_, ec))) old.push_back(it->path());
  if (ec) throw std::runtime_error("cannot list output folder '" + dir_.string() + "': " + ec.message());
  for (const fs::path& p : old)
    if (!fs::remove(p, ec) && ec)
      throw std::runtime_error("cannot remove '" + p.string() + "' of an earlier run: " + ec.message());
}

RunFolder::~RunFolder() {
  if (lock_fd_ >= 0) ::close(lock_fd_);  // releases the lock; the file stays for the next run
}

}  // namespace wl
