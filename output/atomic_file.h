// Files that never appear torn (docs/design.md §9): content is
// written under a temporary name in the same folder and renamed into place.
#pragma once
#include <cstdio>
#include <filesystem>
#include <string>
#include <string_view>

namespace wl {

// Writes `content` to "<path>.tmp-<pid>", flushes it to disk and renames it to
// `path`. Throws std::runtime_error naming the path and the errno text on any
// failure; the temporary file is removed then.
void write_file_atomically(const std::filesystem::path& path, std::string_view content);

// A file written incrementally (e.g. a CSV that grows every step). Writes go to
// "<path>.part"; commit() flushes and renames it to `path`. Destroyed without
// commit(), only the .part file remains (flushed), never a torn final file.
class AtomicOutputFile {
 public:
  explicit AtomicOutputFile(std::filesystem::path path);  // throws if the .part file cannot be created
  ~AtomicOutputFile();
  AtomicOutputFile(const AtomicOutputFile&) = delete;
  AtomicOutputFile& operator=(const AtomicOutputFile&) = delete;

  void write(std::string_view text);  // throws on a write error or after commit()
  void flush();                       // pushes buffered text into the .part file
  void commit();                      // flush, fsync, close, rename .part → final; throws on failure
  bool committed() const { return committed_; }
  const std::filesystem::path& path() const { return path_; }
  std::filesystem::path part_path() const;

 private:
  std::filesystem::path path_;
  std::FILE* file_ = nullptr;
  bool committed_ = false;
};

}  // namespace wl
