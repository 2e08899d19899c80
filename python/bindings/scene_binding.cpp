#include "python/bindings/scene_binding.h"

#include <algorithm>
#include <sstream>
#include <vector>

#include "python/bindings/errors.h"

namespace py = pybind11;

namespace wl::python {
namespace {

// Python values as TOML nodes: bool, int (64-bit), float, str, list/tuple (an
// array; a list of dicts is an array of tables), dict (a table), numpy scalars
// and arrays. A value that has none of these forms (None, an integer beyond 64
// bits, a dict or list that contains itself or nests deeper than a scene can)
// raises weavelab.SceneError naming its key path, e.g. "cloth.warps" or
// "handles[1].node".
class PythonToToml {
 public:
  explicit PythonToToml(std::string origin) : origin_(std::move(origin)) {}

  std::unique_ptr<toml::node> node(const py::handle& x, const std::string& path) {
    const Nesting nesting(*this, x, path);
    if (py::isinstance<py::bool_>(x)) return std::make_unique<toml::value<bool>>(x.cast<bool>());
    if (py::isinstance<py::int_>(x)) return std::make_unique<toml::value<int64_t>>(integer(x, path));
    if (py::isinstance<py::float_>(x)) return std::make_unique<toml::value<double>>(x.cast<double>());
    if (py::isinstance<py::str>(x)) return std::make_unique<toml::value<std::string>>(x.cast<std::string>());
    if (py::isinstance<py::dict>(x)) return std::make_unique<toml::table>(entries(x.cast<py::dict>(), path));
    if (py::hasattr(x, "tolist") && !py::isinstance<py::list>(x))  // numpy scalar or array
      return node(x.attr("tolist")(), path);
    if (py::isinstance<py::list>(x) || py::isinstance<py::tuple>(x)) {
      auto a = std::make_unique<toml::array>();
      int k = 0;
      for (const py::handle& item : x) a->push_back(std::move(*node(item, path + "[" + std::to_string(k++) + "]")));
      return a;
    }
    refuse(path, x.is_none() ? "None" : "a value of type " + std::string(py::str(x.get_type().attr("__name__"))),
           "a bool, int, float, str, list or dict" +
               std::string(x.is_none() ? " (delete the key to have its default)" : ""));
  }

  toml::table table(const py::dict& d, const std::string& path) {
    const Nesting nesting(*this, d, path);
    return entries(d, path);
  }

 private:
  // A scene's tables nest a few levels (handles[1].node is 3); this is far beyond.
  static constexpr size_t kMaxDepth = 32;

  // The values under conversion, outermost first: a value among them contains itself.
  class Nesting {
   public:
    Nesting(PythonToToml& c, const py::handle& x, const std::string& path) : c_(c) {
      if (std::find(c.open_.begin(), c.open_.end(), x.ptr()) != c.open_.end() &&
          (py::isinstance<py::dict>(x) || py::isinstance<py::list>(x)))
        c.refuse(path, "a " + std::string(py::str(x.get_type().attr("__name__"))) + " that contains itself",
                 "nested dicts and lists without cycles");
      if (c.open_.size() == kMaxDepth)
        c.refuse(path, "values nested deeper than " + std::to_string(kMaxDepth) + " levels",
                 "at most " + std::to_string(kMaxDepth) + " levels of dicts and lists");
      c.open_.push_back(x.ptr());
    }
    ~Nesting() { c_.open_.pop_back(); }
    Nesting(const Nesting&) = delete;
    Nesting& operator=(const Nesting&) = delete;

   private:
    PythonToToml& c_;
  };

  toml::table entries(const py::dict& d, const std::string& path) {
    toml::table t;
    for (const auto& [k, v] : d) {
      const std::string key = py::str(k);
      t.insert_or_assign(key, std::move(*node(v, path.empty() ? key : path + "." + key)));
    }
    return t;
  }

  int64_t integer(const py::handle& x, const std::string& path) {
    int overflow = 0;
    const long long v = PyLong_AsLongLongAndOverflow(x.ptr(), &overflow);
    if (v == -1 && PyErr_Occurred()) throw py::error_already_set();
    if (overflow) {
      const long long bits = x.attr("bit_length")().cast<long long>();
      refuse(path, bits < 256 ? std::string(py::str(x)) : "an integer of " + std::to_string(bits) + " bits",
             "an integer from −2⁶³ to 2⁶³ − 1");
    }
    return v;
  }

  [[noreturn]] void refuse(const std::string& path, const std::string& value, const std::string& expected) {
    raise_scene_error(SceneError(origin_, 0, path, value, expected), origin_);
  }

