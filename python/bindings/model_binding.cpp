#include "python/bindings/model_binding.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>

#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include "driver/experiment_meta.h"
#include "driver/run_settings.h"
#include "driver/time_steps.h"
#include "integrators/integrator.h"
#include "models/model_factory.h"
#include "python/bindings/errors.h"
#include "python/bindings/frames.h"
#include "python/bindings/interruption.h"
#include "python/bindings/scene_binding.h"

namespace py = pybind11;

namespace wl::python {
namespace {

struct ModelHandle {
  std::unique_ptr<Model> model;
  Evaluation scratch;  // for the kinetic energy
};

void check_state_size(const ModelHandle& h, const Vec& x, const char* name) {
  if (x.size() != h.model->num_dofs())
    throw py::value_error(std::string(name) + ": got " + std::to_string(x.size()) + " values, expected " +
                          std::to_string(h.model->num_dofs()) + " (Model.num_dofs)");
}

// A sparse matrix as its compressed-column arrays; the Python layer makes a
// scipy.sparse.csc_matrix of them when scipy is present.
py::dict csc_arrays(const SparseMatrix& a) {
  py::dict d;
  d["shape"] = py::make_tuple(a.rows(), a.cols());
  const auto nnz = static_cast<py::ssize_t>(a.nonZeros());
  py::array_t<int> indptr(a.cols() + 1), indices(nnz);
  py::array_t<double> data(nnz);
  std::copy(a.outerIndexPtr(), a.outerIndexPtr() + a.cols() + 1, indptr.mutable_data());
  std::copy(a.innerIndexPtr(), a.innerIndexPtr() + nnz, indices.mutable_data());
  std::copy(a.valuePtr(), a.valuePtr() + nnz, data.mutable_data());
  d["indptr"] = indptr;
  d["indices"] = indices;
  d["data"] = data;
  return d;
}

std::string seconds(double t) {
  char b[32];
  std::snprintf(b, sizeof b, "%.10g", t);
  return b;
}

py::object json_value(const Json& j) { return py::module_::import("json").attr("loads")(j.dump()); }

py::dict outcome_dict(const StepResult& r) {
  py::dict d;
  d["outcome"] = to_string(r.outcome);
  d["message"] = r.message;
  return d;
}

// A model stepped by an integrator with the scene's [time] settings.
class Simulation {
 public:
  // `model` "" is the scene's yarn level (yarn_level_model).
  Simulation(const SceneHandle& scene, const std::string& model) : model_(std::make_shared<ModelHandle>()) {
    const std::string model_name = model.empty() ? yarn_level_model(scene.scene) : model;
    model_->model = in_scene_terms(scene, [&] {
      check_run_settings(scene.scene, {});
      check_run_memory(scene.scene, model_name);
      return make_model(scene.scene, model_name);
    });
    check_linear_solver(scene.scene, *model_->model, {});
    integrator_ = make_integrator(scene.scene.integrator);
    options_ = scene_integrator_options(scene.scene);  // as a run: the [time] table
    duration_ = scene.scene.duration_s;
    options_.linear_solver = parse_linear_solver(scene.scene.linear_solver);
    Model& m = *model_->model;
    integrator_->initialize(m, 0.0, m.initial_q(), m.initial_v(), options_);
  }

  // Advances to t_out, a time from Simulation.t to the scene's duration, with
  // the GIL released; a Ctrl-C or SIGTERM ends it after the step under way.
  py::dict advance_to(double t_out) {
    if (busy_) throw py::value_error("Simulation: a call is already advancing it (another thread)");
    if (!std::isfinite(t_out) || t_out < integrator_->t() || t_out > duration_)
      throw py::value_error("advance_to: got t = " + seconds(t_out) + " s, expected a time from Simulation.t (" +
                            seconds(integrator_->t()) + " s) to the scene's time.duration_s (" + seconds(duration_) +
                            " s)");
    struct Interrupted {};
    CallInterruption interruption;
    integrator_->on_step = [&](const StepRecord&) {
      if (interruption.requested()) throw Interrupted{};
    };
    StepResult r;
    busy_ = true;
    {
      py::gil_scoped_release release;
      try {
        r = interruption.requested() ? StepResult{Outcome::interrupted, interrupted_message(interrupt_signal())}
                                     : integrator_->advance_to(t_out);
      } catch (const Interrupted&) {
        r = {Outcome::interrupted, interrupted_message(interrupt_signal())};
      } catch (...) {
        busy_ = false;
        throw;
      }
    }
    busy_ = false;
    integrator_->on_step = nullptr;
    return outcome_dict(r);
  }

