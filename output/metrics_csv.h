// Per-step metrics as CSV (header line, then one row per call, %.17g), written
// through AtomicOutputFile: "<path>.part" while running, renamed to <path> by
// commit(). Each row is flushed, so an interrupted run keeps a readable .part.
#pragma once
#include <filesystem>
#include <string>
#include <vector>

#include "output/atomic_file.h"

namespace wl {

class MetricsCsv {
 public:
  // Throws std::invalid_argument for no columns or a column name that is empty
  // or holds ',', '"', or a line break; std::runtime_error if the file cannot be created.
  MetricsCsv(std::filesystem::path path, std::vector<std::string> columns);

  // Throws std::invalid_argument unless values.size() == columns().size().
  void row(const std::vector<double>& values);
  void commit();

  const std::vector<std::string>& columns() const { return columns_; }
  int rows() const { return rows_; }

 private:
  AtomicOutputFile file_;
  std::vector<std::string> columns_;
  int rows_ = 0;
};

}  // namespace wl
