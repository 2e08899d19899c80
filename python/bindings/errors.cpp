#include "python/bindings/errors.h"

#include "driver/run_settings.h"

namespace py = pybind11;

namespace wl::python {
namespace {

// Set in bind_errors; module lifetime (never released).
PyObject* g_scene_error = nullptr;
PyObject* g_setting_error = nullptr;

void set_scene_error(const std::string& message, const SceneError& e, const std::string& file, int line) {
  py::object exc = py::reinterpret_borrow<py::object>(g_scene_error)(message);
  exc.attr("file") = file;
  exc.attr("line") = line;
  exc.attr("key") = e.key;
  exc.attr("value") = e.value;
  exc.attr("expected") = e.expected;
  PyErr_SetObject(g_scene_error, exc.ptr());
}

// "option '--output-interval': …" → "argument 'output_interval': …", the
// keyword of run() that carries the option.
std::string as_argument(std::string message) {
  const std::string prefix = "option '--";
  if (!message.starts_with(prefix)) return message;
  const size_t end = message.find('\'', prefix.size());
  if (end == std::string::npos) return message;
  std::string name = message.substr(prefix.size(), end - prefix.size());
  for (char& c : name)
    if (c == '-') c = '_';
  return "argument '" + name + message.substr(end);
}

}  // namespace

void raise_scene_error(const SceneError& e, const std::string& origin) {
  set_scene_error(origin + ": key '" + e.key + "': got " + e.value + ", expected " + e.expected, e, origin, 0);
  throw py::error_already_set();
}

void bind_errors(py::module_& m) {
  g_scene_error = PyErr_NewExceptionWithDoc(
      "weavelab.SceneError",
      "A scene value the scene parser refuses; attributes file, line (0 for a scene edited in memory), key, "
      "value, expected.",
      PyExc_ValueError, nullptr);
  g_setting_error = PyErr_NewExceptionWithDoc("weavelab.SettingError",
                                              "A run argument the run refuses (the rules of the command-line options).",
                                              PyExc_ValueError, nullptr);
  m.add_object("SceneError", py::handle(g_scene_error));
  m.add_object("SettingError", py::handle(g_setting_error));
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const SceneError& e) {
      set_scene_error(e.what(), e, e.file, e.line);
    } catch (const SettingError& e) {
      PyErr_SetString(g_setting_error, as_argument(e.what()).c_str());
    }
  });
}

}  // namespace wl::python
