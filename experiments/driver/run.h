// Runs one scene with one model and integrator, writing the frames (PVD/VTU),
// the metrics CSV and the run summary JSON into an output folder, with
// progress on stderr. A numerical failure ends the run with its outcome in the
// summary; it is not an exception.
#pragma once
#include <filesystem>
#include <map>
#include <string>

#include "integrators/integrator.h"
#include "models/scene/scene.h"

namespace wl {

struct RunOptions {
  std::string model = "yarn";
  std::filesystem::path out_dir;
  bool progress = true;
  std::map<std::string, std::string> overrides;  // command-line values that replaced scene values
};

struct RunReport {
  StepResult result;
  IntegratorStats stats;
  int frames = 0;
  double end_time = 0.0;
};

RunReport run_scene(const Scene& scene, const RunOptions& options);

}  // namespace wl
