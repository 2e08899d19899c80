// Python exceptions of the module (docs/python.md, "Errors"): a bad scene key
// is weavelab.SceneError (a ValueError) with the scene parser's message and
// its parts as attributes; every other bad input a ValueError, a failure to
// write a RuntimeError.
#pragma once
#include <string>

#include <pybind11/pybind11.h>

#include "models/scene/scene.h"

namespace wl::python {

// Creates weavelab.SceneError and weavelab.SettingError in `m` and registers
// the translation of the library's exceptions.
void bind_errors(pybind11::module_& m);

// Raises weavelab.SceneError for `e`; `origin` replaces the file and line of
// the message when the text was generated from an edited scene (its lines
// are not the user's).
[[noreturn]] void raise_scene_error(const SceneError& e, const std::string& origin);

}  // namespace wl::python
