// The compiled core of the Python module `weavelab` (docs/python.md); the
// package's __init__.py (python/weavelab/) is the layer users call.
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "driver/determinism.h"
#include "integrators/integrator.h"
#include "models/model_factory.h"
#include "python/bindings/errors.h"
#include "python/bindings/model_binding.h"
#include "python/bindings/run_binding.h"
#include "python/bindings/scene_binding.h"
#include "python/bindings/studies_binding.h"

PYBIND11_MODULE(_core, m) {
  wl::hold_blas_threads();  // the bits of a `weavelab run` (README, "Reproducibility")
  m.doc() = "weavelab's C++ core: scenes, models, integrators, runs, calibrate and fit";
  wl::python::bind_errors(m);
  wl::python::bind_scene(m);
  wl::python::bind_model(m);
  wl::python::bind_run(m);
  wl::python::bind_studies(m);
  m.def("integrator_names", &wl::integrator_names, "Integrators a run accepts");
  m.def("model_names", &wl::model_names, "Models a scene can be simulated with");
  m.def(
      "integrator_capabilities",
      [](const std::string& name) {
        const wl::IntegratorCapabilities c = wl::make_integrator(name)->capabilities();
        pybind11::dict d;
        d["controls_error"] = c.controls_error;
        d["fixed_step_order"] = c.fixed_step_order;
        d["explicit_method"] = c.explicit_method;
        d["state_dependent_mass"] = c.state_dependent_mass;
        d["sensitivities"] = c.sensitivities;
        d["replays_steps"] = c.replays_steps;
        return d;
      },
      pybind11::arg("name"), "What an integrator is and offers (integrators/integrator.h)");
}
