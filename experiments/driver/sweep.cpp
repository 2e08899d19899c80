#include "experiments/driver/sweep.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "experiments/output/atomic_file.h"
#include "models/fem/fem_material.h"
#include "models/model_factory.h"

namespace wl {

std::vector<double> output_times(const Scene& scene) {
  const int outputs = std::max(1, static_cast<int>(std::llround(scene.duration_s / scene.output_interval_s)));
  std::vector<double> t;
  for (int k = 1; k <= outputs; ++k) t.push_back(std::min(scene.duration_s, k * scene.output_interval_s));
  if (t.back() < scene.duration_s - 1e-12) t.push_back(scene.duration_s);
  return t;
}

RecordedRun run_recorded(const Scene& scene, const std::string& model_name, const std::string& integrator_name,
                         const IntegratorOptions& options, const RecordOptions& record) {
  auto model = make_model(scene, model_name);
  auto integrator = make_integrator(integrator_name);
  IntegratorOptions opt = options;
  opt.runaway_speed = std::min(opt.runaway_speed, record.speed_bound);

  RecordedRun run;
  run.dofs = model->num_dofs();
  const std::vector<double> times = output_times(scene);
  const int nodes = static_cast<int>(model->frame(0.0, model->initial_q(), model->initial_v()).points.rows());
  run.trajectory.positions.resize(3 * nodes, static_cast<Eigen::Index>(times.size()));

  using clock = std::chrono::steady_clock;
  const auto start = clock::now();
  auto last_report = start;
  double cpu = 0.0, wall = 0.0;
  auto timed = [&](auto&& body) {
    const std::clock_t c0 = std::clock();
    const auto w0 = clock::now();
    body();
    cpu += double(std::clock() - c0) / CLOCKS_PER_SEC;
    wall += std::chrono::duration<double>(clock::now() - w0).count();
  };

  integrator->on_step = [&](const StepRecord& r) {
    const double s = model->max_node_speed(integrator->v());
    run.max_node_speed = std::max(run.max_node_speed, std::isfinite(s) ? s : std::numeric_limits<double>::infinity());
    if (record.progress) {
      const auto now = clock::now();
      if (std::chrono::duration<double>(now - last_report).count() >= 5.0) {
        last_report = now;
        std::fprintf(stderr, "    %s t = %.4g / %.4g s, %ld steps, %.0f s\n", record.label.c_str(), r.t,
                     scene.duration_s, integrator->stats().steps, std::chrono::duration<double>(now - start).count());
      }
    }
  };

  timed([&] { integrator->initialize(*model, 0.0, model->initial_q(), model->initial_v(), opt); });
  int reached = 0;
  Evaluation scratch;
  if (record.energies)
    run.initial_energy_J = kinetic_energy(*model, 0.0, model->initial_q(), model->initial_v(), scratch) +
                           model->potential_energy(model->initial_q());
  for (double t_out : times) {
    timed([&] { run.result = integrator->advance_to(t_out); });
    if (run.result.outcome == Outcome::ok && run.max_node_speed > record.speed_bound)
      run.result = {Outcome::diverged, "max node speed " + std::to_string(run.max_node_speed) +
                                           " m/s exceeds the bound " + std::to_string(record.speed_bound) + " m/s"};
    if (run.result.outcome != Outcome::ok) break;
    const Frame f = model->frame(integrator->t(), integrator->q(), integrator->v());
    run.trajectory.times.push_back(t_out);
    run.trajectory.positions.col(reached) = Eigen::Map<const Eigen::VectorXd>(f.points.data(), 3 * nodes);
    ++reached;
    if (record.energies) {
      run.kinetic_J.push_back(kinetic_energy(*model, integrator->t(), integrator->q(), integrator->v(), scratch));
      run.potential_J.push_back(model->potential_energy(integrator->q()));
    }
    if (record.on_frame) record.on_frame(f);
  }
  run.trajectory.positions.conservativeResize(Eigen::NoChange, reached);
  run.cpu_s = cpu;
  run.wall_s = wall;
  run.end_time = integrator->t();
  run.stats = integrator->stats();
  return run;
}

ErrorNorms trajectory_error(const Trajectory& run, const Trajectory& reference) {
  if (run.positions.rows() != reference.positions.rows())
    throw std::invalid_argument("trajectory_error: " + std::to_string(run.nodes()) + " nodes against " +
                                std::to_string(reference.nodes()) + " in the reference");
  if (run.times.size() != reference.times.size() || run.positions.cols() != reference.positions.cols())
    throw std::invalid_argument("trajectory_error: " + std::to_string(run.times.size()) + " output times against " +
                                std::to_string(reference.times.size()) + " in the reference");
  for (size_t k = 0; k < run.times.size(); ++k)
    if (std::abs(run.times[k] - reference.times[k]) > 1e-9 * std::max(1.0, std::abs(reference.times[k])))
      throw std::invalid_argument("trajectory_error: output time " + std::to_string(run.times[k]) + " against " +
                                  std::to_string(reference.times[k]) + " in the reference");
  ErrorNorms e;
  const int nodes = run.nodes();
  const Eigen::Index cols = run.positions.cols();
  if (nodes == 0 || cols == 0) return e;
  double sum = 0.0;
  for (Eigen::Index k = 0; k < cols; ++k)
    for (int n = 0; n < nodes; ++n) {
      const double d2 =
          (run.positions.col(k).segment<3>(3 * n) - reference.positions.col(k).segment<3>(3 * n)).squaredNorm();
      sum += d2;
      e.max = std::max(e.max, std::sqrt(d2));
    }
  e.rms = std::sqrt(sum / (double(nodes) * double(cols)));
  return e;
}

// ---- Reference ------------------------------------------------------------

std::string reference_key(const std::string& scene_text, const std::string& model_name,
                          const std::map<std::string, std::string>& overrides, const ReferenceOptions& options) {
  std::ostringstream key;
  key << "weavelab reference v1\nmodel=" << model_name << "\nintegrator=" << options.integrator << "\n";
  for (const auto& [k, v] : overrides) key << "override " << k << "=" << v << "\n";  // std::map: sorted
  key << "scene:\n" << scene_text;
  return key.str();
}

std::string reference_hash(const std::string& key) {
  std::uint64_t h = 14695981039346656037ull;  // FNV-1a 64
  for (unsigned char c : key) {
    h ^= c;
    h *= 1099511628211ull;
  }
  char buf[17];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(h));
  return buf;
}

