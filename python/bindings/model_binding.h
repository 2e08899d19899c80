// weavelab.Model (a yarn or continuum model of a scene: force, Jacobians,
// energies and frames at a given state) and weavelab.Simulation (a model and
// an integrator stepped from Python).
#pragma once
#include <pybind11/pybind11.h>

namespace wl::python {

void bind_model(pybind11::module_& m);

}  // namespace wl::python
