#include "output/metrics_csv.h"

#include <cstdio>
#include <stdexcept>

namespace wl {
namespace {

// Returns `path` once the column names are valid (used before the file is created).
const std::filesystem::path& with_valid_metrics_columns(const std::vector<std::string>& columns,
                                                        const std::filesystem::path& path) {
  if (columns.empty()) throw std::invalid_argument("MetricsCsv '" + path.string() + "': no columns given");
  for (const std::string& c : columns)
    if (c.empty() || c.find_first_of(",\"\r\n") != std::string::npos)
      throw std::invalid_argument("MetricsCsv '" + path.string() + "': column name '" + c +
                                  "' must be non-empty without ',', '\"' or line breaks");
  return path;
}

}  // namespace

MetricsCsv::MetricsCsv(std::filesystem::path path, std::vector<std::string> columns)
    : file_(with_valid_metrics_columns(columns, path)), columns_(std::move(columns)) {
  std::string header;
  for (size_t k = 0; k < columns_.size(); ++k) {
    if (k) header += ',';
    header += columns_[k];
  }
  header += '\n';
  file_.write(header);
  file_.flush();
}

void MetricsCsv::row(const std::vector<double>& values) {
  if (values.size() != columns_.size())
    throw std::invalid_argument("MetricsCsv '" + file_.path().string() + "': row has " + std::to_string(values.size()) +
                                " values, expected " + std::to_string(columns_.size()) + " (one per column)");
  std::string line;
  line.reserve(25 * values.size());
  char buf[32];
  for (size_t k = 0; k < values.size(); ++k) {
    if (k) line += ',';
    const int n = std::snprintf(buf, sizeof buf, "%.17g", values[k]);
    line.append(buf, static_cast<size_t>(n));
  }
  line += '\n';
  file_.write(line);
  file_.flush();
  ++rows_;
}

void MetricsCsv::commit() { file_.commit(); }

}  // namespace wl
