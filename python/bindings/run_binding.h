// weavelab._run: a run of a scene through the run driver
// (driver/run.h), the frames kept in memory as arrays and,
// with an output folder, written as by `weavelab run`.
#pragma once
#include <pybind11/pybind11.h>

namespace wl::python {

void bind_run(pybind11::module_& m);

}  // namespace wl::python