  // One step of dt_s, the last one shortened to end at the scene's duration.
  py::dict step() {
    if (integrator_->t() >= duration_)
      throw py::value_error("step: Simulation.t (" + seconds(integrator_->t()) +
                            " s) is at the scene's time.duration_s: nothing is left to step");
    return advance_to(std::min(integrator_->t() + options_.dt, duration_));
  }
  double t() const { return integrator_->t(); }
  Vec q() const { return integrator_->q(); }
  Vec v() const { return integrator_->v(); }
  py::object stats() const { return json_value(statistics_json(integrator_->stats())); }
  py::dict frame() const { return frame_arrays(model_->model->frame(t(), integrator_->q(), integrator_->v())); }
  std::shared_ptr<ModelHandle> model() const { return model_; }
  std::string integrator() const { return integrator_->name(); }

 private:
  std::shared_ptr<ModelHandle> model_;  // outlives the integrator, which holds a reference to it
  std::unique_ptr<Integrator> integrator_;
  IntegratorOptions options_;
  double duration_ = 0.0;  // the scene's time.duration_s: what its schedules are defined over
  bool busy_ = false;
};

}  // namespace

void bind_model(py::module_& m) {
  py::class_<ModelHandle, std::shared_ptr<ModelHandle>>(
      m, "Model",
      "A yarn-level ('yarn' woven, 'knit' knitted) or continuum ('fem') model of a scene (docs/models.md); "
      "kind None is the scene's yarn level")
      .def(py::init([](const SceneHandle& scene, const std::optional<std::string>& given) {
             const std::string kind = given ? *given : yarn_level_model(scene.scene);
             auto h = std::make_shared<ModelHandle>();
             h->model = in_scene_terms(scene, [&] {
               check_run_memory(scene.scene, kind);
               return make_model(scene.scene, kind);
             });
             return h;
           }),
           py::arg("scene"), py::arg("kind") = py::none())
      .def_property_readonly("name", [](const ModelHandle& h) { return h.model->name(); })
      .def_property_readonly("num_dofs", [](const ModelHandle& h) { return h.model->num_dofs(); })
      .def_property_readonly("initial_q", [](const ModelHandle& h) { return h.model->initial_q(); })
      .def_property_readonly("initial_v", [](const ModelHandle& h) { return h.model->initial_v(); })
      .def_property_readonly("fixed_dofs",
                             [](const ModelHandle& h) {
                               const auto f = h.model->fixed_dofs();
                               return std::vector<int>(f.begin(), f.end());
                             })
      .def_property_readonly("parameter_keys", [](const ModelHandle& h) { return h.model->parameter_keys(); })
      .def("describe", [](const ModelHandle& h) { return h.model->describe(); })
      .def(
          "evaluate",
          [](ModelHandle& h, const Vec& q, const Vec& v, double t, bool jacobians, bool mass) {
            check_state_size(h, q, "q");
            check_state_size(h, v, "v");
            Evaluation e;
            allocate_evaluation(*h.model, e);
            const unsigned flags = kForce | (jacobians ? kDfdq | kDfdv : 0u) | (mass ? kMass : 0u);
            h.model->evaluate(t, q, v, flags, e);
            py::dict d;
            d["force"] = e.force;
            if (jacobians) {
              d["dfdq"] = csc_arrays(e.dfdq);
              d["dfdv"] = csc_arrays(e.dfdv);
            }
            if (mass) d["mass"] = csc_arrays(e.mass);
            return d;
          },
          py::arg("q"), py::arg("v"), py::arg("t") = 0.0, py::arg("jacobians") = true, py::arg("mass") = true)
      .def(
          "energies",
          [](ModelHandle& h, const Vec& q, const Vec& v, double t) {
            check_state_size(h, q, "q");
            check_state_size(h, v, "v");
            py::dict d;
            d["kinetic_J"] = h.model->kinetic_energy(t, q, v, h.scratch);
            d["potential_J"] = h.model->potential_energy(q);
            return d;
          },
          py::arg("q"), py::arg("v"), py::arg("t") = 0.0)
      .def(
          "frame",
          [](const ModelHandle& h, const Vec& q, const Vec& v, double t) {
            check_state_size(h, q, "q");
            check_state_size(h, v, "v");
            return frame_arrays(h.model->frame(t, q, v));
          },
          py::arg("q"), py::arg("v"), py::arg("t") = 0.0);

  py::class_<Simulation>(m, "_Simulation")
      .def(py::init<const SceneHandle&, const std::string&>(), py::arg("scene"), py::arg("model") = "")
      .def("advance_to", &Simulation::advance_to, py::arg("t"))
      .def("step", &Simulation::step)
      .def_property_readonly("t", &Simulation::t)
      .def_property_readonly("q", &Simulation::q)
      .def_property_readonly("v", &Simulation::v)
      .def_property_readonly("model", &Simulation::model)
      .def_property_readonly("integrator", &Simulation::integrator)
      .def("stats", &Simulation::stats)
      .def("frame", &Simulation::frame);
}

}  // namespace wl::python
