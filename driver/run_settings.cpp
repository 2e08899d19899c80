#include "driver/run_settings.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <limits>
#include <utility>

#include "driver/memory_estimate.h"
#include "integrators/amg_preconditioner.h"
#include "integrators/integrator.h"
#include "models/fem/fem_material.h"

namespace wl {
namespace {

std::string shortest(double x) {
  char buf[64];
  const auto res = std::to_chars(buf, buf + sizeof buf, x);
  return std::string(buf, res.ptr);
}

// Bound on the step matrix's entries per DoF (the yarn grid has about 37).
constexpr int kMaxPatternEntriesPerDof = 64;

// Scene key → (command-line option, key in the override record).
struct Overridable {
  const char* key;
  const char* option;
  const char* record;
};
constexpr Overridable kOverridable[] = {
    {"time.duration_s", "--duration", "duration_s"},
    {"time.dt_s", "--dt", "dt_s"},
    {"time.output_interval_s", "--output-interval", "output_interval_s"},
    {"time.rtol", "--rtol", "rtol"},
    {"time.atol", "--rtol", "rtol"},
    {"time.integrator", "--integrator", "integrator"},
    {"time.adaptive", "--adaptive", "adaptive"},
    {"time.linear_solver", "--linear-solver", "linear_solver"},
};

const Overridable* overridden(const std::string& key, const std::map<std::string, std::string>& record) {
  for (const auto& o : kOverridable)
    if (key == o.key && record.count(o.record)) return &o;
  return nullptr;
}

[[noreturn]] void fail(const Scene& scene, const std::map<std::string, std::string>& record, const std::string& key,
                       const std::string& value, const std::string& expected) {
  if (const Overridable* o = overridden(key, record)) {
    if (key == "time.atol")  // set by --rtol: atol = 1e-3·rtol
      throw SettingError(o->option, record.at(o->record),
                         "a tolerance whose atol = 1e-3·rtol is " + expected + " (it gives " + value + ")");
    throw SettingError(o->option, value, expected);
  }
  const auto line = scene.key_lines.find(key);
  if (line != scene.key_lines.end()) throw SceneError(scene.source, line->second, key, value, expected);
  const auto table = scene.key_lines.find(key.substr(0, key.find('.')));
  throw SceneError(scene.source, table != scene.key_lines.end() ? table->second : 1, key, value + " (the default)",
                   expected);
}

// Adaptive steps (--adaptive, --rtol or the scene's [time] adaptive = true) ask for
// error control, which the integrator must declare (IntegratorCapabilities::controls_error);
// one without it would run fixed steps while the record says adaptive.
void check_error_control(const Scene& scene, const std::map<std::string, std::string>& record) {
  if (!scene.adaptive || make_integrator(scene.integrator)->capabilities().controls_error) return;
  std::string controlled;
  for (const auto& n : integrator_names())
    if (make_integrator(n)->capabilities().controls_error) controlled += (controlled.empty() ? "" : ", ") + n;
  const std::string none = scene.integrator + " has none (it would run fixed steps of dt); choose one of " + controlled;
  if (record.count("adaptive")) {
    const bool rtol = record.count("rtol") > 0;
    throw SettingError(rtol ? "--rtol" : "--adaptive", rtol ? record.at("rtol") : "true",
                       "an integrator with error control: " + none + ", or drop the option");
  }
  if (record.count("integrator"))  // the scene's adaptive = true under the command line's integrator
    fail(scene, record, "time.integrator", "\"" + scene.integrator + "\"",
         "an integrator with error control, as the scene's [time] adaptive = true asks: " + none);
  fail(scene, record, "time.adaptive", "true",
       "false under " + scene.integrator +
           ", which has no error control (it would run fixed steps of dt); "
           "or an integrator with one: " +
           controlled);
}

}  // namespace

SettingError::SettingError(const std::string& option, const std::string& value, const std::string& expected)
    : std::invalid_argument("option '" + option + "': got " + value + ", expected " + expected) {}

void check_run_settings(const Scene& scene, const std::map<std::string, std::string>& record) {
  const auto rank = [&](const std::string& key) {
    return overridden(key, record) ? 2 : scene.key_lines.count(key) ? 1 : 0;
  };
  if (const auto bad = time_settings_violation(scene, rank)) fail(scene, record, bad->key, bad->value, bad->expected);
  const auto names = integrator_names();
  if (std::find(names.begin(), names.end(), scene.integrator) == names.end()) {
    std::string known;
    for (const auto& n : names) known += (known.empty() ? "" : ", ") + n;
    fail(scene, record, "time.integrator", "\"" + scene.integrator + "\"", "one of " + known);
  }
  check_error_control(scene, record);
  // The settling phase changes the step of a run under way (docs/models.md §3.11.6).
  if (scene.settle_dt_s > 0.0 && !make_integrator(scene.integrator)->capabilities().replays_steps)
    fail(scene, record, "time.settle_dt_s", shortest(scene.settle_dt_s),
         "no settling phase under " + scene.integrator +
             ": it needs an integrator of our own fixed steps "
             "(be-linear, be-newton, sdirk2, symplectic)");
  const auto solvers = linear_solver_names();
  if (std::find(solvers.begin(), solvers.end(), scene.linear_solver) == solvers.end()) {
    std::string known;
    for (const auto& n : solvers) known += (known.empty() ? "" : ", ") + n;
    fail(scene, record, "time.linear_solver", "\"" + scene.linear_solver + "\"", "one of " + known);
  }
  if (scene.linear_solver == "amg" && !amg_available())
    fail(scene, record, "time.linear_solver", "\"amg\"",
         "auto, umfpack, cholmod or gmres: amg needs hypre and this weavelab was built without it "
         "(Debian libhypre-dev, then configure again)");
}

void check_linear_solver(const Scene& scene, const Model& model, const std::map<std::string, std::string>& record) {
  const auto terms = model.asymmetric_terms();
  if (scene.linear_solver != "cholmod" || terms.empty()) return;
  std::string names;
  for (const auto& t : terms) names += (names.empty() ? "" : ", ") + t;
  fail(scene, record, "time.linear_solver", "\"cholmod\"",
       "auto, umfpack, gmres or amg: cholmod needs a symmetric step matrix and this " + model.name() +
           " model's is not (terms " + names + ")");
}

std::optional<std::string> memory_shortfall(const Scene& scene, const std::string& model_name) {
  const MemoryEstimate e = estimate_run_memory(scene, model_name);
  const double available = available_memory_bytes();
  const auto gb = [](double b) { return shortest(std::round(b / 1e8) / 10.0) + " GB"; };
  if (e.bytes > available)
    return "a cloth that fits in memory: the " + model_name + " model has " + std::to_string(e.dofs) +
           " DoFs and needs about " + gb(e.bytes) + ", " + gb(available) + " available";
  // The model's sparsity pattern has 32-bit indices (the factorizations' are 64-bit).
  if (static_cast<double>(e.dofs) * kMaxPatternEntriesPerDof > std::numeric_limits<int>::max())
    return "at most " + std::to_string(std::numeric_limits<int>::max() / kMaxPatternEntriesPerDof) +
           " DoFs (32-bit sparse pattern); the " + model_name + " model has " + std::to_string(e.dofs);
  return std::nullopt;
}

void check_run_memory(const Scene& scene, const std::string& model_name) {
  const auto expected = memory_shortfall(scene, model_name);
  if (!expected) return;
  if (scene.knit)
    fail(scene, {}, "cloth.pattern.courses",
         std::to_string(scene.knit->courses) + " (× " + std::to_string(scene.knit->wales) + " wales)", *expected);
  fail(scene, {}, "cloth.warps", std::to_string(scene.warps) + " (× " + std::to_string(scene.wefts) + " wefts)",
       *expected);
}

void fit_scene_times(Scene& scene, const std::map<std::string, std::string>& record) {
  auto notice = [](const std::string& what) { std::fprintf(stderr, "weavelab: note: %s\n", what.c_str()); };
  auto usable = [](double x) { return std::isfinite(x) && x > 0.0; };
  const bool duration = record.count("duration_s") && usable(scene.duration_s);
  const bool dt = record.count("dt_s") && usable(scene.dt_s), interval = record.count("output_interval_s");
  if (duration && !dt && scene.dt_s > scene.duration_s) {
    notice("--duration " + shortest(scene.duration_s) + " s is shorter than the scene's step; the step is " +
           shortest(scene.duration_s) + " s (was " + shortest(scene.dt_s) + " s)");
    scene.dt_s = scene.duration_s;
  }
  if (duration && !interval && scene.output_interval_s > scene.duration_s) {
    notice("--duration " + shortest(scene.duration_s) +
           " s is shorter than the scene's output interval; frames every " + shortest(scene.duration_s) + " s (was " +
           shortest(scene.output_interval_s) + " s)");
    scene.output_interval_s = scene.duration_s;
  }
  if (dt && !interval && scene.dt_s > scene.output_interval_s && scene.dt_s <= scene.duration_s) {
    notice("--dt " + shortest(scene.dt_s) + " s is longer than the scene's output interval; frames every " +
           shortest(scene.dt_s) + " s (was " + shortest(scene.output_interval_s) + " s)");
    scene.output_interval_s = scene.dt_s;
  }
}

void apply_run_overrides(Scene& scene, const RunOverrides& o, std::map<std::string, std::string>& record) {
  if (o.integrator) {
    scene.integrator = *o.integrator;
    record["integrator"] = *o.integrator;
  }
  if (o.linear_solver) {
    scene.linear_solver = *o.linear_solver;
    record["linear_solver"] = *o.linear_solver;
  }
  if (o.dt_s) {
    scene.dt_s = *o.dt_s;
    record["dt_s"] = shortest(*o.dt_s);
  }
  if (o.duration_s) {
    scene.duration_s = *o.duration_s;
    record["duration_s"] = shortest(*o.duration_s);
  }
  if (o.output_interval_s) {
    scene.output_interval_s = *o.output_interval_s;
    record["output_interval_s"] = shortest(*o.output_interval_s);
  }
  if (o.rtol) {
    scene.adaptive = true;
    scene.rtol = *o.rtol;
    scene.atol = 1e-3 * *o.rtol;
    record["rtol"] = shortest(*o.rtol);
  }
  if (o.adaptive || o.rtol) {
    scene.adaptive = true;
    record["adaptive"] = "true";
  }
  if (o.fem_parameter_file) {
    const std::string& path = *o.fem_parameter_file;
    std::error_code ec;
    if (path.empty() || !std::filesystem::is_regular_file(path, ec))
      throw SettingError("--fem-params", "'" + path + "'", "an existing FEM parameter file (TOML)");
    scene.fem.parameter_file = path;
    record["fem.parameter_file"] = path;
    (void)fem_material(scene);  // the file's own errors: FemParameterError with its line
  }
  if (o.error_estimate) {
    scene.error_estimate = true;
    record["error_estimate"] = "true";
  }
  if (o.accuracy_m) {
    const std::string value = shortest(*o.accuracy_m);
    if (!(std::isfinite(*o.accuracy_m) && *o.accuracy_m > 0.0))
      throw SettingError("--accuracy", value, "a finite number > 0 (m)");
    for (const auto& [key, option] : {std::pair{"dt_s", "--dt"}, std::pair{"rtol", "--rtol"},
                                      std::pair{"adaptive", "--adaptive"}, std::pair{"integrator", "--integrator"}})
      if (record.count(key))
        throw SettingError(
            "--accuracy", value + " with " + option,
            "no " + std::string(option) + " beside it: --accuracy chooses the integrator, its step and tolerance");
    scene.accuracy_m = *o.accuracy_m;
    record["accuracy_m"] = value;
  }
  fit_scene_times(scene, record);
  check_run_settings(scene, record);
}

void apply_duration_override(Scene& scene, double duration_s, std::map<std::string, std::string>& record) {
  scene.duration_s = duration_s;
  record["duration_s"] = shortest(duration_s);
  fit_scene_times(scene, record);
  const auto bad = time_settings_violation(scene, [&](const std::string& key) {
    return key == "time.duration_s" ? 2 : scene.key_lines.count(key) ? 1 : 0;
  });
  if (bad) fail(scene, record, bad->key, bad->value, bad->expected);
}

double positive_option(const std::string& option, double value) {
  if (!(std::isfinite(value) && value > 0.0)) throw SettingError(option, shortest(value), "a finite number > 0");
  return value;
}

std::filesystem::path output_folder(const std::optional<std::string>& given, const std::filesystem::path& fallback) {
  if (given && given->empty()) throw SettingError("--out", "''", "a non-empty folder path");
  const std::filesystem::path folder = given ? std::filesystem::path(*given) : fallback;
  std::error_code ec;
  if (std::filesystem::exists(folder, ec) && !std::filesystem::is_directory(folder, ec)) {
    const std::string expected = "a folder, or a path where none exists yet (it names an existing file)";
    if (given) throw SettingError("--out", "'" + folder.string() + "'", expected);
    throw std::invalid_argument("output folder '" + folder.string() + "': expected " + expected + "; choose --out");
  }
  return folder;
}

}  // namespace wl
