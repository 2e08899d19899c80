#include "output/csv_table.h"

#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace wl {
namespace {

const std::filesystem::path& with_valid_table_columns(const std::vector<std::string>& columns,
                                                      const std::filesystem::path& path) {
  if (columns.empty()) throw std::invalid_argument("CsvTable '" + path.string() + "': no columns given");
  for (const std::string& c : columns)
    if (c.empty()) throw std::invalid_argument("CsvTable '" + path.string() + "': empty column name");
  return path;
}

std::string csv_line(const std::vector<std::string>& cells) {
  std::string line;
  for (size_t k = 0; k < cells.size(); ++k) {
    if (k) line += ',';
    line += csv_cell(cells[k]);
  }
  return line + '\n';
}

}  // namespace

std::string csv_cell(const std::string& text) {
  if (text.find_first_of(",\"\r\n") == std::string::npos) return text;
  std::string q = "\"";
  for (char c : text) {
    if (c == '"') q += '"';
    q += c;
  }
  return q + '"';
}

std::string csv_number(double x) {
  if (std::isnan(x)) return "";
  if (std::isinf(x)) return x > 0 ? "inf" : "-inf";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.10g", x);
  return buf;
}

CsvTable::CsvTable(std::filesystem::path path, std::vector<std::string> columns)
    : file_(with_valid_table_columns(columns, path)), columns_(std::move(columns)) {
  file_.write(csv_line(columns_));
  file_.flush();
}

void CsvTable::row(const std::vector<std::string>& cells) {
  if (cells.size() != columns_.size())
    throw std::invalid_argument("CsvTable '" + file_.path().string() + "': row has " + std::to_string(cells.size()) +
                                " cells, expected " + std::to_string(columns_.size()));
  file_.write(csv_line(cells));
  file_.flush();
  ++rows_;
}

void CsvTable::commit() { file_.commit(); }

}  // namespace wl
