// Command-line values that replace a scene's settings, checked by the same
// rules as the scene file (time_settings_violation in models/scene/scene.h)
// plus the ones only the driver can check (the integrator name). A violation
// is a SettingError (exit 2) naming the option or the scene file, line and key,
// the value and what was expected; nothing has been written then.
#pragma once
#include <filesystem>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>

#include "models/core/model.h"
#include "models/scene/scene.h"

namespace wl {

// A bad command-line value: what() reads
//   "option '--dt': got nan, expected a finite number > 0 (s)".
class SettingError : public std::invalid_argument {
 public:
  SettingError(const std::string& option, const std::string& value, const std::string& expected);
};

// Overrides of `weavelab run` (absent = the scene's value).
struct RunOverrides {
  std::optional<std::string> integrator, linear_solver;
  std::optional<double> dt_s, duration_s, output_interval_s, rtol;  // --rtol implies adaptive, atol = 1e-3 rtol
  bool adaptive = false;
  std::optional<std::string> fem_parameter_file;  // --fem-params: replaces [fem] parameter_file
  bool error_estimate = false;                    // --error-estimate: time.error_estimate = true
  std::optional<double> accuracy_m;               // --accuracy: time.accuracy_m
};

// Applies the overrides to `scene`, records them in `record` (scene key →
// value, as the summary lists them) and checks the result with check_run_settings;
// a parameter file must exist (SettingError) and parse (FemParameterError, file:line).
// A --duration (or --dt) that leaves the scene's output interval (or step)
// out of order is forgiven: the scene's value follows it, with a notice on
// stderr (fit_scene_times); two command-line values that contradict each
// other stay an error. --accuracy beside --dt, --rtol, --adaptive or
// --integrator is an error: it chooses those itself.
void apply_run_overrides(Scene& scene, const RunOverrides& overrides, std::map<std::string, std::string>& record);

// Checks a scene's run settings: the time rules and the integrator name. A
// violated rule names the command-line option when `record` holds its key
// (SettingError), else the scene's file and line (SceneError).
void check_run_settings(const Scene& scene, const std::map<std::string, std::string>& record);

// The scene's linear solver for this model: cholmod only where the model's
// step matrix is symmetric (SceneError or SettingError otherwise).
void check_linear_solver(const Scene& scene, const Model& model, const std::map<std::string, std::string>& record);

// Refuses (SceneError at [cloth] warps) a run of `model_name` whose memory
// estimate (memory_estimate.h) exceeds the memory available, before anything
// is allocated; the message gives the estimate.
void check_run_memory(const Scene& scene, const std::string& model_name);

// What check_run_memory expects when `model_name` on `scene` does not fit
// ("a cloth that fits in memory: ..."), nullopt when it fits.
std::optional<std::string> memory_shortfall(const Scene& scene, const std::string& model_name);

// The forgiving rule of apply_run_overrides: a finite, positive --duration
// (--dt) from the command line (`record`) pulls the scene's own step and
// output interval into order with it, with a notice on stderr.
void fit_scene_times(Scene& scene, const std::map<std::string, std::string>& record);

// --duration of the experiments: the same rules, recorded as "duration_s".
void apply_duration_override(Scene& scene, double duration_s, std::map<std::string, std::string>& record);

// A finite number > 0 for a plain option (e.g. --budget); SettingError otherwise.
double positive_option(const std::string& option, double value);

// The --out folder: `given` when set (an empty path is a SettingError), else
// `fallback`; checked before any work: a path naming an existing file that is
// not a folder is std::invalid_argument (exit 2; a SettingError for --out).
std::filesystem::path output_folder(const std::optional<std::string>& given, const std::filesystem::path& fallback);

}  // namespace wl
