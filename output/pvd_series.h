// A time series of frames for ParaView: dir/frames/<basename>_00000.vtu, ...
// plus dir/<basename>.pvd listing them. Every file is written atomically and
// the .pvd is rewritten after each frame, so an interrupted run leaves a valid
// series of the frames written so far.
#pragma once
#include <filesystem>
#include <string>
#include <vector>

#include "models/core/frame.h"

namespace wl {

class PvdSeries {
 public:
  // Creates dir/frames/ if needed and writes an empty collection dir/<basename>.pvd.
  // Throws std::runtime_error (with the path) if the folders cannot be created,
  // std::invalid_argument for an empty basename or one containing '/'.
  PvdSeries(std::filesystem::path dir, std::string basename);

  // Writes the next frame file, then the updated .pvd (timestep = frame.time).
  void add(const Frame& frame);

  int size() const { return static_cast<int>(times_.size()); }
  std::filesystem::path pvd_path() const;
  std::filesystem::path frame_path(int index) const;  // absolute-ish: dir/frames/<basename>_NNNNN.vtu
  std::string relative_frame_path(int index) const;   // as listed in the .pvd: frames/<basename>_NNNNN.vtu

 private:
  std::string pvd_text() const;
  std::filesystem::path dir_;
  std::string basename_;
  std::vector<double> times_;
};

}  // namespace wl
