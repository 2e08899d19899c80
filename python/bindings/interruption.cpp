#include "python/bindings/interruption.h"

#include <pybind11/pybind11.h>

namespace py = pybind11;

namespace wl::python {

CallInterruption::CallInterruption() {
  const py::module_ threading = py::module_::import("threading");
  if (threading.attr("current_thread")().is(threading.attr("main_thread")())) scope_.emplace();
}

}  // namespace wl::python
