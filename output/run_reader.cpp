#include "output/run_reader.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "models/scene/scene.h"
#include "models/scene/scene_limits.h"

namespace wl {
namespace {

// The whole of a regular file (never a device or a pipe, which may not end).
std::string read_text(const std::filesystem::path& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec))
    throw RunReadError(path.string() + ": " + (std::filesystem::exists(path, ec) ? "not a regular file" : "missing") +
                       " (expected a file written by 'weavelab run')");
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

int line_number_at(const std::string& text, size_t pos) {
  return 1 + static_cast<int>(std::count(text.begin(), text.begin() + std::min(pos, text.size()), '\n'));
}

std::string format_g(double x) {
  char b[32];
  std::snprintf(b, sizeof b, "%.6g", x);
  return b;
}

// Where a frame is: its file and its place in run.pvd.
struct FrameSource {
  std::filesystem::path file;
  size_t index = 0;  // in run.pvd, from 0
  double time = 0.0;
  std::string at(const std::string& text, size_t pos) const {
    return file.string() + ":" + std::to_string(line_number_at(text, pos)) + ": frame " + std::to_string(index) +
           " (t = " + format_g(time) + " s)";
  }
};

// The numbers of the DataArray named `name`, `components` per point, each
// finite; false when there is none.
bool data_array(const std::string& text, const FrameSource& src, const std::string& name, size_t count, int components,
                std::vector<double>& values) {
  const size_t at = text.find("Name=\"" + name + "\"");
  if (at == std::string::npos) return false;
  const size_t open_end = text.find('>', at), close = text.find("</DataArray>", at);
  if (open_end == std::string::npos || close == std::string::npos)
    throw RunReadError(src.at(text, at) + ": array '" + name + "' is not closed");
  values.clear();
  values.reserve(count);
  const char* p = text.c_str() + open_end + 1;
  const char* stop = text.c_str() + close;
  while (p < stop) {
    if (std::isspace(static_cast<unsigned char>(*p))) {
      ++p;
      continue;
    }
    char* next = nullptr;
    const double x = std::strtod(p, &next);
    if (next == p) {
      throw RunReadError(src.at(text, p - text.c_str()) + ": array '" + name + "' holds a value that is not a number");
    }
    if (!std::isfinite(x)) {
      const size_t k = values.size();
      const std::string component = components == 3 ? std::string(" coordinate ") + "xyz"[k % 3] : "";
      throw RunReadError(src.at(text, p - text.c_str()) + ", point " + std::to_string(k / components) + ": array '" +
                         name + "'" + component + ": got " + std::string(p, static_cast<const char*>(next)) +
                         ", expected a finite number");
    }
    if (values.size() == count)
      throw RunReadError(src.at(text, p - text.c_str()) + ": array '" + name + "' has more than the " +
                         std::to_string(count) + " values of its NumberOfPoints");
    values.push_back(x);
    p = next;
  }
  if (values.size() != count)
    throw RunReadError(src.at(text, at) + ": array '" + name + "' has " + std::to_string(values.size()) +
                       " values, expected " + std::to_string(count));
  return true;
}

// NumberOfPoints, at most what a scene may have (kMaxYarns² crossings) and
// what the file can hold: every coordinate takes a digit and a separator.
long long number_of_points(const std::string& text, const FrameSource& src, size_t piece) {
  const std::string n_text = attribute(text, piece, text.find('>', piece), "NumberOfPoints");
  const long long most = std::min<long long>(kMaxYarns * kMaxYarns, static_cast<long long>(text.size() / 6));
  char* end = nullptr;
  errno = 0;
  const long long n = std::strtoll(n_text.c_str(), &end, 10);
  if (n_text.empty() || *end != '\0' || errno == ERANGE || n <= 0 || n > most)
    throw RunReadError(src.at(text, piece) + ": NumberOfPoints '" + n_text + "', expected an integer from 1 to " +
                       std::to_string(most) + " (at most " + std::to_string(kMaxYarns) +
                       "² = " + std::to_string(kMaxYarns * kMaxYarns) + " points, and a file of " +
                       std::to_string(text.size()) + " bytes holds at most " + std::to_string(text.size() / 6) + ")");
  return n;
}

RecordedFrame read_vtu(const FrameSource& src) {
  const std::string text = read_text(src.file);
  const size_t piece = text.find("<Piece ");
  if (text.find("<VTKFile type=\"UnstructuredGrid\"") == std::string::npos || piece == std::string::npos)
    throw RunReadError(src.file.string() + ": not a VTK UnstructuredGrid file");
  const long long n = number_of_points(text, src, piece);
  RecordedFrame f;
  f.time = src.time;
  std::vector<double> xyz;
  if (!data_array(text, src, "Points", 3 * n, 3, xyz)) throw RunReadError(src.file.string() + ": no Points array");
  f.points = Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>>(xyz.data(), n, 3);
  if (data_array(text, src, "u", n, 1, f.u) != data_array(text, src, "v", n, 1, f.v))
    throw RunReadError(src.file.string() + ": has one of the point arrays 'u', 'v' without the other");
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
    const auto where = [&] { return pvd.string() + ":" + std::to_string(line_number_at(text, at)); };
    const size_t end = text.find('>', at);
    const std::string t = attribute(text, at, end, "timestep"), file = attribute(text, at, end, "file");
    char* stop = nullptr;
    const double time = std::strtod(t.c_str(), &stop);
    if (t.empty() || *stop != '\0' || file.empty())
      throw RunReadError(where() + ": DataSet without a numeric timestep and a file");
    if (!std::isfinite(time) || (!frames.empty() && !(time > frames.back().time)))
      throw RunReadError(where() + ": timestep " + t + ", expected a finite time after the previous frame's" +
                         (frames.empty() ? std::string() : " (" + format_g(frames.back().time) + " s)"));
    // A run writes its frame at t = 0 and at most kMaxFrames after it.
    if (static_cast<double>(frames.size()) >= kMaxFrames + 1)
      throw RunReadError(where() + ": more than " + format_g(kMaxFrames + 1) + " frames (a run writes at most " +
                         format_g(kMaxFrames) + " after t = 0)");
    const std::filesystem::path frame_file = run_dir / file;
    std::error_code ec;
    if (!std::filesystem::is_regular_file(frame_file, ec))  // a device or a pipe may never end
      throw RunReadError(where() + ": frame " + std::to_string(frames.size()) + " (t = " + format_g(time) +
                         " s): " + frame_file.string() + ": " +
                         (std::filesystem::exists(frame_file, ec) ? "not a regular file" : "missing") +
                         " (expected a frame written by 'weavelab run')");
    frames.push_back(read_vtu({frame_file, frames.size(), time}));
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
