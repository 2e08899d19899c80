#include "driver/calibrate.h"

#include "driver/time_error.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <numeric>
#include <sstream>
#include <stdexcept>
#include <thread>

#include "calibration/fem_test_patch.h"
#include "calibration/first_guess.h"
#include "calibration/knit_test_patch.h"
#include "driver/experiment_meta.h"
#include "driver/interrupt.h"
#include "driver/recorded_run.h"
#include "driver/run_settings.h"
#include "models/fem/fem_model.h"
#include "models/fem/tile_law_file.h"
#include "models/model_factory.h"
#include "output/atomic_file.h"
#include "output/csv_table.h"
#include "output/json_writer.h"

namespace wl {
namespace {

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

// Reads a whole text file; throws std::runtime_error naming the path.
std::string read_text_file(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot read '" + path.string() + "'");
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// The yarn crossings of one output frame: positions and material coordinates (u, v).
struct CrossingFrame {
  Eigen::MatrixXd x;  // n × 3
  std::vector<Vec2> uv;
};

struct VariantRun {
  std::string name;
  std::vector<double> times, rms, max;
  RecordedRun run;
};

// Yarn-vs-continuum distance per frame, at each crossing's material point
// (the continuum surface interpolated in the triangle that holds (u, v)).
VariantRun run_continuum_variant(const std::string& name, const Scene& scene, const std::vector<CrossingFrame>& yarn,
                                 const IntegratorOptions& iopt, bool progress) {
  VariantRun v;
  v.name = name;
  const FemModel geometry(scene);
  size_t k = 0;
  RecordOptions rec;
  rec.progress = progress;
  rec.label = name;
  rec.step_ends = true;  // for its time error estimate
  rec.on_step = [](Model&, double, const Vec&, const Vec&) { throw_if_interrupted(); };
  rec.on_frame = [&](const Frame& f) {
    if (k >= yarn.size()) return;
    Vec q(3 * f.points.rows());
    for (Eigen::Index i = 0; i < f.points.rows(); ++i) q.segment<3>(3 * i) = f.points.row(i).transpose();
    double sum = 0, mx = 0;
    int compared = 0;
    const CrossingFrame& y = yarn[k];
    for (Eigen::Index n = 0; n < y.x.rows(); ++n) {
      Vec3 s;
      if (!geometry.surface_point(q, y.uv[n], &s)) continue;  // a crossing slid out of the mesh: not compared
      const double d = (s - y.x.row(n).transpose()).norm();
      sum += d * d;
      mx = std::max(mx, d);
      ++compared;
    }
    v.times.push_back(f.time);
    v.rms.push_back(compared > 0 ? std::sqrt(sum / compared) : NAN);
    v.max.push_back(mx);
    ++k;
  };
  v.run = run_recorded(scene, "fem", scene.integrator, iopt, rec);
  return v;
}

}  // namespace

Scene with_material(Scene s, const FemMaterial& m, bool border_strip) {
  s.fem.tile_law = tile_law_path(s.fem);  // the law stays: m holds its parameters, not its terms
  s.fem.parameter_file.clear();
  s.fem.border_strip = border_strip;
  s.fem.areal_density_kg_per_m2 = m.areal_density_kg_per_m2;
  s.fem.warp_stretch_N_per_m = m.warp_stretch_N_per_m;
  s.fem.weft_stretch_N_per_m = m.weft_stretch_N_per_m;
  s.fem.shear_N_per_m = m.shear_N_per_m;
  s.fem.shear_lock_angle_rad = m.shear_lock_angle_rad;
  s.fem.shear_lock_exponent = m.shear_lock_exponent;
  s.fem.warp_bending_N_m = m.warp_bending_N_m;
  s.fem.weft_bending_N_m = m.weft_bending_N_m;
  s.fem.diagonal_bending_N_m.reset();
  if (m.diagonal_bending_N_m > 0) s.fem.diagonal_bending_N_m = m.diagonal_bending_N_m;
  auto optional = [](double v) { return v > 0 ? std::optional<double>(v) : std::nullopt; };
  s.fem.stretch_coupling_N_per_m = optional(m.stretch_coupling_N_per_m);
  s.fem.warp_stretch_quartic_N_per_m = optional(m.warp_stretch_quartic_N_per_m);
  s.fem.weft_stretch_quartic_N_per_m = optional(m.weft_stretch_quartic_N_per_m);
  s.fem.areal_stretch_quartic_N_per_m = optional(m.areal_stretch_quartic_N_per_m);
  s.fem.shear_law = m.shear_knots_rad.empty() ? FemSettings::ShearLaw::linear_lock : FemSettings::ShearLaw::spline;
  s.fem.shear_knots_rad = m.shear_knots_rad;
  for (int i = 0; i < FemSettings::kMaxShearKnots; ++i) {
    s.fem.shear_knot_N_per_m[i].reset();
    if (i < static_cast<int>(m.shear_knots_rad.size()) && m.shear_knot_N_per_m[i] > 0)
      s.fem.shear_knot_N_per_m[i] = m.shear_knot_N_per_m[i];
  }
  return s;
}

namespace {

double curve_range(const std::vector<double>& r) {
  double m = 0.0;
  for (double x : r) m = std::max(m, std::abs(x));
  return m;
}

double mean(const std::vector<double>& x) {
  return x.empty() ? 0.0 : std::accumulate(x.begin(), x.end(), 0.0) / x.size();
}
double maximum(const std::vector<double>& x) { return x.empty() ? 0.0 : *std::max_element(x.begin(), x.end()); }
double cpu_per_step(const RecordedRun& r) { return r.stats.steps > 0 ? r.cpu_s / r.stats.steps : 0.0; }

// The parameter file holds the knot values; the law and its knot angles belong in the scene.
std::string shear_law_note(const FemMaterial& m) {
  if (m.shear_knots_rad.empty()) return "linear_lock";
  std::ostringstream k;
  k.precision(17);
  for (size_t i = 0; i < m.shear_knots_rad.size(); ++i) k << (i ? ", " : "") << m.shear_knots_rad[i];
  return "fitted with [fem] shear_law = \"spline\" and shear_knots_rad = [" + k.str() + "]: set them in the scene";
}

}  // namespace

double matched_areal_density(const Scene& s) { return yarn_matched_areal_density(s); }

CalibratePlan plan_calibration(const CalibrateConfig& c) {
  CalibratePlan p;
  p.scene = load_scene(c.scene_path.string());
  p.scene_text = read_text_file(c.scene_path);
  if (p.scene.knit) {
    // Knit patches (docs/calibration.md §8): what has no knit counterpart yet is refused.
    const std::string knit = "calibrate: " + c.scene_path.string() + " is knitted ([cloth.pattern]): ";
    if (!c.validate.empty())
      throw std::invalid_argument(
          knit +
          "--validate: not offered for knits, expected none (measure the calibrated continuum on "
          "a knit scene with `weavelab fidelity --fem-params`, docs/calibration.md §8)");
    if (c.border_strip)
      throw std::invalid_argument(knit + "--border-strip: a woven border's half spacing, expected without it");
    if (c.grid_line_bending)
      throw std::invalid_argument(knit +
                                  "--grid-line-bending: its line widths assume one crossing spacing, the contact grid "
                                  "has two (W/2, C); expected hinge bending");
  }
  const int size =
      p.scene.knit ? std::min(p.scene.knit->courses, p.scene.knit->wales) : std::min(p.scene.warps, p.scene.wefts);
  const int patch = c.patch > 0    ? c.patch
                    : p.scene.knit ? default_knit_patch(p.scene, std::min(size, 33))
                                   : std::max(std::min(size, 33), minimum_patch(p.scene));
  p.test_scene = material_test_scene(p.scene, patch, c.sliding);  // too small: invalid_argument
  for (const std::string& model : {yarn_level_model(p.test_scene), std::string("fem")})
    if (const auto expected = memory_shortfall(p.test_scene, model))  // before any allocation: exit 2
      throw SettingError(c.patch > 0 ? "--patch" : "the default patch", std::to_string(patch), *expected);
  p.test_scene.fem.border_strip = c.border_strip;
  p.test_scene.fem.grid_line_bending = c.grid_line_bending;
  std::vector<std::string> names = c.tests.empty() ? default_test_names() : c.tests;
  for (const std::string& name : names) {
    TestSpec t = test_spec(name);  // unknown: invalid_argument
    const TestKind kind = t.kind;
    if (p.scene.knit && t.rotated && in_plane(kind))
      throw std::invalid_argument("--tests " + name + ": " + c.scene_path.string() +
                                  " is knitted, and its in-plane tests hold every node's z (docs/calibration.md §8): "
                                  "expected it unrotated");
    for (const TestSpec& other : p.tests)
      if (test_name(other) == test_name(t)) throw std::invalid_argument("--tests: '" + name + "' is listed twice");
    t.ladder = p.scene.knit ? default_knit_ladder(kind, p.test_scene) : default_ladder(kind, patch, p.scene.spacing_m);
    if (auto it = c.ladders.find(name); it != c.ladders.end()) t.ladder = it->second;
    if (t.ladder.size() < 2) throw std::invalid_argument("--ladder " + name + ": need at least 2 loads");
    for (size_t i = 0; i < t.ladder.size(); ++i)
      if (!(t.ladder[i] > 0) || !std::isfinite(t.ladder[i]) || (i > 0 && !(t.ladder[i] > t.ladder[i - 1])))
        throw std::invalid_argument("--ladder " + name + ": got " + std::to_string(t.ladder[i]) + " at position " +
                                    std::to_string(i + 1) + ", expected increasing finite loads > 0 [" +
                                    load_unit(kind) + "]");
    if (kind == TestKind::shear && t.ladder.back() >= 1.5)
      throw std::invalid_argument("--ladder shear: shear angles must stay below 1.5 rad, got " +
                                  std::to_string(t.ladder.back()));
    p.tests.push_back(t);
  }
  for (const auto& [name, ladder] : c.ladders) {
    const std::string canonical = test_name(test_spec(name));  // unknown: invalid_argument
    if (std::none_of(p.tests.begin(), p.tests.end(), [&](const TestSpec& t) { return test_name(t) == canonical; }))
      throw std::invalid_argument("--ladder " + name + ": the test is not among --tests");
  }
  if (!c.shear_knots_rad.empty()) {
    const auto& k = c.shear_knots_rad;
    if (k.size() > FemSettings::kMaxShearKnots)
      throw std::invalid_argument("--shear-spline: got " + std::to_string(k.size()) + " knots, expected at most " +
                                  std::to_string(FemSettings::kMaxShearKnots));
    for (size_t i = 0; i < k.size(); ++i)
      if (!(k[i] > (i ? k[i - 1] : 0.0)) || k[i] > 1.5)
        throw std::invalid_argument("--shear-spline: got " + std::to_string(k[i]) + " at position " +
                                    std::to_string(i + 1) + ", expected increasing shear angles in (0, 1.5] rad");
  }
  auto has = [&](TestKind kind) {
    return std::any_of(p.tests.begin(), p.tests.end(), [&](const TestSpec& t) { return t.kind == kind; });
  };
  if (c.stretch_coupling && !has(TestKind::biaxial))
    throw std::invalid_argument("--stretch-coupling: no test informs the coupling, expected biaxial among --tests");
  if (c.stretch_stiffening && !has(TestKind::uniaxial_warp) && !has(TestKind::uniaxial_weft) && !has(TestKind::biaxial))
    throw std::invalid_argument(
        "--stretch-stiffening: no test informs it, expected uniaxial-warp, uniaxial-weft or biaxial among --tests");
  FemMaterial probe;
  for (const std::string& key : c.fit.free) (void)material_value(probe, key);  // unknown: invalid_argument
  if (c.fit.loss != "none" && c.fit.loss != "huber" && c.fit.loss != "cauchy")
    throw std::invalid_argument("--loss: got '" + c.fit.loss + "', expected none, huber or cauchy");
  if (c.fit.residuals != "range" && c.fit.residuals != "relative")
    throw std::invalid_argument("--residuals: got '" + c.fit.residuals + "', expected range or relative");
  if (c.fit.starts < 1) throw std::invalid_argument("--starts: need at least 1, got " + std::to_string(c.fit.starts));
  // A bad parameter file is reported before anything runs (a knit's continuum has no material
  // without one: only the file is read, docs/models.md §11.9).
  if (!p.scene.knit) {
    (void)fem_material(p.scene);
  } else if (!p.scene.fem.parameter_file.empty()) {
    FemMaterial law;
    law.shear_knots_rad = p.scene.fem.shear_knots_rad;
    (void)read_fem_parameter_file(p.scene.fem.parameter_file, law);
  }
  for (const auto& v : c.validate) {
    p.validation_scenes.push_back(at_time_steps(load_scene(v.string()), c.time_steps));
    // Its initial state, as `run` checks it (a node inside an obstacle: invalid_argument), before anything is written.
    const Scene& vs = p.validation_scenes.back();
    check_run_memory(vs, yarn_level_model(vs));
    (void)make_model(vs, yarn_level_model(vs));
    p.validation_texts.push_back(read_text_file(v));
  }
  return p;
}

namespace {

// Equilibrium solves that end at their Newton iteration (or descent step) on SIGINT or SIGTERM.
EquilibriumOptions stoppable() {
  EquilibriumOptions o;
  o.stop_requested = [] { return interrupt_signal() != 0; };
  return o;
}

// The yarn level's response per test: the fit's targets, and R(0) per test (knits).
struct YarnCurves {
  std::vector<FitCurve> curves;
  std::vector<double> at_rest;  // R(0) per test: knits (docs/calibration.md §8)
};

// 1. The yarn-level tests; a test that does not converge far enough to fit is a std::runtime_error.
YarnCurves yarn_level_curves(const CalibrateConfig& c, const CalibratePlan& p) {
  // The tests run at once, one per hardware thread as the fit's starts; the curves do not depend on it.
  const int threads = c.fit.threads > 0 ? c.fit.threads : static_cast<int>(std::thread::hardware_concurrency());
  std::vector<ResponsePoint> rests;
  const std::vector<ResponseCurve> yarn_curves = run_yarn_tests(
      p.test_scene, p.tests, threads,
      [&](int k, const ResponseCurve& r) {
        if (c.progress)
          std::fprintf(stderr, "  yarn %-14s %zu/%zu loads%s %s\n", test_name(p.tests[k]).c_str(), r.points.size(),
                       p.tests[k].ladder.size(), r.complete ? "" : ", stopped:", r.message.c_str());
      },
      &rests, stoppable());
  throw_if_interrupted();
  YarnCurves out;
  for (size_t k = 0; k < p.tests.size(); ++k) {
    const TestSpec& t = p.tests[k];
    const ResponseCurve& r = yarn_curves[k];
    const ResponsePoint& rest = rests[k];  // R(0) of a knit
    if (r.points.size() < 2) throw std::runtime_error("yarn-level test did not converge: " + r.message);
    FitCurve fc{{t.kind, {}, t.rotated}, {}};
    // A knit's target is the change from its self-stressed rest shape, R(λ) − R(0)
    // (docs/calibration.md §8); a woven patch is stress-free at rest (R(0) is not solved for).
    for (const ResponsePoint& pt : r.points) {
      fc.test.ladder.push_back(pt.load);
      fc.target.push_back(p.scene.knit ? pt.response - rest.response : pt.response);
    }
    if (p.scene.knit && c.progress)
      std::fprintf(stderr, "       %-14s R(0) = %.4g %s, %.3g %% of the curve's range\n", "", rest.response,
                   response_unit(t.kind).c_str(), 100 * std::abs(rest.response) / curve_range(fc.target));
    out.at_rest.push_back(rest.response);
    out.curves.push_back(fc);
  }
  return out;
}

FirstGuessOptions first_guess_options(const CalibrateConfig& c) {
  FirstGuessOptions o;
  o.diagonal_bending = c.diagonal_bending;
  o.stretch_coupling = c.stretch_coupling;
  o.stretch_stiffening = c.stretch_stiffening;
  o.shear_knots_rad = c.shear_knots_rad;
  return o;
}

void print_fit(const FitResult& fit, const std::vector<FitCurve>& curves, double fit_s) {
  std::fprintf(stderr, "  fit: %s (cost %.4g, %d iterations, %d curve evaluations, %.1f s)\n",
               fit.converged ? "converged" : "NOT converged", fit.cost, fit.iterations, fit.evaluations, fit_s);
  for (size_t i = 0; i < curves.size(); ++i)
    std::fprintf(stderr, "    %-14s residual %.3g %% of the curve's range\n", test_name(curves[i].test).c_str(),
                 100 * fit.relative_rms[i]);
}

// curves.csv: per test and load the yarn, fitted and first-guess response.
void write_curves_csv(const std::filesystem::path& out_dir, const std::vector<FitCurve>& curves,
                      const std::vector<ResponseCurve>& first, const FitResult& fit) {
  CsvTable csv(out_dir / "curves.csv", {"test", "load", "load_unit", "yarn", "fitted", "first_guess", "response_unit"});
  for (size_t i = 0; i < curves.size(); ++i)
    for (size_t k = 0; k < curves[i].target.size(); ++k) {
      const TestKind kind = curves[i].test.kind;
      const double fg = k < first[i].points.size() ? first[i].points[k].response : NAN;
      csv.row({test_name(curves[i].test), csv_number(curves[i].test.ladder[k]), load_unit(kind),
               csv_number(curves[i].target[k]), csv_number(fit.fitted[i][k]), csv_number(fg), response_unit(kind)});
    }
  csv.commit();
}

// The yarn level of a validation scene: its run and its crossings per frame.
struct YarnValidation {
  RecordedRun run;
  std::vector<CrossingFrame> frames;
};

YarnValidation run_yarn_validation(const Scene& vs, const std::string& label, const IntegratorOptions& iopt,
                                   bool progress) {
  YarnValidation y;
  RecordOptions rec;
  rec.progress = progress;
  rec.label = label + " yarn";
  rec.step_ends = true;
  rec.on_step = [](Model&, double, const Vec&, const Vec&) { throw_if_interrupted(); };
  rec.on_frame = [&](const Frame& f) {
    CrossingFrame cf;
    cf.x = f.points;
    const DataArray *u = nullptr, *v = nullptr;
    for (const DataArray& a : f.point_data) {
      if (a.name == "u") u = &a;
      if (a.name == "v") v = &a;
    }
    for (Eigen::Index n = 0; n < f.points.rows(); ++n) cf.uv.emplace_back(u->values[n], v->values[n]);
    y.frames.push_back(std::move(cf));
  };
  if (progress) std::fprintf(stderr, "  validation %s: yarn level\n", label.c_str());
  y.run = run_recorded(vs, yarn_level_model(vs), vs.integrator, iopt, rec);
  if (y.run.result.outcome != Outcome::ok)
    throw std::runtime_error("validation " + label + ": the yarn-level run ended '" + to_string(y.run.result.outcome) +
                             "': " + y.run.result.message);
  return y;
}

// One continuum variant of a validation scene against its yarn level: its rows of validation.csv and its record.
Json validate_variant(const CalibrateConfig& c, const Scene& vs, const std::string& label, const std::string& name,
                      const FemMaterial& m, const YarnValidation& yarn, const TimeErrorEstimate& yarn_error,
                      CsvTable& vcsv) {
  const IntegratorOptions iopt = scene_integrator_options(vs);
  if (c.progress) std::fprintf(stderr, "  validation %s: continuum, %s\n", label.c_str(), name.c_str());
  Scene variant_scene = with_material(vs, m, c.border_strip && name != "first_guess");
  variant_scene.fem.grid_line_bending = c.grid_line_bending && name != "first_guess";
  const VariantRun vr = run_continuum_variant(name, variant_scene, yarn.frames, iopt, c.progress);
  const TimeErrorEstimate fem_error = estimate_time_error(variant_scene, "fem", vs.integrator, iopt, vr.run);
  throw_if_interrupted();  // the estimate ends its second run at a signal
  for (size_t k = 0; k < vr.times.size(); ++k)
    vcsv.row({label, name, csv_number(vr.times[k]), csv_number(vr.rms[k]), csv_number(vr.max[k])});
  const RecordedRun& yr = yarn.run;
  Json j = Json::object();
  j.set("variant", name);
  j.set("outcome", to_string(vr.run.result.outcome));
  j.set("areal_density_kg_per_m2", m.areal_density_kg_per_m2);
  j.set("mean_rms_m", mean(vr.rms));
  j.set("max_rms_m", maximum(vr.rms));
  j.set("max_m", maximum(vr.max));
  j.set("cpu_s_per_step", cpu_per_step(vr.run));
  j.set("step_time_ratio_to_yarn", cpu_per_step(yr) > 0 ? cpu_per_step(vr.run) / cpu_per_step(yr) : NAN);
  j.set("time_error", fem_error.to_json());
  const std::string budget = error_budget_verdict(mean(vr.rms), yarn_error, fem_error);
  j.set("budget", budget);
  if (c.progress)
    std::fprintf(stderr,
                 "    %s: RMS distance mean %.3g mm, worst frame %.3g mm, max %.3g mm; time error yarn %.3g mm, "
                 "continuum %.3g mm (mean RMS): %s\n",
                 name.c_str(), 1e3 * mean(vr.rms), 1e3 * maximum(vr.rms), 1e3 * maximum(vr.max),
                 1e3 * yarn_error.mean_rms, 1e3 * fem_error.mean_rms, budget.c_str());
  return j;
}

// Validation scene `s`: the yarn level, then the continuum at the first guess, with the calibrated
// stiffness only, and fully calibrated (the areal density matched to the scene's yarn mass).
Json validate_scene(const CalibrateConfig& c, const CalibratePlan& p, size_t s, const FemMaterial& calibrated,
                    CsvTable& vcsv) {
  const Scene& vs = p.validation_scenes[s];
  const std::string label = c.validate[s].stem().string();
  const IntegratorOptions iopt = scene_integrator_options(vs);
  const YarnValidation yarn = run_yarn_validation(vs, label, iopt, c.progress);
  FemMaterial stiff_only = calibrated;
  stiff_only.areal_density_kg_per_m2 = default_fem_material(vs).areal_density_kg_per_m2;
  FemMaterial full = calibrated;
  full.areal_density_kg_per_m2 = matched_areal_density(vs);
  const std::vector<std::pair<std::string, FemMaterial>> variants{
      {"first_guess", default_fem_material(vs)}, {"calibrated_stiffness", stiff_only}, {"calibrated", full}};
  Json entry = Json::object();
  entry.set("scene", c.validate[s].string());
  entry.set("scene_hash", text_hash(p.validation_texts[s]));
  entry.set("resolution", c.time_steps.describe());
  entry.set("frames", static_cast<int>(yarn.frames.size()));
  entry.set("yarn_cpu_s_per_step", cpu_per_step(yarn.run));
  // Each side's time error beside the distance (docs/models.md §7.8).
  if (c.progress) std::fprintf(stderr, "  validation %s: yarn-level time error\n", label.c_str());
  const TimeErrorEstimate yarn_error = estimate_time_error(vs, yarn_level_model(vs), vs.integrator, iopt, yarn.run);
  throw_if_interrupted();
  entry.set("yarn_time_error", yarn_error.to_json());
  Json vars = Json::array();
  for (const auto& [name, m] : variants) vars.push(validate_variant(c, vs, label, name, m, yarn, yarn_error, vcsv));
  entry.set("variants", std::move(vars));
  return entry;
}

// 4. Validation on motion: validation.csv and the records of calibration.json, one per scene
// validated. On a signal validation.csv is closed with the rows so far and Interrupted passes on.
void validate_on_motion(const CalibrateConfig& c, const CalibratePlan& p, const FemMaterial& calibrated,
                        Json& validation) {
  if (p.validation_scenes.empty()) return;
  CsvTable vcsv(c.out_dir / "validation.csv", std::vector<std::string>{"scene", "variant", "time_s", "rms_m", "max_m"});
  try {
    for (size_t s = 0; s < p.validation_scenes.size(); ++s) validation.push(validate_scene(c, p, s, calibrated, vcsv));
  } catch (const Interrupted&) {
    vcsv.commit();
    throw;
  }
  vcsv.commit();
}

// params.toml: the calibrated parameters with their provenance.
void write_params_toml(const CalibrateConfig& c, const CalibratePlan& p, const std::vector<FitCurve>& curves,
                       const FitResult& fit, const FemMaterial& calibrated, int patch) {
  std::ostringstream rms;
  for (size_t i = 0; i < curves.size(); ++i)
    rms << (i ? ", " : "") << test_name(curves[i].test) << " " << fit.relative_rms[i];
  write_fem_parameter_file(
      (c.out_dir / "params.toml").string(), calibrated,
      {{"source_scene", c.scene_path.string()},
       {"source_scene_hash", text_hash(p.scene_text)},
       {"git_revision", git_revision()},
       {"patch",
        std::to_string(patch) + " x " + std::to_string(patch) + (p.scene.knit ? " courses x wales (knit)" : "")},
       {"border_strip", c.border_strip ? "fitted with [fem] border_strip = true: set it in the scene" : "false"},
       {"grid_line_bending",
        c.grid_line_bending ? "fitted with [fem] grid_line_bending = true: set it in the scene" : "false"},
       {"shear_law", shear_law_note(calibrated)},
       {"residual_rms_relative", rms.str()},
       {"areal_density", p.scene.knit ? "yarn mass of the knit test patch over its contact grid's area"
                                      : "total yarn mass of the scene over the crossing grid's area"},
       {"created", utc_now()}});
}

// calibration.json "parameters": the fitted keys, then the areal density (not fitted).
Json calibrated_parameters_json(const FitResult& fit, const FemMaterial& guess, const FemMaterial& calibrated) {
  Json params = Json::array();
  for (const FittedParameter& fp : fit.parameters) {
    Json e = Json::object();
    e.set("key", fp.key);
    e.set("start", fp.start);
    e.set("value", fp.value);
    e.set("std_error", fp.std_error);
    e.set("at_bound", fp.at_bound);
    e.set("lower", fp.lower);
    e.set("upper", fp.upper);
    e.set("weakly_determined", fp.weakly_determined);
    e.set("start_spread", fp.start_spread);
    params.push(std::move(e));
  }
  Json density = Json::object();
  density.set("key", "areal_density_kg_per_m2");
  density.set("start", guess.areal_density_kg_per_m2);
  density.set("value", calibrated.areal_density_kg_per_m2);
  density.set("std_error", nullptr);
  density.set("at_bound", false);
  density.set(
      "note",
      "not fitted: static tests cannot see mass; set so that the continuum carries the yarn level's total mass");
  params.push(std::move(density));
  return params;
}

// calibration.json "tests": per test its points and residual, and a knit's R(0).
Json tests_json(const YarnCurves& yarn, const FitResult& fit, bool knit) {
  const std::vector<FitCurve>& curves = yarn.curves;
  Json tests = Json::array();
  for (size_t i = 0; i < curves.size(); ++i) {
    Json e = Json::object();
    e.set("test", test_name(curves[i].test));
    e.set("points", static_cast<int>(curves[i].target.size()));
    e.set("residual_rms_relative", fit.relative_rms[i]);
    if (knit) {  // R(0), and relative to the range of the fit's target R − R(0)
      e.set("response_at_rest", yarn.at_rest[i]);
      e.set("response_at_rest_relative", yarn.at_rest[i] / curve_range(curves[i].target));
    }
    e.set("load_unit", load_unit(curves[i].test.kind));
    e.set("response_unit", response_unit(curves[i].test.kind));
    tests.push(std::move(e));
  }
  return tests;
}

Json starts_json(const FitResult& fit) {
  Json starts = Json::array();
  for (const StartOutcome& s : fit.starts) {
    Json e = Json::object();
    e.set("start", Json(s.start));
    e.set("value", Json(s.value));
    e.set("cost", s.cost);
    e.set("iterations", s.iterations);
    e.set("usable", s.usable);
    starts.push(std::move(e));
  }
  return starts;
}

Json fit_json(const CalibrateConfig& c, const FitResult& r) {
  Json fit = Json::object();
  fit.set("converged", r.converged);
  fit.set("interrupted", r.interrupted);
  fit.set("message", r.message);
  fit.set("cost", r.cost);
  fit.set("iterations", r.iterations);
  fit.set("curve_evaluations", r.evaluations);
  fit.set("loss", c.fit.loss);
  fit.set("residuals", c.fit.residuals);
  fit.set("seed", static_cast<int>(c.fit.seed));
  return fit;
}

Json timings_json(const CalibrateSummary& out) {
  Json timing = Json::object();
  timing.set("yarn_tests_wall_s", out.yarn_tests_s);
  timing.set("fem_tests_wall_s", out.fem_tests_s);
  timing.set("fit_wall_s", out.fit_s);
  timing.set("fit_cpu_s", out.fit.cpu_s);
  timing.set("validation_wall_s", out.validation_s);
  return timing;
}

std::string outcome_of(const CalibrateSummary& s) {
  return !s.interrupted_in.empty() ? "interrupted" : s.fit.converged ? "converged" : "not_converged";
}

// calibration.json of a calibration a signal ended before its fit was whole: what it
// reached (the starts as far as they got), no parameters.
void write_interrupted_json(const CalibrateConfig& c, const CalibratePlan& p, const CalibrateSummary& s, int patch) {
  Json j = Json::object();
  j.set("outcome", outcome_of(s));
  j.set("interrupted_in", s.interrupted_in);
  j.set("message", interrupted_message(interrupt_signal()));
  j.set("scene", scene_json(c.scene_path, p.scene_text, p.scene, {}));
  j.set("scene_hash", text_hash(p.scene_text));
  j.set("patch", patch);
  j.set("cloth", p.scene.knit ? "knit" : "woven");
  Json tests = Json::array();
  for (const TestSpec& t : p.tests) tests.push(test_name(t));
  j.set("tests", std::move(tests));
  if (s.fit.interrupted) {
    j.set("starts", starts_json(s.fit));
    j.set("fit", fit_json(c, s.fit));
  }
  j.set("timings", timings_json(s));
  j.set("created", utc_now());
  add_provenance(j);
  std::filesystem::create_directories(c.out_dir);
  write_file_atomically(c.out_dir / "calibration.json", j.dump());
}

// What calibration.json holds beside the validation records.
struct CalibrationRecord {
  const YarnCurves& yarn;
  const FemMaterial &guess, &calibrated;
  const CalibrateSummary& summary;
  int patch;
};

void write_calibration_json(const CalibrateConfig& c, const CalibratePlan& p, const CalibrationRecord& r,
                            Json validation) {
  const FitResult& fit = r.summary.fit;
  Json j = Json::object();
  j.set("outcome", outcome_of(r.summary));
  if (!r.summary.interrupted_in.empty()) {
    j.set("interrupted_in", r.summary.interrupted_in);
    j.set("message", interrupted_message(interrupt_signal()));
  }
  j.set("scene", scene_json(c.scene_path, p.scene_text, p.scene, {}));
  j.set("scene_hash", text_hash(p.scene_text));
  j.set("patch", r.patch);
  j.set("cloth", p.scene.knit ? "knit" : "woven");
  j.set("sliding", c.sliding);
  j.set("border_strip", c.border_strip);
  j.set("grid_line_bending", c.grid_line_bending);
  j.set("shear_knots_rad", Json(r.calibrated.shear_knots_rad));
  j.set("parameters", calibrated_parameters_json(fit, r.guess, r.calibrated));
  Json corr = Json::array();
  for (const auto& row : fit.correlation) corr.push(Json(row));
  j.set("correlation", std::move(corr));
  j.set("covariance_note", fit.covariance_message.empty()
                               ? "ceres::Covariance (DENSE_SVD) of log-parameters times the residual variance"
                               : fit.covariance_message);
  j.set("singular_values", Json(fit.singular_values));
  j.set("tests", tests_json(r.yarn, fit, p.scene.knit.has_value()));
  j.set("starts", starts_json(fit));
  j.set("starts_at_best", fit.starts_at_best);
  j.set("fit", fit_json(c, fit));
  j.set("timings", timings_json(r.summary));
  j.set("validation", std::move(validation));
  j.set("created", utc_now());
  add_provenance(j);
  write_file_atomically(c.out_dir / "calibration.json", j.dump());
}

}  // namespace

CalibrateSummary run_calibration(const CalibrateConfig& c, const CalibratePlan& p) {
  CalibrateSummary out;
  const int patch = p.test_scene.knit ? p.test_scene.knit->courses : p.test_scene.warps;
  if (c.progress)
    std::fprintf(stderr, "calibrate: %zu tests on a %d x %d %spatch of %s\n", p.tests.size(), patch, patch,
                 p.test_scene.knit ? "(courses x wales) knit " : "", c.scene_path.string().c_str());
  // On SIGINT or SIGTERM each stage ends at its current equilibrium iteration, Ceres iteration or
  // time step and calibration.json records the stage with outcome `interrupted`.
  std::string stage = "the yarn-level tests";
  try {
    auto t0 = Clock::now();
    const YarnCurves yarn = yarn_level_curves(c, p);  // 1. the yarn level
    out.yarn_tests_s = seconds_since(t0);

    // 2. Continuum tests at the first guess (also the time of one evaluation of every test).
    stage = "the continuum tests";
    const FemMaterial guess = continuum_first_guess(p.scene, p.test_scene, yarn.curves, first_guess_options(c));
    FemTestPatches patches(p.test_scene);  // kept over the fit's curve evaluations
    const EquilibriumOptions equilibrium = stoppable();
    const ContinuumTest continuum = [&](const FemMaterial& m, const TestSpec& t, const std::vector<std::string>& keys) {
      return patches.run(m, t, keys, equilibrium);
    };
    t0 = Clock::now();
    std::vector<ResponseCurve> first;
    for (const FitCurve& fc : yarn.curves) first.push_back(continuum(guess, fc.test, {}));
    out.fem_tests_s = seconds_since(t0);
    throw_if_interrupted();

    // 3. Fit.
    stage = "the fit";
    t0 = Clock::now();
    FitOptions fo = c.fit;
    fo.progress = c.progress;
    fo.stop_requested = [] { return interrupt_signal() != 0; };
    out.fit = fit_continuum(yarn.curves, guess, continuum, fo);
    out.fit_s = seconds_since(t0);
    if (out.fit.interrupted) throw Interrupted{};
    FemMaterial calibrated = out.fit.material;
    calibrated.areal_density_kg_per_m2 =
        p.scene.knit ? knit_areal_density(p.test_scene) : matched_areal_density(p.scene);
    if (c.progress) print_fit(out.fit, yarn.curves, out.fit_s);
    std::filesystem::create_directories(c.out_dir);
    write_curves_csv(c.out_dir, yarn.curves, first, out.fit);
    write_params_toml(c, p, yarn.curves, out.fit, calibrated, patch);

    stage = "the validation";
    t0 = Clock::now();
    Json validation = Json::array();
    try {
      validate_on_motion(c, p, calibrated, validation);  // 4. validation on motion
    } catch (const Interrupted&) {
      out.interrupted_in = stage;  // the fit is whole: the full record with the scenes validated so far
    }
    out.validation_s = seconds_since(t0);
    write_calibration_json(c, p, {yarn, guess, calibrated, out, patch}, std::move(validation));
  } catch (const Interrupted&) {
    out.interrupted_in = stage;
    write_interrupted_json(c, p, out, patch);
  }
  return out;
}

}  // namespace wl
