#include "python/bindings/studies_binding.h"

#include <pybind11/stl.h>

#include "driver/calibrate.h"
#include "driver/fit_command.h"
#include "python/bindings/interruption.h"

namespace py = pybind11;

namespace wl::python {
namespace {

// Returns whether the fit converged.
bool calibrate(const std::string& scene_path, const std::string& out, const std::vector<std::string>& tests,
               const std::vector<std::string>& free, int patch,
               const std::map<std::string, std::vector<double>>& ladders, int starts, unsigned seed,
               const std::string& loss, bool sliding, bool border_strip, const std::vector<std::string>& validate,
               const std::string& time_steps, double rtol, bool progress) {
  CalibrateConfig c;
  c.scene_path = scene_path;
  c.out_dir = out;
  c.tests = tests;
  c.fit.free = free;
  c.patch = patch;
  c.ladders = ladders;
  c.fit.starts = starts;
  c.fit.seed = seed;
  c.fit.loss = loss;
  c.sliding = sliding;
  c.border_strip = border_strip;
  for (const auto& v : validate) c.validate.emplace_back(v);
  c.time_steps = parse_time_steps("time_steps", time_steps, rtol);
  c.progress = progress;
  const CalibratePlan plan = plan_calibration(c);  // every input checked; nothing written yet
  const CallInterruption interruption;             // Ctrl-C ends the stage under way; calibration.json says so
  py::gil_scoped_release release;
  return run_calibration(c, plan).fit.converged;
}

bool fit(const std::string& scene_path, const std::string& target, const std::vector<std::string>& free,
         const std::string& out, const std::map<std::string, double>& start, int frames, const std::string& model,
         const std::string& integrator, double bound_factor, int max_iterations, const std::string& fem_params,
         const std::vector<int>& window, bool progress) {
  FitCommandConfig c;
  c.scene_path = scene_path;
  c.target_dir = target;
  c.out_dir = out;
  c.frames = frames;
  c.fem_params = fem_params;
  c.fit.free = free;
  c.fit.start = start;
  c.fit.model = model;
  c.fit.integrator = integrator;
  c.fit.bound_factor = bound_factor;
  c.fit.max_iterations = max_iterations;
  c.fit.window = window;
  c.fit.progress = progress;
  const FitCommandPlan plan = plan_fit(c);  // every input checked; nothing written yet
  const CallInterruption interruption;      // Ctrl-C ends the fit; fit.json says so
  py::gil_scoped_release release;
  return run_fit(c, plan).converged;
}

}  // namespace

void bind_studies(py::module_& m) {
  m.def("_calibrate", &calibrate, py::arg("scene"), py::arg("out"), py::arg("tests"), py::arg("free"), py::arg("patch"),
        py::arg("ladders"), py::arg("starts"), py::arg("seed"), py::arg("loss"), py::arg("sliding"),
        py::arg("border_strip"), py::arg("validate"), py::arg("time_steps"), py::arg("rtol"), py::arg("progress"));
  m.def("_fit", &fit, py::arg("scene"), py::arg("target"), py::arg("free"), py::arg("out"), py::arg("start"),
        py::arg("frames"), py::arg("model"), py::arg("integrator"), py::arg("bound_factor"), py::arg("max_iterations"),
        py::arg("fem_params"), py::arg("window"), py::arg("progress"));
}

}  // namespace wl::python
