// weavelab._calibrate and weavelab._fit: `weavelab calibrate` and
// `weavelab fit` through their drivers (driver/calibrate.h,
// fit_command.h), writing the same output folders; the Python layer returns
// calibration.json and fit.json as dicts.
#pragma once
#include <pybind11/pybind11.h>

namespace wl::python {

void bind_studies(pybind11::module_& m);

}  // namespace wl::python
