#include "driver/fidelity_reference.h"

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "output/atomic_file.h"
#include "output/binary_io.h"

namespace wl {
namespace {

constexpr char kFidelityMagic[8] = {'W', 'L', 'F', 'I', 'D', '0', '2', '\0'};
constexpr char kOldMagic[8] = {'W', 'L', 'F', 'I', 'D', '0', '1', '\0'};  // without the frame times
constexpr const char* kFile = "reference.bin";

void put_row(std::string& out, const FidelityRow& r) {
  for (const std::string* s : {&r.variant, &r.model, &r.outcome, &r.message, &r.same_as_full, &r.time_error_method})
    put_string(out, *s);
  put<std::int64_t>(out, r.dofs);
  put<std::int64_t>(out, r.steps);
  for (double x : {r.cpu_s, r.wall_s, r.rms_m, r.worst_frame_rms_m, r.max_m, r.energy_diff_J, r.compared_fraction,
                   r.time_error_mean_rms_m, r.time_error_worst_frame_rms_m})
    put(out, x);
}

bool get_row(std::istream& in, FidelityRow& r) {
  for (std::string* s : {&r.variant, &r.model, &r.outcome, &r.message, &r.same_as_full, &r.time_error_method})
    if (!get_string(in, *s)) return false;
  std::int64_t dofs = 0, steps = 0;
  if (!get(in, dofs) || !get(in, steps)) return false;
  r.dofs = static_cast<int>(dofs);
  r.steps = static_cast<long>(steps);
  for (double* x : {&r.cpu_s, &r.wall_s, &r.rms_m, &r.worst_frame_rms_m, &r.max_m, &r.energy_diff_J,
                    &r.compared_fraction, &r.time_error_mean_rms_m, &r.time_error_worst_frame_rms_m})
    if (!get(in, *x)) return false;
  return true;
}

}  // namespace

std::string fidelity_reference_key(const FidelityConfig& c) {
  std::ostringstream key;
  key << "weavelab fidelity reference v1\nreference=" << c.reference << "\nresolution=" << c.time_steps.describe()
      << "\n";
  for (const auto& [k, v] : c.overrides) key << "override " << k << "=" << v << "\n";  // std::map: sorted
  key << "scene:\n" << c.scene.text;
  return key.str();
}

void write_fidelity_reference(const std::filesystem::path& dir, const std::string& key, const FidelityReference& ref) {
  const ReferenceFrames& f = ref.frames;
  std::string out(kFidelityMagic, sizeof kFidelityMagic);
  put_string(out, key);
  put_row(out, ref.row);
  put<std::uint64_t>(out, f.x.size());
  put<std::uint64_t>(out, static_cast<std::uint64_t>(f.crossings()));
  for (size_t k = 0; k < f.x.size(); ++k) {
    put(out, f.times[k]);
    out.append(reinterpret_cast<const char*>(f.x[k].data()), sizeof(double) * f.x[k].size());
    for (const Vec2& uv : f.uv[k]) put(out, uv);
    put(out, f.energy_change[k]);
  }
  std::filesystem::create_directories(dir);
  write_file_atomically(dir / kFile, out);
}

FidelityReference read_fidelity_reference(const std::filesystem::path& dir, const std::string& key) {
  const std::filesystem::path path = dir / kFile;
  auto fail = [&](const std::string& why) {
    return std::invalid_argument("--reference-from: " + path.string() + ": " + why);
  };
  std::ifstream in(path, std::ios::binary);
  if (!in) throw fail("cannot be read (written by `weavelab fidelity --reference-only --out DIR`)");
  char magic[8];
  if (in.read(magic, 8) && std::memcmp(magic, kOldMagic, 8) == 0)
    throw fail("written by an older weavelab (without frame times): write it again with --reference-only");
  if (!in || std::memcmp(magic, kFidelityMagic, 8) != 0) throw fail("not a fidelity reference file");
  std::string stored;
  if (!get_string(in, stored)) throw fail("truncated");
  if (stored != key) throw fail("written for another scene, overrides, reference or time steps than this command's");
  FidelityReference ref;
  std::uint64_t frames = 0, crossings = 0;
  if (!get_row(in, ref.row) || !get(in, frames) || !get(in, crossings) || frames > (1u << 24) || crossings > (1u << 24))
    throw fail("truncated");
  ReferenceFrames& f = ref.frames;
  for (std::uint64_t k = 0; k < frames; ++k) {
    FramePoints x(static_cast<Eigen::Index>(crossings), 3);
    std::vector<Vec2> uv(crossings);
    double e = 0, t = 0;
    bool ok = get(in, t) && static_cast<bool>(in.read(reinterpret_cast<char*>(x.data()), sizeof(double) * x.size()));
    for (Vec2& p : uv) ok = ok && get(in, p);
    if (!ok || !get(in, e)) throw fail("truncated");
    f.times.push_back(t);
    f.x.push_back(std::move(x));
    f.uv.push_back(std::move(uv));
    f.energy_change.push_back(e);
  }
  if (in.peek() != std::char_traits<char>::eof()) throw fail("trailing bytes: not a fidelity reference file");
  return ref;
}

void check_reference_frames(const ReferenceFrames& f, const std::vector<double>& output_times, int crossings,
                            const std::filesystem::path& dir) {
  auto fail = [&](const std::string& why) {
    return std::invalid_argument("--reference-from: " + (dir / kFile).string() + ": " + why +
                                 " (a file of this scene's key that does not hold its reference: write it again with "
                                 "--reference-only)");
  };
  if (f.x.size() != output_times.size() || f.crossings() != crossings)
    throw fail("holds " + std::to_string(f.x.size()) + " frames of " + std::to_string(f.crossings()) +
               " compared points, the scene's reference has " + std::to_string(output_times.size()) +
               " frames (its output times) of " + std::to_string(crossings));
  for (size_t k = 0; k < f.x.size(); ++k) {
    const double dt = output_times[k] - (k ? output_times[k - 1] : 0.0);
    if (!(std::abs(f.times[k] - output_times[k]) <= 1e-9 * dt)) {
      char why[160];
      std::snprintf(why, sizeof why, "frame %zu is at t = %.12g s, the scene's output time is %.12g s", k, f.times[k],
                    output_times[k]);
      throw fail(why);
    }
    bool finite = std::isfinite(f.energy_change[k]) && f.x[k].allFinite();
    for (const Vec2& uv : f.uv[k]) finite = finite && uv.allFinite();
    if (!finite) throw fail("frame " + std::to_string(k) + " holds a value that is not finite");
  }
}

}  // namespace wl
