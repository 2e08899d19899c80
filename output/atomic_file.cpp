#include "output/atomic_file.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>

namespace wl {
namespace {

[[noreturn]] void fail(const std::string& what, const std::filesystem::path& path, int err) {
  throw std::runtime_error(what + " '" + path.string() + "': " + std::strerror(err));
}

std::filesystem::path with_suffix(const std::filesystem::path& path, const std::string& suffix) {
  std::filesystem::path p = path;
  p += suffix;
  return p;
}

}  // namespace

void write_file_atomically(const std::filesystem::path& path, std::string_view content) {
  const std::filesystem::path tmp = with_suffix(path, ".tmp-" + std::to_string(::getpid()));
  const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) fail("cannot create temporary file for", path, errno);
  auto abandon = [&](const char* what) {
    const int err = errno;
    ::close(fd);
    ::unlink(tmp.c_str());
    fail(what, path, err);
  };
  const char* data = content.data();
  size_t left = content.size();
  while (left > 0) {
    const ssize_t n = ::write(fd, data, left);
    if (n < 0) {
      if (errno == EINTR) continue;
      abandon("cannot write");
    }
    data += n;
    left -= static_cast<size_t>(n);
  }
  if (::fsync(fd) != 0) abandon("cannot flush");
  if (::close(fd) != 0) {
    const int err = errno;
    ::unlink(tmp.c_str());
    fail("cannot close", path, err);
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0) {
    const int err = errno;
    ::unlink(tmp.c_str());
    fail("cannot rename temporary file to", path, err);
  }
}

AtomicOutputFile::AtomicOutputFile(std::filesystem::path path) : path_(std::move(path)) {
  const auto part = part_path();
  file_ = std::fopen(part.c_str(), "wb");
  if (!file_) fail("cannot create", part, errno);
}

AtomicOutputFile::~AtomicOutputFile() {
  if (file_) std::fclose(file_);  // leaves the .part file; the final name is untouched
}

std::filesystem::path AtomicOutputFile::part_path() const { return with_suffix(path_, ".part"); }

void AtomicOutputFile::write(std::string_view text) {
  if (!file_) throw std::runtime_error("write to '" + path_.string() + "' after commit()");
  if (std::fwrite(text.data(), 1, text.size(), file_) != text.size()) fail("cannot write", part_path(), errno);
}

void AtomicOutputFile::flush() {
  if (file_ && std::fflush(file_) != 0) fail("cannot flush", part_path(), errno);
}

void AtomicOutputFile::commit() {
  if (committed_) return;
  if (!file_) throw std::runtime_error("commit of '" + path_.string() + "' after a failed commit");
  std::FILE* f = file_;
  file_ = nullptr;
  const auto part = part_path();
  if (std::fflush(f) != 0 || ::fsync(::fileno(f)) != 0) {
    const int err = errno;
    std::fclose(f);
    fail("cannot flush", part, err);
  }
  if (std::fclose(f) != 0) fail("cannot close", part, errno);
  if (std::rename(part.c_str(), path_.c_str()) != 0) fail("cannot rename '" + part.string() + "' to", path_, errno);
  committed_ = true;
}

}  // namespace wl
