#include "output/run_reader.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstdlib>
#include <fstream>
#include <sstream>

namespace wl {
namespace {

std::string read_text(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw RunReadError(path.string() + ": cannot be read");
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// Value of attribute `name` in the tag text [begin, end).
std::string attribute(const std::string& text, size_t begin, size_t end, const std::string& name) {
  const std::string key = " " + name + "=\"";
  const size_t at = text.find(key, begin);
  if (at == std::string::npos || at >= end) return {};
  const size_t from = at + key.size(), to = text.find('"', from);
  return to == std::string::npos || to > end ? std::string{} : text.substr(from, to - from);
}

int line_of(const std::string& text, size_t pos) {
  return 1 + static_cast<int>(std::count(text.begin(), text.begin() + std::min(pos, text.size()), '\n'));
}

// The numbers of the DataArray named `name`; false when there is none.
bool data_array(const std::string& text, const std::filesystem::path& file, const std::string& name, size_t count,
                std::vector<double>& values) {
  const size_t at = text.find("Name=\"" + name + "\"");
  if (at == std::string::npos) return false;
  const size_t open_end = text.find('>', at), close = text.find("</DataArray>", at);
  if (open_end == std::string::npos || close == std::string::npos)
    throw RunReadError(file.string() + ":" + std::to_string(line_of(text, at)) + ": array '" + name +
                       "' is not closed");
  values.clear();
  values.reserve(count);
  const char* p = text.c_str() + open_end + 1;
  const char* stop = text.c_str() + close;
  while (p < stop) {
    char* next = nullptr;
    errno = 0;
    const double x = std::strtod(p, &next);
    if (next == p) {
      if (std::isspace(static_cast<unsigned char>(*p))) {
        ++p;
        continue;
      }
      throw RunReadError(file.string() + ":" + std::to_string(line_of(text, p - text.c_str())) + ": array '" + name +
                         "' holds a value that is not a number");
    }
    values.push_back(x);
    p = next;
  }
  if (values.size() != count)
    throw RunReadError(file.string() + ": array '" + name + "' has " + std::to_string(values.size()) +
                       " values, expected " + std::to_string(count));
  return true;
}

RecordedFrame read_vtu(const std::filesystem::path& file, double time) {
  const std::string text = read_text(file);
  const size_t piece = text.find("<Piece ");
  if (text.find("<VTKFile type=\"UnstructuredGrid\"") == std::string::npos || piece == std::string::npos)
    throw RunReadError(file.string() + ": not a VTK UnstructuredGrid file");
  const std::string n_text = attribute(text, piece, text.find('>', piece), "NumberOfPoints");
  char* end = nullptr;
  const long n = std::strtol(n_text.c_str(), &end, 10);
  if (n_text.empty() || *end != '\0' || n <= 0)
    throw RunReadError(file.string() + ":" + std::to_string(line_of(text, piece)) + ": NumberOfPoints '" + n_text +
                       "', expected a positive integer");
  RecordedFrame f;
  f.time = time;
  std::vector<double> xyz;
  if (!data_array(text, file, "Points", 3 * n, xyz)) throw RunReadError(file.string() + ": no Points array");
  f.points = Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>>(xyz.data(), n, 3);
  if (data_array(text, file, "u", n, f.u) != data_array(text, file, "v", n, f.v))
    throw RunReadError(file.string() + ": has one of the point arrays 'u', 'v' without the other");
  return f;
}

}  // namespace

std::vector<RecordedFrame> read_run_frames(const std::filesystem::path& run_dir) {
  const std::filesystem::path pvd = run_dir / "run.pvd";
  if (!std::filesystem::is_directory(run_dir)) throw RunReadError(run_dir.string() + ": not a folder");
  if (!std::filesystem::exists(pvd))
    throw RunReadError(pvd.string() + ": missing (expected the output folder of 'weavelab run')");
  const std::string text = read_text(pvd);
  std::vector<RecordedFrame> frames;
  for (size_t at = text.find("<DataSet "); at != std::string::npos; at = text.find("<DataSet ", at + 1)) {
    const size_t end = text.find('>', at);
    const std::string t = attribute(text, at, end, "timestep"), file = attribute(text, at, end, "file");
    char* stop = nullptr;
    const double time = std::strtod(t.c_str(), &stop);
    if (t.empty() || *stop != '\0' || file.empty())
      throw RunReadError(pvd.string() + ":" + std::to_string(line_of(text, at)) +
                         ": DataSet without a numeric timestep and a file");
    frames.push_back(read_vtu(run_dir / file, time));
    if (frames.back().points.rows() != frames.front().points.rows())
      throw RunReadError((run_dir / file).string() + ": " + std::to_string(frames.back().points.rows()) +
                         " points, the first frame has " + std::to_string(frames.front().points.rows()));
  }
  if (frames.empty()) throw RunReadError(pvd.string() + ": lists no frames");
  return frames;
}

std::optional<double> read_run_time_error(const std::filesystem::path& run_dir) {
  std::ifstream in(run_dir / "summary.json");
  if (!in) return std::nullopt;
  std::stringstream text;
  text << in.rdbuf();
  const std::string s = text.str();
  // The estimate is a flat object: its first "}" ends it.
  const size_t start = s.find("\"time_error\": {");
  if (start == std::string::npos) return std::nullopt;
  const size_t end = s.find('}', start), key = s.find("\"mean_rms_m\": ", start);
  if (key == std::string::npos || key > end) return std::nullopt;
  const char* number = s.c_str() + key + std::string("\"mean_rms_m\": ").size();
  char* stop = nullptr;
  const double value = std::strtod(number, &stop);
  if (stop == number) return std::nullopt;
  return value;
}

}  // namespace wl
