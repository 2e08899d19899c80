// weavelab.Scene: a scene held as its TOML table and the validated wl::Scene
// parsed from it. Every edit goes through the scene parser (load_scene's
// checks and messages), so a scene in memory is always a valid one.
#pragma once
#include <string>

#include <pybind11/pybind11.h>
#include "models/scene/toml_include.h"

#include "models/scene/scene.h"
#include "python/bindings/errors.h"

namespace wl::python {

struct SceneHandle {
  Scene scene;
  toml::table table;    // the keys as written (file or dict), after the edits
  std::string origin;   // the file it came from, or "<dict>"; names it in errors
  bool edited = false;  // the text was generated from the table (its lines are not the user's)
};

// A scene from a table: serialized as TOML and parsed as `origin` (relative
// [fem] paths resolve against its directory); weavelab.SceneError on a bad value.
SceneHandle scene_from_table(toml::table table, const std::string& origin);

// Returns f(); a SceneError from it (a value the run's rules refuse, or a knit
// only its model refuses) names the user's file and line, or for an edited
// scene its origin (line 0): the generated text's lines are not the user's.
template <class F>
decltype(auto) in_scene_terms(const SceneHandle& scene, F&& f) {
  try {
    return f();
  } catch (const SceneError& e) {
    if (!scene.edited) throw;
    raise_scene_error(e, scene.origin);
  }
}

void bind_scene(pybind11::module_& m);

}  // namespace wl::python
