#include "driver/fidelity.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <stdexcept>

#include "driver/experiment_meta.h"
#include "driver/fidelity_reference.h"
#include "driver/interrupted_record.h"
#include "driver/recorded_run.h"
#include "driver/time_error.h"
#include "models/fem/fem_model.h"
#include "models/fem/knit_contact_mesh.h"
#include "models/fem/tile_law_file.h"
#include "output/atomic_file.h"
#include "output/csv_table.h"
#include "output/json_writer.h"

namespace wl {
namespace {

const DataArray& point_array(const Frame& f, const std::string& name) {
  for (const DataArray& a : f.point_data)
    if (a.name == name) return a;
  throw std::logic_error("fidelity: frame without point data '" + name + "'");
}

// The points a ladder compares: a woven cloth's crossings at their current material coordinates
// (u, v); a knit's stitch contacts, each the midpoint of its two nodes, at its material point on
// the contact grid (docs/models.md §11.9).
class ComparedPoints {
 public:
  explicit ComparedPoints(const Scene& s) {
    if (s.knit) contacts_ = knit_grid_contacts(s);
  }
  FramePoints points(const Frame& f) const {
    return contacts_.empty() ? f.points : knit_contact_midpoints(contacts_, f.points);
  }
  // The points of a frame of `s`: its crossings, or the knit's stitch contacts.
  int count(const Scene& s) const {
    return contacts_.empty() ? s.nodes_u() * s.nodes_v() : static_cast<int>(contacts_.size());
  }
  std::vector<Vec2> uv(const Frame& f) const {
    std::vector<Vec2> uv;
    if (!contacts_.empty()) {
      for (const KnitGridContact& c : contacts_) uv.push_back(c.uv);
      return uv;
    }
    const DataArray &u = point_array(f, "u"), &v = point_array(f, "v");
    for (Eigen::Index n = 0; n < f.points.rows(); ++n) uv.emplace_back(u.values[n], v.values[n]);
    return uv;
  }

 private:
  std::vector<KnitGridContact> contacts_;
};

// Distances of one run to the reference, accumulated frame by frame.
class DistanceTally {
 public:
  // d[n] = distance at reference crossing n, NaN where the point is not compared.
  void add_frame(const std::vector<double>& d) {
    double sum = 0;
    int compared = 0;
    for (double x : d) {
      if (std::isnan(x)) continue;
      sum += x * x;
      max_ = std::max(max_, x);
      ++compared;
    }
    sum_ += sum;
    compared_ += compared;
    if (compared > 0) worst_frame_ = std::max(worst_frame_, std::sqrt(sum / compared));
  }
  void fill(FidelityRow& row, const ReferenceFrames& ref) const {
    row.rms_m = compared_ > 0 ? std::sqrt(sum_ / compared_) : NAN;
    row.worst_frame_rms_m = compared_ > 0 ? worst_frame_ : NAN;
    row.max_m = compared_ > 0 ? max_ : NAN;
    const double points = double(ref.x.size()) * ref.crossings();
    row.compared_fraction = points > 0 ? compared_ / points : 0.0;
  }

