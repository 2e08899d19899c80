// The reference of a fidelity ladder kept in a file, so that the ladder's rungs
// can run as separate jobs (experiments/fidelity/Snakefile, docs/design.md
// §7.5): `weavelab fidelity --reference-only` writes it, `--reference-from DIR`
// reads it instead of running the reference again. A rung measured against the
// file gives bit for bit the row it gets in one process.
#pragma once
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "driver/fidelity.h"
#include "models/core/frame.h"

namespace wl {

using FramePoints = decltype(Frame::points);  // crossings × 3, row-major

// The reference's crossings at its output frames: positions, current material
// coordinates (u, v) and the change of its total energy T + V since t = 0.
struct ReferenceFrames {
  std::vector<double> times;  // of the frames [s]
  std::vector<FramePoints> x;
  std::vector<std::vector<Vec2>> uv;
  std::vector<double> energy_change;  // (T + V)(t_k) − (T + V)(0) [J]
  int crossings() const { return x.empty() ? 0 : static_cast<int>(x.front().rows()); }
};

struct FidelityReference {
  ReferenceFrames frames;
  FidelityRow row;  // the reference measured against itself, as in fidelity.csv
};

// What the frames depend on: the scene text, the command-line overrides, the
// reference variant and the comparison's time steps.
std::string fidelity_reference_key(const FidelityConfig& config);

// <dir>/reference.bin, written atomically. Format (little-endian, as held here):
//   char[8] "WLFID02\0"; key (u64 length, bytes); the row: strings variant, model,
//   outcome, message, same_as_full, time_error_method; i64 dofs, steps; f64 cpu_s,
//   wall_s, rms_m, worst_frame_rms_m, max_m, energy_diff_J, compared_fraction,
//   time_error_mean_rms_m, time_error_worst_frame_rms_m; u64 frames, crossings;
//   per frame f64 time, f64 x[crossings × 3] (row-major), f64 uv[crossings × 2],
//   f64 energy_change.
void write_fidelity_reference(const std::filesystem::path& dir, const std::string& key, const FidelityReference& ref);

// Reads <dir>/reference.bin; throws std::invalid_argument naming the file when
// it is missing, not such a file, or written for another key (another scene,
// overrides, reference or time steps).
FidelityReference read_fidelity_reference(const std::filesystem::path& dir, const std::string& key);

// The frames a reference of the scene has: one at each output time, each of
// `crossings` compared points, every value finite. Throws std::invalid_argument
// naming <dir>/reference.bin and what differs (a file whose key matches but
// whose frames do not: damaged or written by other code).
void check_reference_frames(const ReferenceFrames& frames, const std::vector<double>& output_times, int crossings,
                            const std::filesystem::path& dir);

}  // namespace wl