namespace {

constexpr char kMagic[8] = {'W', 'L', 'R', 'E', 'F', '0', '1', '\0'};

template <class T>
void put(std::string& out, const T& x) {
  out.append(reinterpret_cast<const char*>(&x), sizeof(T));
}

template <class T>
bool get(std::istream& in, T& x) {
  return static_cast<bool>(in.read(reinterpret_cast<char*>(&x), sizeof(T)));
}

std::string format_g(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", x);
  return buf;
}

}  // namespace

void write_reference_file(const std::filesystem::path& path, const std::string& key, const Reference& ref) {
  std::string out;
  out.append(kMagic, sizeof kMagic);
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
  if (!in.read(magic, 8) || std::memcmp(magic, kMagic, 8) != 0) return false;
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
  ref.hash = reference_hash(key);
  ref.file = options.cache_dir / (ref.hash + ".bin");
  const std::vector<double> times = output_times(scene);
  if (read_reference_file(ref.file, key, ref)) {
    bool same = ref.trajectory.times.size() == times.size();
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

// ---- Stability ------------------------------------------------------------

StabilityLimit find_stability_limit(const std::function<StabilityProbe(double dt)>& probe, double dt_min, double dt_max,
                                    int bisections) {
  if (!(dt_min > 0) || !(dt_max > dt_min))
    throw std::invalid_argument("find_stability_limit: need 0 < dt_min < dt_max, got " + format_g(dt_min) + ", " +
                                format_g(dt_max));
  StabilityLimit lim;
  auto run = [&](double dt) {
    StabilityProbe p = probe(dt);
    lim.probes.emplace_back(dt, p);
    return p;
  };
  StabilityProbe top = run(dt_max);
  if (top.bounded) {
    lim.largest_stable_dt = dt_max;
    return lim;
  }
  lim.smallest_unstable_dt = dt_max;
  lim.failure = top;
  double lo = std::log(dt_min), hi = std::log(dt_max);
  bool found_bounded = false;
  for (int i = 0; i < bisections; ++i) {
    const double mid = 0.5 * (lo + hi), dt = std::exp(mid);
    StabilityProbe p = run(dt);
    if (p.bounded) {
      lo = mid;
      found_bounded = true;
      lim.largest_stable_dt = dt;
    } else {
      hi = mid;
      lim.smallest_unstable_dt = dt;
      lim.failure = p;
    }
  }
  if (!found_bounded) {
    StabilityProbe p = run(dt_min);
    if (p.bounded) {
      lim.largest_stable_dt = dt_min;
    } else {
      lim.smallest_unstable_dt = dt_min;
      lim.failure = p;
    }
  }
  return lim;
}

Scene scale_stretch(const Scene& scene, double factor) {
  Scene s = scene;
  const FemMaterial base = fem_material(scene);
  for (auto& [name, type] : s.yarn_types) type.stretch_modulus_Pa *= factor;
  s.fem.warp_stretch_N_per_m = factor * base.warp_stretch_N_per_m;
  s.fem.weft_stretch_N_per_m = factor * base.weft_stretch_N_per_m;
  return s;
}

std::string read_text_file(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot read '" + path.string() + "'");
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

}  // namespace wl