  std::string origin_;
  std::vector<PyObject*> open_;
};

py::object python_from_node(const toml::node& n) {
  if (const auto* t = n.as_table()) {
    py::dict d;
    for (const auto& [k, v] : *t) d[py::str(std::string(k.str()))] = python_from_node(v);
    return d;
  }
  if (const auto* a = n.as_array()) {
    py::list l;
    for (const auto& v : *a) l.append(python_from_node(v));
    return l;
  }
  if (const auto* b = n.as_boolean()) return py::bool_(b->get());
  if (const auto* i = n.as_integer()) return py::int_(i->get());
  if (const auto* f = n.as_floating_point()) return py::float_(f->get());
  if (const auto* s = n.as_string()) return py::str(s->get());
  return n.visit([](const auto& value) {  // a date or time, as written
    std::ostringstream os;
    os << value;
    return py::str(os.str());
  });
}

std::vector<std::string> split_key(const std::string& key) {
  std::vector<std::string> parts;
  std::string part;
  for (char c : key + ".") {
    if (c != '.') {
      part += c;
      continue;
    }
    if (part.empty()) throw py::key_error("scene key '" + key + "': expected dotted names, e.g. 'time.dt_s'");
    parts.push_back(std::exchange(part, {}));
  }
  return parts;
}

// The table holding the last part of `key` (created on the way when `create`),
// or nullptr.
toml::table* parent_table(toml::table& root, const std::vector<std::string>& parts, bool create) {
  toml::table* t = &root;
  for (size_t k = 0; k + 1 < parts.size(); ++k) {
    toml::node* next = t->get(parts[k]);
    if (!next && create) next = &t->insert_or_assign(parts[k], toml::table{}).first->second;
    if (!next || !next->is_table()) return nullptr;
    t = next->as_table();
  }
  return t;
}

std::string toml_text(const toml::table& t) {
  std::ostringstream os;
  os << t << "\n";
  return os.str();
}

void replace_table(SceneHandle& h, toml::table table) {
  SceneHandle next = scene_from_table(std::move(table), h.origin);
  h = std::move(next);
}

SceneHandle load(const std::string& path) {
  SceneHandle h;
  h.scene = load_scene(path);  // a bad file: SceneError with its file and line
  h.table = toml::parse(h.scene.text, path);
  h.origin = path;
  return h;
}

}  // namespace

SceneHandle scene_from_table(toml::table table, const std::string& origin) {
  SceneHandle h;
  h.origin = origin;
  h.edited = true;
  try {
    h.scene = parse_scene(toml_text(table), origin);
  } catch (const SceneError& e) {
    raise_scene_error(e, origin);
  }
  h.table = std::move(table);
  return h;
}

void bind_scene(py::module_& m) {
  py::class_<SceneHandle>(m, "Scene",
                          "A validated scene (experiments/scenes/README.md); scene['time.dt_s'] = 0.002 edits a key "
                          "through the scene parser, a refused value raises weavelab.SceneError naming the key")
      .def(py::init([](const py::dict& d) { return scene_from_table(PythonToToml("<dict>").table(d, ""), "<dict>"); }),
           py::arg("tables"), "A scene from nested dicts shaped like the TOML file ({'cloth': {'warps': 9}, ...})")
      .def_static("load", &load, py::arg("path"), "Reads and validates a scene file (TOML)")
      .def(
          "__getitem__",
          [](const SceneHandle& h, const std::string& key) {
            const auto parts = split_key(key);
            toml::table root = h.table;
            const toml::table* t = parent_table(root, parts, false);
            const toml::node* n = t ? t->get(parts.back()) : nullptr;
            if (!n) throw py::key_error("scene key '" + key + "' is not written in the scene (its default applies)");
            return python_from_node(*n);
          },
          py::arg("key"))
      .def(
          "__setitem__",
          [](SceneHandle& h, const std::string& key, const py::handle& value) {
            const auto parts = split_key(key);
            toml::table next = h.table;
            toml::table* t = parent_table(next, parts, true);
            if (!t) throw py::key_error("scene key '" + key + "': a part of it is not a table");
            t->insert_or_assign(parts.back(), std::move(*PythonToToml(h.origin).node(value, key)));
            replace_table(h, std::move(next));
          },
          py::arg("key"), py::arg("value"))
      .def(
          "__delitem__",
          [](SceneHandle& h, const std::string& key) {
            const auto parts = split_key(key);
            toml::table next = h.table;
            toml::table* t = parent_table(next, parts, false);
            if (!t || !t->erase(parts.back())) throw py::key_error("scene key '" + key + "' is not written");
            replace_table(h, std::move(next));
          },
          py::arg("key"), "Removes a key: its default applies")
      .def(
          "update",
          [](SceneHandle& h, const py::dict& values) {
            toml::table next = h.table;
            for (const auto& [k, v] : values) {
              const std::string key = py::str(k);
              const auto parts = split_key(key);
              toml::table* t = parent_table(next, parts, true);
              if (!t) throw py::key_error("scene key '" + key + "': a part of it is not a table");
              t->insert_or_assign(parts.back(), std::move(*PythonToToml(h.origin).node(v, key)));
            }
            replace_table(h, std::move(next));
          },
          py::arg("values"), "Sets several dotted keys at once, checked together")
      .def("copy", [](const SceneHandle& h) { return h; })
      .def("to_dict", [](const SceneHandle& h) { return python_from_node(h.table); })
      .def_property_readonly(
          "toml", [](const SceneHandle& h) { return h.scene.text; }, "The text that is simulated")
      .def_property_readonly("source", [](const SceneHandle& h) { return h.origin; })
      .def_property_readonly("edited", [](const SceneHandle& h) { return h.edited; })
      .def_property_readonly("duration_s", [](const SceneHandle& h) { return h.scene.duration_s; })
      .def_property_readonly("dt_s", [](const SceneHandle& h) { return h.scene.dt_s; })
      .def_property_readonly("output_interval_s", [](const SceneHandle& h) { return h.scene.output_interval_s; })
      .def_property_readonly("integrator", [](const SceneHandle& h) { return h.scene.integrator; })
      .def_property_readonly("warps", [](const SceneHandle& h) { return h.scene.warps; })
      .def_property_readonly("wefts", [](const SceneHandle& h) { return h.scene.wefts; })
      .def("__repr__", [](const SceneHandle& h) {
        return "<weavelab.Scene " + h.origin + (h.edited ? " (edited)" : "") + ": " + std::to_string(h.scene.warps) +
               "x" + std::to_string(h.scene.wefts) + ", " + h.scene.integrator + ">";
      });
}

}  // namespace wl::python
