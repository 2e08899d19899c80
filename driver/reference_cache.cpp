#include "driver/reference_cache.h"

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "driver/experiment_meta.h"
#include "models/model_factory.h"
#include "output/atomic_file.h"
#include "output/binary_io.h"

namespace wl {

std::string reference_key(const std::string& scene_text, const std::string& model_name,
                          const std::map<std::string, std::string>& overrides, const ReferenceOptions& options) {
  std::ostringstream key;
  key << "weavelab reference v1\nmodel=" << model_name << "\nintegrator=" << options.integrator << "\n";
  for (const auto& [k, v] : overrides) key << "override " << k << "=" << v << "\n";  // std::map: sorted
  key << "scene:\n" << scene_text;
  return key.str();
}

namespace {

constexpr char kReferenceMagic[8] = {'W', 'L', 'R', 'E', 'F', '0', '1', '\0'};

std::string format_g(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", x);
  return buf;
}

// The points of a frame of the model (its nodes): a trajectory has 3 rows per point.
Eigen::Index frame_points(const Scene& scene, const std::string& model_name) {
  const std::unique_ptr<Model> model = make_model(scene, model_name);
  return model->frame(0.0, model->initial_q(), model->initial_v()).points.rows();
}

}  // namespace

void write_reference_file(const std::filesystem::path& path, const std::string& key, const Reference& ref) {
  std::string out;
  out.append(kReferenceMagic, sizeof kReferenceMagic);
  put<std::uint64_t>(out, key.size());
  out += key;
  put(out, ref.rtol);
  put(out, ref.atol);
  put(out, ref.cpu_s);
  const auto& tr = ref.trajectory;
  put<std::uint64_t>(out, tr.times.size());
  put<std::uint64_t>(out, static_cast<std::uint64_t>(tr.positions.rows()));
  for (double t : tr.times) put(out, t);
  out.append(reinterpret_cast<const char*>(tr.positions.data()), sizeof(double) * tr.positions.size());
  if (path.has_parent_path()) std::filesystem::create_directories(path.parent_path());
  write_file_atomically(path, out);
}

bool read_reference_file(const std::filesystem::path& path, const std::string& key, Reference& ref) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return false;
  char magic[8];
  if (!in.read(magic, 8) || std::memcmp(magic, kReferenceMagic, 8) != 0) return false;
  std::uint64_t key_len = 0, times = 0, rows = 0;
  if (!get(in, key_len) || key_len != key.size()) return false;
  std::string stored(key_len, '\0');
  if (!in.read(stored.data(), static_cast<std::streamsize>(key_len)) || stored != key) return false;
  Reference r;
  if (!get(in, r.rtol) || !get(in, r.atol) || !get(in, r.cpu_s) || !get(in, times) || !get(in, rows)) return false;
  if (times > (1u << 24) || rows > (1u << 28) || times * rows > (1u << 28)) return false;
  r.trajectory.times.resize(times);
  for (auto& t : r.trajectory.times)
    if (!get(in, t)) return false;
  r.trajectory.positions.resize(static_cast<Eigen::Index>(rows), static_cast<Eigen::Index>(times));
  if (!in.read(reinterpret_cast<char*>(r.trajectory.positions.data()),
               static_cast<std::streamsize>(sizeof(double) * rows * times)))
    return false;
  if (in.peek() != std::char_traits<char>::eof()) return false;  // trailing bytes: not our file
  ref.trajectory = std::move(r.trajectory);
  ref.rtol = r.rtol;
  ref.atol = r.atol;
  ref.cpu_s = r.cpu_s;
  return true;
}

Reference load_or_compute_reference(const Scene& scene, const std::string& scene_text, const std::string& model_name,
                                    const std::map<std::string, std::string>& overrides,
                                    const ReferenceOptions& options) {
  const std::string key = reference_key(scene_text, model_name, overrides, options);
  Reference ref;
  ref.required_rtol = options.required_rtol;
  ref.hash = text_hash(key);
  ref.file = options.cache_dir / (ref.hash + ".bin");
  const std::vector<double> times = output_times(scene);
  if (read_reference_file(ref.file, key, ref)) {
    // The file holds this scene's trajectory: its output times, its model's points, finite.
    bool same = ref.trajectory.times.size() == times.size() &&
                ref.trajectory.positions.rows() == 3 * frame_points(scene, model_name) &&
                ref.trajectory.positions.allFinite();
    for (size_t k = 0; same && k < times.size(); ++k) same = std::abs(ref.trajectory.times[k] - times[k]) < 1e-12;
    if (same) {
      ref.from_cache = true;
      if (options.progress)
        std::fprintf(stderr, "  reference %s (%s, rtol %g) read from %s\n", model_name.c_str(),
                     options.integrator.c_str(), ref.rtol, ref.file.string().c_str());
      return ref;
    }
  }
  for (double rtol : options.rtols) {
    IntegratorOptions opt;
    opt.adaptive = true;
    opt.rtol = rtol;
    opt.atol = rtol * options.atol_per_rtol;
    opt.dt = options.initial_dt;
    opt.max_steps = options.max_steps;
    if (options.progress)
      std::fprintf(stderr, "  reference %s: %s at rtol %g, atol %g ...\n", model_name.c_str(),
                   options.integrator.c_str(), opt.rtol, opt.atol);
    RecordOptions rec;
    rec.progress = options.progress;
    rec.label = "reference " + model_name;
    rec.stop_at_signal = true;
    RecordedRun run = run_recorded(scene, model_name, options.integrator, opt, rec);
    std::string attempt = "rtol=" + format_g(rtol) + ": " + to_string(run.result.outcome);
    if (!run.result.message.empty()) attempt += ": " + run.result.message;
    ref.attempts.push_back(attempt);
    if (options.progress)
      std::fprintf(stderr, "  reference %s: %s (%.1f s CPU)\n", model_name.c_str(), attempt.c_str(), run.cpu_s);
    if (run.result.outcome != Outcome::ok) continue;
    ref.trajectory = std::move(run.trajectory);
    ref.rtol = opt.rtol;
    ref.atol = opt.atol;
    ref.cpu_s = run.cpu_s;
    write_reference_file(ref.file, key, ref);
    return ref;
  }
  std::string all;
  for (const auto& a : ref.attempts) all += "\n  " + a;
  throw std::runtime_error("no reference for the " + model_name + " model: " + options.integrator +
                           " converged at none of the tolerances tried:" + all);
}

}  // namespace wl
