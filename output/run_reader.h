// Reads back the frames of a finished run folder (run.pvd and the ASCII .vtu
// files it lists, as written by PvdSeries and to_vtu): per frame its time, the
// points and, where present, the crossings' material coordinates (point data
// "u", "v"). Only the project's own output format is understood.
#pragma once
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <vector>

#include <Eigen/Core>

namespace wl {

struct RecordedFrame {
  double time = 0.0;
  Eigen::MatrixXd points;    // n × 3
  std::vector<double> u, v;  // per point, empty when the frame has no such arrays
};

class RunReadError : public std::invalid_argument {  // bad input: exit 2
 public:
  using std::invalid_argument::invalid_argument;
};

// Frames in the order of run.pvd; throws RunReadError naming the file (and the
// line, frame and point where there is one) and what is wrong: missing, not a
// run folder, not a regular file, malformed, a value that is not finite, times
// that do not increase, point counts that differ, more points than a scene may
// have (kMaxYarns²) or than the file can hold, more frames than a run writes
// (kMaxFrames after t = 0).
std::vector<RecordedFrame> read_run_frames(const std::filesystem::path& run_dir);

// The mean over frames of the RMS time error a run estimated (summary.json,
// "time_error": {"mean_rms_m": …}, written by `run --error-estimate`) [m];
// nullopt when the run has no summary or no estimate.
std::optional<double> read_run_time_error(const std::filesystem::path& run_dir);

}  // namespace wl
