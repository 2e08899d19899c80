#include "python/bindings/run_binding.h"

#include <optional>

#include <pybind11/stl.h>

#include "driver/run.h"
#include "driver/run_settings.h"
#include "models/model_factory.h"
#include "python/bindings/errors.h"
#include "python/bindings/frames.h"
#include "python/bindings/interruption.h"
#include "python/bindings/scene_binding.h"

namespace py = pybind11;

namespace wl::python {
namespace {

// The keywords of run(), each the twin of a `weavelab run` option (README, "Using it").
py::dict run(const SceneHandle& handle, const std::string& model, const std::optional<std::string>& out, bool progress,
             const std::optional<std::string>& integrator, const std::optional<std::string>& linear_solver,
             std::optional<double> dt, std::optional<double> duration, std::optional<double> output_interval,
             bool adaptive, std::optional<double> rtol, bool error_estimate, std::optional<double> accuracy,
             const std::optional<std::string>& fem_params) {
  Scene scene = handle.scene;
  RunOverrides ov;
  ov.integrator = integrator;
  ov.linear_solver = linear_solver;
  ov.dt_s = dt;
  ov.duration_s = duration;
  ov.output_interval_s = output_interval;
  ov.adaptive = adaptive;
  ov.rtol = rtol;
  ov.error_estimate = error_estimate;
  ov.accuracy_m = accuracy;
  ov.fem_parameter_file = fem_params;
  RunOptions opt;
  opt.model = model.empty() ? yarn_level_model(scene) : model;  // "": the scene's yarn level
  opt.progress = progress;
  in_scene_terms(handle, [&] {  // the command line's rules, the forgiving one included
    apply_run_overrides(scene, ov, opt.overrides);
  });
  if (out) opt.out_dir = output_folder(out, {});
  FrameStack frames;
  opt.on_frame = [&](const Frame& f) { frames.add(f); };
  const RunReport rep = in_scene_terms(handle, [&] {  // a knit only its model refuses
    CallInterruption interruption;                    // the driver ends the run after the step under way
    py::gil_scoped_release release;
    return run_scene(scene, opt);
  });
  py::dict d = frames.arrays();
  d["outcome"] = to_string(rep.result.outcome);
  d["message"] = rep.result.message;
  d["end_time"] = rep.end_time;
  d["summary_json"] = rep.summary_json;
  d["out"] = out ? py::cast(opt.out_dir.string()) : py::none();
  return d;
}

}  // namespace

void bind_run(py::module_& m) {
  m.def("_run", &run, py::arg("scene"), py::arg("model") = "", py::arg("out") = py::none(), py::arg("progress") = false,
        py::arg("integrator") = py::none(), py::arg("linear_solver") = py::none(), py::arg("dt") = py::none(),
        py::arg("duration") = py::none(), py::arg("output_interval") = py::none(), py::arg("adaptive") = false,
        py::arg("rtol") = py::none(), py::arg("error_estimate") = false, py::arg("accuracy") = py::none(),
        py::arg("fem_params") = py::none());
}

}  // namespace wl::python