 private:
  double sum_ = 0, max_ = 0, worst_frame_ = 0;
  long compared_ = 0;
};

// Yarn variant: distance at the same crossing (same warp and weft).
std::vector<double> crossing_distances(const FramePoints& x, const FramePoints& ref) {
  std::vector<double> d(ref.rows());
  for (Eigen::Index n = 0; n < ref.rows(); ++n) d[n] = (x.row(n) - ref.row(n)).norm();
  return d;
}

// Continuum variant: distance to the surface at the crossing's material point;
// NaN where the crossing slid out of the mesh.
std::vector<double> surface_distances(const FemModel& geometry, const FramePoints& x, const FramePoints& ref,
                                      const std::vector<Vec2>& uv) {
  const Vec q = Eigen::Map<const Vec>(x.data(), x.size());
  std::vector<double> d(ref.rows(), NAN);
  for (Eigen::Index n = 0; n < ref.rows(); ++n) {
    Vec3 s;
    if (geometry.surface_point(q, uv[n], &s)) d[n] = (s - ref.row(n).transpose()).norm();
  }
  return d;
}

// Runs a scene `repeats` times: the first run's record (measured through
// `record`), with CPU and wall time the medians over all runs.
RecordedRun timed_runs(const Scene& s, const std::string& model, const RecordOptions& record, int repeats,
                       long max_steps = IntegratorOptions{}.max_steps) {
  IntegratorOptions options = scene_integrator_options(s);
  options.max_steps = max_steps;
  RecordedRun first = run_recorded(s, model, s.integrator, options, record);
  std::vector<double> cpu{first.cpu_s}, wall{first.wall_s};
  for (int i = 1; i < repeats && first.result.outcome == Outcome::ok; ++i) {
    RecordOptions timing_only;
    timing_only.stop_at_signal = true;
    const RecordedRun again = run_recorded(s, model, s.integrator, options, timing_only);
    cpu.push_back(again.cpu_s);
    wall.push_back(again.wall_s);
  }
  auto median = [](std::vector<double> x) {
    std::sort(x.begin(), x.end());
    const size_t n = x.size();
    return n % 2 ? x[n / 2] : 0.5 * (x[n / 2 - 1] + x[n / 2]);
  };
  first.cpu_s = median(cpu);
  first.wall_s = median(wall);
  return first;
}

FidelityRow row_of(const PlannedVariant& p, const RecordedRun& run) {
  FidelityRow r;
  r.variant = p.name;
  r.model = p.variant.model;
  r.same_as_full = p.variant.same_as_full;
  r.outcome = to_string(run.result.outcome);
  r.message = run.result.message;
  r.dofs = run.dofs;
  r.steps = run.stats.steps;
  r.cpu_s = run.cpu_s;
  r.wall_s = run.wall_s;
  return r;
}

// max_k |ΔE_run(t_k) − ΔE_ref(t_k)| with ΔE = (T + V)(t) − (T + V)(0): changes, so
// that each model's own zero of V (a term left out, another elastic energy) drops out.
double max_energy_difference(const RecordedRun& run, const ReferenceFrames& ref) {
  double m = 0;
  for (size_t k = 0; k < run.kinetic_J.size() && k < ref.energy_change.size(); ++k)
    m = std::max(m, std::abs(run.kinetic_J[k] + run.potential_J[k] - run.initial_energy_J - ref.energy_change[k]));
  return m;
}

// The run's own time error into the row (docs/models.md §7.8), when asked for.
void add_time_error(FidelityRow& row, const Scene& s, const std::string& model, const RecordedRun& run,
                    const FidelityConfig& c) {
  if (!c.error_estimate || run.result.outcome != Outcome::ok) return;
  if (c.progress) std::fprintf(stderr, "fidelity: %s time error\n", row.variant.c_str());
  const TimeErrorEstimate e = estimate_time_error(s, model, s.integrator, scene_integrator_options(s), run);
  throw_if_interrupted();  // the estimate ends its second run at a signal
  row.time_error_method = e.method;
  if (!e.ok()) {
    row.time_error_method += std::string(" (second run ") + to_string(e.second_run.outcome) + ")";
    return;
  }
  row.time_error_mean_rms_m = e.mean_rms;
  row.time_error_worst_frame_rms_m = *std::max_element(e.rms.begin(), e.rms.end());
}

Json choice_json(const FidelityChoice& c, double cloth_size) {
  Json j = Json::object();
  j.set("tolerance_m", c.tolerance_m);
  j.set("tolerance_of_cloth_size", c.tolerance_m / cloth_size);
  j.set("variant", c.variant);
  j.set("cpu_s", c.cpu_s);
  j.set("speedup_over_reference", c.speedup);
  return j;
}

}  // namespace

FidelityChoice cheapest_within(const std::vector<FidelityRow>& rows, double tolerance) {
  FidelityChoice c;
  c.tolerance_m = tolerance;
  const FidelityRow* best = nullptr;
  for (const FidelityRow& r : rows)
    if (r.complete() && r.worst_frame_rms_m <= tolerance && !(r.time_error_worst_frame_rms_m > tolerance) &&
        (!best || r.cpu_s < best->cpu_s))
      best = &r;
  if (best) {
    c.variant = best->variant;
    c.cpu_s = best->cpu_s;
    c.speedup = best->cpu_s > 0 ? rows.front().cpu_s / best->cpu_s : NAN;
  }
  return c;
}

std::vector<bool> pareto_front(const std::vector<double>& cost, const std::vector<double>& error) {
  std::vector<bool> front(cost.size(), true);
  for (size_t i = 0; i < cost.size(); ++i)
    for (size_t j = 0; j < cost.size() && front[i]; ++j)
      if (j != i && cost[j] <= cost[i] && error[j] <= error[i] && (cost[j] < cost[i] || error[j] < error[i]))
        front[i] = false;
  return front;
}

FidelityPlan plan_fidelity(const FidelityConfig& c) {
  FidelityPlan p;
  const Scene& s = c.scene;
  if (s.knit) {
    const KnitContactGrid g = knit_contact_grid(s);
    p.cloth_size_m = std::max(g.span_u(), g.span_v());
  } else {
    p.cloth_size_m = (std::max(s.wefts, s.warps) - 1) * s.spacing_m;
  }
  p.tolerance_m = c.tolerance_m.value_or(0.01 * p.cloth_size_m);
  if (!(p.tolerance_m > 0) || !std::isfinite(p.tolerance_m))
    throw std::invalid_argument("--tolerance: got " + std::to_string(p.tolerance_m) + ", expected a distance > 0 [m]");

  if (c.repeats < 1) throw std::invalid_argument("--repeats: got " + std::to_string(c.repeats) + ", expected ≥ 1");

  std::optional<FemMaterial> calibrated;
  Scene continuum_base = s;  // the scene the continuum variants start from
  if (c.fem_params) {
    Scene with_file = s;
    with_file.fem.parameter_file = c.fem_params->string();
    calibrated = fem_material(with_file);  // a bad file: FemParameterError
    p.calibration = "--fem-params " + c.fem_params->string();
    // A tile law is the continuum's law, not only its parameters: the variants run it (docs/models.md §6.9).
    if (is_tile_law_file(c.fem_params->string())) continuum_base.fem.tile_law = c.fem_params->string();
  } else if (!s.fem.parameter_file.empty() || !s.fem.tile_law.empty()) {
    calibrated = fem_material(s);
    p.calibration = !s.fem.parameter_file.empty() ? "the scene's [fem] parameter_file " + s.fem.parameter_file
                                                  : "the scene's [fem] tile_law " + s.fem.tile_law;
  }

  auto scene_of = [&](const std::string& option, const std::string& name) {
    try {
      VariantScene v = variant_scene(continuum_base, name, calibrated);
      if (!v.time_rung) v.scene = at_time_steps(v.scene, c.time_steps);
      if (name == "scene_step" && c.time_steps.scene) v.same_as_full = "the comparison runs at the scene's step";
      return v;
    } catch (const std::invalid_argument& e) {  // an unknown name
      throw std::invalid_argument(option + ": " + e.what());
    }
  };
  p.reference = {c.reference, scene_of("--reference", c.reference)};
  if (p.reference.variant.model == "fem")
    throw std::invalid_argument("--reference: got '" + c.reference +
                                "', expected a yarn-level variant (the distances are measured at its crossings)");

  const bool named = !c.variants.empty();
  for (const std::string& name : named ? c.variants : fidelity_variant_names()) {
    VariantScene v = scene_of("--variants", name);
    if (name == c.reference) continue;
    if (std::any_of(p.variants.begin(), p.variants.end(), [&](const PlannedVariant& q) { return q.name == name; }))
      throw std::invalid_argument("--variants: '" + name + "' is listed twice");
    if (!v.impossible.empty()) {
      if (named) throw std::invalid_argument("--variants: '" + name + "' cannot run on this scene: " + v.impossible);
      p.left_out.emplace_back(name, v.impossible);
      continue;
    }
    // A variant equal to the full model is run only when named (it then measures the noise floor).
    if (!named && !v.same_as_full.empty()) {
      p.left_out.emplace_back(name, "same as full: " + v.same_as_full);
      continue;
    }
    p.variants.push_back({name, std::move(v)});
  }
  return p;
}

namespace {

// 1. The reference: its crossings, material coordinates and energy at every
// frame into `ref`, and its row (the reference against itself), run here or
// read from the file of a --reference-only run.
FidelityRow reference_row(const FidelityConfig& c, const FidelityPlan& p, const ComparedPoints& compared,
                          RecordOptions rec, ReferenceFrames& ref) {
  if (c.reference_from) {
    FidelityReference stored = read_fidelity_reference(*c.reference_from, fidelity_reference_key(c));
    check_reference_frames(stored.frames, output_times(p.reference.variant.scene), compared.count(c.scene),
                           *c.reference_from);
    ref = std::move(stored.frames);
    if (c.progress)
      std::fprintf(stderr, "fidelity: reference %s read from %s\n", p.reference.name.c_str(),
                   c.reference_from->string().c_str());
    return stored.row;
  }
  rec.on_frame = [&](const Frame& f) {
    ref.times.push_back(f.time);
    ref.x.push_back(compared.points(f));
    ref.uv.push_back(compared.uv(f));
  };
  if (c.progress) std::fprintf(stderr, "fidelity: reference %s\n", p.reference.name.c_str());
  const Scene& rs = p.reference.variant.scene;
  const RecordedRun rr = timed_runs(rs, p.reference.variant.model, rec, c.repeats);
  if (rr.result.outcome != Outcome::ok)
    throw std::runtime_error("the reference '" + p.reference.name + "' ended '" + to_string(rr.result.outcome) +
                             "' at t = " + std::to_string(rr.end_time) + " s: " + rr.result.message);
  for (size_t k = 0; k < rr.kinetic_J.size(); ++k)
    ref.energy_change.push_back(rr.kinetic_J[k] + rr.potential_J[k] - rr.initial_energy_J);
  // the reference against itself, through the same measurement as every yarn variant
  FidelityRow row = row_of(p.reference, rr);
  DistanceTally tally;
  for (size_t k = 0; k < ref.x.size(); ++k) tally.add_frame(crossing_distances(ref.x[k], ref.x[k]));
  tally.fill(row, ref);
  row.energy_diff_J = max_energy_difference(rr, ref);
  add_time_error(row, rs, p.reference.variant.model, rr, c);
  if (c.progress && !std::isnan(row.time_error_worst_frame_rms_m))
    std::fprintf(stderr, "  reference time error: worst-frame RMS %.3g mm (mean %.3g mm)%s\n",
                 1e3 * row.time_error_worst_frame_rms_m, 1e3 * row.time_error_mean_rms_m,
                 row.time_error_worst_frame_rms_m > 0.1 * p.tolerance_m
                     ? ": above a tenth of the tolerance, distances that small do not measure a model difference"
                     : "");
  if (c.reference_only) write_fidelity_reference(c.out_dir, fidelity_reference_key(c), {ref, row});
  return row;
}

// 2. One variant, measured against the reference frame by frame as it runs.
FidelityRow variant_row(const FidelityConfig& c, const PlannedVariant& pv, const ComparedPoints& compared,
                        const RecordOptions& rec, const ReferenceFrames& ref, long reference_steps) {
  const Scene& vs = pv.variant.scene;
  const bool continuum = pv.variant.model == "fem";
  std::unique_ptr<FemModel> geometry = continuum ? std::make_unique<FemModel>(vs) : nullptr;
  DistanceTally tally;
  size_t k = 0;
  RecordOptions vr = rec;
  vr.label = pv.name;
  vr.on_frame = [&](const Frame& f) {
    if (k >= ref.x.size()) return;
    tally.add_frame(continuum ? surface_distances(*geometry, f.points, ref.x[k], ref.uv[k])
                              : crossing_distances(compared.points(f), ref.x[k]));
    ++k;
  };
  if (c.progress) std::fprintf(stderr, "fidelity: %s (%s)\n", pv.name.c_str(), pv.variant.model.c_str());
  // A rung that runs away under error control shrinks its steps instead of
  // leaving its bounds: it stops at 20× the reference's steps (outcome max_steps).
  const RecordedRun run = timed_runs(vs, pv.variant.model, vr, c.repeats, 20 * reference_steps + 1000);
  FidelityRow row = row_of(pv, run);
  tally.fill(row, ref);
  row.energy_diff_J = max_energy_difference(run, ref);
  add_time_error(row, vs, pv.variant.model, run, c);
  if (c.progress)
    std::fprintf(stderr,
                 "  %s: %s, %d DoFs, CPU %.3g s, worst-frame RMS %.3g mm, max %.3g mm; own time error %.3g mm\n",
                 pv.name.c_str(), row.outcome.c_str(), row.dofs, row.cpu_s, 1e3 * row.worst_frame_rms_m,
                 1e3 * row.max_m, 1e3 * row.time_error_worst_frame_rms_m);
  return row;
}

// The Pareto front of the complete rows (CPU time against worst-frame distance) and the cheapest
// variant within the tolerance, 1 % and 5 % of the cloth size.
void mark_front_and_choices(const FidelityPlan& p, FidelityResult& out) {
  std::vector<double> cost, error;
  std::vector<size_t> complete;
  for (size_t i = 0; i < out.rows.size(); ++i)
    if (out.rows[i].complete()) {
      complete.push_back(i);
      cost.push_back(out.rows[i].cpu_s);
      error.push_back(out.rows[i].worst_frame_rms_m);
    }
  const std::vector<bool> front = pareto_front(cost, error);
  for (size_t i = 0; i < complete.size(); ++i) out.rows[complete[i]].on_front = front[i];
  out.within_tolerance = cheapest_within(out.rows, p.tolerance_m);
  out.within_1_percent = cheapest_within(out.rows, 0.01 * p.cloth_size_m);
  out.within_5_percent = cheapest_within(out.rows, 0.05 * p.cloth_size_m);
}

Json row_json(const FidelityRow& r) {
  Json j = Json::object();
  j.set("variant", r.variant);
  j.set("model", r.model);
  j.set("outcome", r.outcome);
  j.set("message", r.message);
  j.set("dofs", r.dofs);
  j.set("steps", r.steps);
  j.set("cpu_s", r.cpu_s);
  j.set("wall_s", r.wall_s);
  j.set("rms_m", r.rms_m);
  j.set("worst_frame_rms_m", r.worst_frame_rms_m);
  j.set("max_m", r.max_m);
  j.set("energy_diff_J", r.energy_diff_J);
  j.set("compared_fraction", r.compared_fraction);
  if (!r.time_error_method.empty()) {
    Json te = Json::object();
    te.set("method", r.time_error_method);
    te.set("mean_rms_m", r.time_error_mean_rms_m);
    te.set("worst_frame_rms_m", r.time_error_worst_frame_rms_m);
    j.set("time_error", std::move(te));
  }
  j.set("on_front", r.on_front);
  if (!r.same_as_full.empty()) j.set("same_as_full", r.same_as_full);
  return j;
}

// fidelity.csv; the rows of fidelity.json.
Json write_fidelity_csv(const std::filesystem::path& out_dir, const std::vector<FidelityRow>& rows) {
  CsvTable csv(out_dir / "fidelity.csv",
               {"variant", "model", "dofs", "steps", "cpu_s", "wall_s", "rms_m", "worst_frame_rms_m", "max_m",
                "energy_diff_J", "compared_fraction", "time_error_method", "time_error_mean_rms_m",
                "time_error_worst_frame_rms_m", "outcome", "on_front", "same_as_full"});
  Json records = Json::array();
  for (const FidelityRow& r : rows) {
    csv.row({r.variant, r.model, std::to_string(r.dofs), std::to_string(r.steps), csv_number(r.cpu_s),
             csv_number(r.wall_s), csv_number(r.rms_m), csv_number(r.worst_frame_rms_m), csv_number(r.max_m),
             csv_number(r.energy_diff_J), csv_number(r.compared_fraction), r.time_error_method,
             csv_number(r.time_error_mean_rms_m), csv_number(r.time_error_worst_frame_rms_m), r.outcome,
             r.on_front ? "1" : "0", r.same_as_full});
    records.push(row_json(r));
  }
  csv.commit();
  return records;
}

// 3. Files: fidelity.csv and fidelity.json; with `interrupted_in`, the rows a signal left
// (driver/interrupted_record.h) without the choices, which need the whole ladder.
void write_fidelity(const FidelityConfig& c, const FidelityPlan& p, const FidelityResult& out,
                    const std::string& interrupted_in = "") {
  std::filesystem::create_directories(c.out_dir);
  Json rows = write_fidelity_csv(c.out_dir, out.rows);
  Json left_out = Json::array();
  for (const auto& [name, why] : p.left_out) left_out.push(Json::object().set("variant", name).set("reason", why));
  Json j = Json::object();
  if (!interrupted_in.empty()) mark_interrupted(j, interrupted_in);
  j.set("scene", scene_json(c.scene_path, c.scene.text, c.scene, c.overrides));
  j.set("scene_hash", text_hash(c.scene.text));
  j.set("reference", p.reference.name);
  j.set("resolution", c.time_steps.describe() + " for the reference and the model rungs; the time rungs at their own");
  j.set("time_errors", c.error_estimate ? "each run's own estimate (docs/models.md §7.8); a variant whose "
                                          "worst-frame time error exceeds the tolerance is not within it"
                                        : "not estimated (--no-error-estimate)");
  j.set("calibration", p.calibration.empty() ? "none: the calibrated continuum variants are left out" : p.calibration);
  j.set("cloth_size_m", p.cloth_size_m);
  j.set("repeats", c.repeats);
  j.set("timing", "cpu_s and wall_s: medians over the repeats of each run (process CPU time, all threads)");
  j.set("error_measure", "worst_frame_rms_m: the largest per-frame RMS distance to the reference crossings");
  if (interrupted_in.empty()) {
    j.set("cheapest_within_tolerance", choice_json(out.within_tolerance, p.cloth_size_m));
    j.set("cheapest_within_1_percent", choice_json(out.within_1_percent, p.cloth_size_m));
    j.set("cheapest_within_5_percent", choice_json(out.within_5_percent, p.cloth_size_m));
  }
  j.set("variants", std::move(rows));
  j.set("left_out", std::move(left_out));
  j.set("wall_s", out.wall_s);
  j.set("created", utc_now());
  add_provenance(j);
  write_file_atomically(c.out_dir / "fidelity.json", j.dump());
}

}  // namespace

FidelityResult run_fidelity(const FidelityConfig& c, const FidelityPlan& p) {
  using Clock = std::chrono::steady_clock;
  const auto t0 = Clock::now();
  FidelityResult out;
  for (const auto& [name, why] : p.left_out)  // also with --quiet: what the ladder lacks
    std::fprintf(stderr, "fidelity: %s left out: %s\n", name.c_str(), why.c_str());
  ReferenceFrames ref;
  const ComparedPoints compared(c.scene);
  RecordOptions rec;
  rec.progress = c.progress;
  rec.energies = true;
  rec.label = p.reference.name;
  rec.step_ends = true;  // for the Richardson time-error estimate
  rec.stop_at_signal = true;
  std::string stage = "the reference " + p.reference.name;
  try {
    out.rows.push_back(reference_row(c, p, compared, rec, ref));
    const long reference_steps = out.rows.front().steps;
    if (!c.reference_only)  // every variant (none after --reference-only)
      for (const PlannedVariant& pv : p.variants) {
        stage = "the variant " + pv.name;
        out.rows.push_back(variant_row(c, pv, compared, rec, ref, reference_steps));
      }
  } catch (const Interrupted&) {  // the rows complete so far
    out.wall_s = std::chrono::duration<double>(Clock::now() - t0).count();
    write_fidelity(c, p, out, stage);
    throw Interrupted{stage};
  }
  mark_front_and_choices(p, out);
  out.wall_s = std::chrono::duration<double>(Clock::now() - t0).count();
  write_fidelity(c, p, out);
  return out;
}

}  // namespace wl
