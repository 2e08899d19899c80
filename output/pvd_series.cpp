#include "output/pvd_series.h"

#include <cstdio>
#include <stdexcept>
#include <system_error>

#include "output/atomic_file.h"
#include "output/vtu_writer.h"

namespace wl {

PvdSeries::PvdSeries(std::filesystem::path dir, std::string basename)
    : dir_(std::move(dir)), basename_(std::move(basename)) {
  if (basename_.empty() || basename_.find('/') != std::string::npos)
    throw std::invalid_argument("PvdSeries: basename '" + basename_ + "' must be a non-empty file name without '/'");
  std::error_code ec;
  std::filesystem::create_directories(dir_ / "frames", ec);
  if (ec) throw std::runtime_error("cannot create folder '" + (dir_ / "frames").string() + "': " + ec.message());
  write_file_atomically(pvd_path(), pvd_text());
}

std::filesystem::path PvdSeries::pvd_path() const { return dir_ / (basename_ + ".pvd"); }

std::string PvdSeries::relative_frame_path(int index) const {
  char number[16];
  std::snprintf(number, sizeof number, "%05d", index);
  return "frames/" + basename_ + "_" + number + ".vtu";
}

std::filesystem::path PvdSeries::frame_path(int index) const { return dir_ / relative_frame_path(index); }

void PvdSeries::add(const Frame& frame) {
  const int index = size();
  write_file_atomically(frame_path(index), to_vtu(frame));
  times_.push_back(frame.time);
  write_file_atomically(pvd_path(), pvd_text());
}

std::string PvdSeries::pvd_text() const {
  std::string out;
  out += "<?xml version=\"1.0\"?>\n";
  out += "<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n";
  out += "  <Collection>\n";
  for (int k = 0; k < size(); ++k) {
    char time[32];
    std::snprintf(time, sizeof time, "%.17g", times_[k]);
    out += "    <DataSet timestep=\"";
    out += time;
    out += "\" group=\"\" part=\"0\" file=\"";
    out += xml_escape(relative_frame_path(k));
    out += "\"/>\n";
  }
  out += "  </Collection>\n";
  out += "</VTKFile>\n";
  return out;
}

}  // namespace wl
