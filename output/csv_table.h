// A CSV table of text cells (header line, then one row per call), for the
// experiment results: cells holding ',', '"' or line breaks are quoted
// (RFC 4180). Written through AtomicOutputFile: "<path>.part" while running,
// renamed to <path> by commit(); every row is flushed.
#pragma once
#include <filesystem>
#include <string>
#include <vector>

#include "output/atomic_file.h"

namespace wl {

class CsvTable {
 public:
  // Throws std::invalid_argument for no columns or an empty column name.
  CsvTable(std::filesystem::path path, std::vector<std::string> columns);
  // Throws std::invalid_argument unless cells.size() == columns().size().
  void row(const std::vector<std::string>& cells);
  void commit();
  const std::vector<std::string>& columns() const { return columns_; }
  int rows() const { return rows_; }

 private:
  AtomicOutputFile file_;
  std::vector<std::string> columns_;
  int rows_ = 0;
};

// One CSV cell, quoted when needed.
std::string csv_cell(const std::string& text);
// A number as a CSV cell: %.10g; NaN → "" (empty cell), ±inf → "inf"/"-inf".
std::string csv_number(double x);

}  // namespace wl
