#include "driver/modes.h"

#include <cmath>
#include <cstdio>
#include <optional>
#include <stdexcept>

#include "driver/experiment_meta.h"
#include "driver/interrupted_record.h"
#include "integrators/integrator.h"
#include "models/common/self_contact.h"
#include "models/fem/fem_material.h"
#include "models/fem/fem_model.h"
#include "models/model_factory.h"
#include "models/yarn/yarn_model.h"
#include "output/atomic_file.h"
#include "output/csv_table.h"
#include "output/json_writer.h"
#include "output/vtu_writer.h"

namespace wl {
namespace {

// Settling when Newton's method from rest fails (linearized_modes) [s].
constexpr double kSettleSteps[] = {1e-2, 2e-3}, kSettleTime = 2.0;

// ‖A − Aᵀ‖_F / ‖A‖_F.
double relative_asymmetry(const SparseMatrix& a) {
  const SparseMatrix at = a.transpose();
  const double n = a.norm();
  return n > 0 ? SparseMatrix(a - at).norm() / n : 0.0;
}

// Mode `k` at every point of `frame` (the crossings for the yarn level, the
// vertices for the continuum), scaled by `scale`.
DataArray mode_array(const Model& model, const Scene& scene, const Eigen::MatrixXd& shapes, int k, double scale) {
  DataArray a{"mode_" + std::string(k < 10 ? "0" : "") + std::to_string(k), 3, {}};
  if (const auto* yarn = dynamic_cast<const YarnModel*>(&model)) {
    for (int n = 0; n < yarn->grid().num_nodes(); ++n)
      for (int c = 0; c < 3; ++c) a.values.push_back(scale * shapes(yarn->grid().dofs(n).x + c, k));
  } else {
    for (Eigen::Index d = 0; d < shapes.rows(); ++d) a.values.push_back(scale * shapes(d, k));
  }
  return a;
}

DataArray slide_array(const YarnModel& yarn, const Eigen::MatrixXd& shapes, int k, double scale,
                      const std::string& name) {
  DataArray a{name + "_slide", 2, {}};
  for (int n = 0; n < yarn.grid().num_nodes(); ++n) {
    const NodeDofs& d = yarn.grid().dofs(n);
    a.values.push_back(is_dof(d.u) ? scale * shapes(d.u, k) : 0.0);
    a.values.push_back(is_dof(d.v) ? scale * shapes(d.v, k) : 0.0);
  }
  return a;
}

// Largest crossing displacement of mode k.
double largest_displacement(const Eigen::MatrixXd& crossing_shapes, int k) {
  double m = 0;
  for (Eigen::Index c = 0; c + 2 < crossing_shapes.rows(); c += 3)
    m = std::max(m, crossing_shapes.col(k).segment<3>(c).norm());
  return m;
}

std::string mode_vtu(Model& model, const Scene& scene, const LinearizedModes& lm, const std::vector<double>& signs) {
  Frame f = model.frame(0.0, lm.q, Vec::Zero(model.num_dofs()));
  const auto* yarn = dynamic_cast<const YarnModel*>(&model);
  for (int k = 0; k < static_cast<int>(lm.modes.eigenvalues.size()); ++k) {
    const double scale = signs[k] / largest_displacement(lm.crossing_shapes, k);
    f.point_data.push_back(mode_array(model, scene, lm.modes.shapes, k, scale));
    if (yarn) f.point_data.push_back(slide_array(*yarn, lm.modes.shapes, k, scale, f.point_data.back().name));
  }
  return to_vtu(f);
}

Json fd_json(const StiffnessCheck& fd) {
  Json freqs = Json::array();
  for (double e : fd.eigenvalues) freqs.push(frequency_hz(e));
  return Json::object()
      .set("asymmetry", fd.asymmetry)
      .set("relative_difference_from_assembled", fd.difference)
      .set("relative_norm_outside_pattern", fd.outside_pattern)
      .set("frequencies_hz", std::move(freqs));
}

Json model_json(const LinearizedModes& lm, int dofs) {
  Json freqs = Json::array();
  for (double e : lm.modes.eigenvalues) freqs.push(frequency_hz(e));
  return Json::object()
      .set("dofs", dofs)
      .set("free_dofs", static_cast<int>(lm.modes.shapes.rows()))
      .set("equilibrium", lm.route)
      .set("planar_hang_lowest_hz", std::isnan(lm.unstable_planar_hz) ? Json() : Json(lm.unstable_planar_hz))
      .set("stable", lm.modes.eigenvalues.front() > 0)
      .set("equilibrium_newton_iterations", lm.equilibrium.iterations)
      .set("equilibrium_residual_N", lm.equilibrium.residual)
      .set("stiffness_asymmetry", lm.asymmetry)
      .set("finite_difference_stiffness", lm.fd.eigenvalues.empty() ? Json() : fd_json(lm.fd))
      .set("operator_solves", static_cast<double>(lm.modes.operator_products))
      .set("frequencies_hz", std::move(freqs));
}

}  // namespace

Scene modal_scene(const Scene& scene) {
  refuse_self_contact(scene, "modes (the linearization)");
  Scene s = scene;
  s.terms.wind = false;
  s.wind_velocity_m_per_s = {0.0, 0.0, 0.0};
  return s;
}

std::vector<NodeRef> compared_crossings(const Scene& scene) {
  const int stride = std::max(1, scene.fem.stride);
  std::vector<NodeRef> out;
  for (int j = 0; j < scene.nodes_v(); j += stride)
    for (int i = 0; i < scene.nodes_u(); i += stride) out.push_back({i, j});
  return out;
}

int crossing_position_dof(const Model& model, const NodeRef& node) {
  if (const auto* yarn = dynamic_cast<const YarnModel*>(&model))
    return yarn->grid().dofs(yarn->grid().node(node.i, node.j)).x;
  if (const auto* fem = dynamic_cast<const FemModel*>(&model)) return 3 * fem->vertex_of_node(node);
  throw std::invalid_argument("modes: model '" + model.name() + "' has no crossings");
}

namespace {

// Backward Euler (be-linear, one solve with M − h²K per step) from (q, v = 0):
// its numerical damping takes the released cloth to rest. A run that fails
// (e.g. sliding coordinates that cross after a long step) is repeated at the
// next shorter step; `how` names the run that settled, or why none did.
std::optional<Vec> settle(Model& model, const Vec& q, std::string& how) {
  how.clear();
  for (double h : kSettleSteps) {
    auto be = make_integrator("be-linear");
    IntegratorOptions io;
    io.dt = h;
    be->on_step = [](const StepRecord&) { throw_if_interrupted(); };
    be->initialize(model, 0.0, q, Vec::Zero(model.num_dofs()), io);
    const StepResult sr = be->advance_to(kSettleTime);
    char text[160];
    if (sr.outcome == Outcome::ok) {
      std::snprintf(text, sizeof text, "backward Euler (be-linear) at h = %g s for %g s", h, kSettleTime);
      how += text;
      return be->q();
    }
    std::snprintf(text, sizeof text, "backward Euler at h = %g s ended '%s' at t = %g s (", h, to_string(sr.outcome),
                  be->t());
    how += text + sr.message + "); ";
  }
  how = "settling failed: " + how;
  return std::nullopt;
}

// K by central differences of the full force, whose frozen inputs (contact
// normal forces F_n, friction's F_u) are recomputed at every state (docs/models.md
// §5.4, §10.2), kept on the model's sparsity pattern; `outside` gets the
// Frobenius norm of what falls outside it.
SparseMatrix finite_difference_stiffness(Model& model, const Vec& q, double& outside) {
  const int n = model.num_dofs();
  Evaluation e;
  allocate_evaluation(model, e);
  const Vec zero = Vec::Zero(n);
  SparseMatrix k = model.pattern();
  k.coeffRef(0, 0);  // keeps the pattern's structure; values set below
  for (int i = 0; i < k.nonZeros(); ++i) k.valuePtr()[i] = 0.0;
  outside = 0.0;
  Vec plus, qh = q;
  for (int j = 0; j < n; ++j) {
    const double h = 1e-6 * std::max(1e-3, std::abs(q[j]));  // positions ~1e-2 m, sliding coordinates ~1e-2 m
    throw_if_interrupted();
    qh[j] = q[j] + h;
    model.evaluate(0.0, qh, zero, kForce, e);
    plus = e.force;
    qh[j] = q[j] - h;
    model.evaluate(0.0, qh, zero, kForce, e);
    qh[j] = q[j];
    Vec column = -(plus - e.force) / (2 * h);  // K = −∂f/∂q
    for (SparseMatrix::InnerIterator it(k, j); it; ++it) {
      it.valueRef() = column[it.row()];
      column[it.row()] = 0.0;
    }
    outside += column.squaredNorm();
  }
  outside = std::sqrt(outside);
  model.evaluate(0.0, q, zero, kForce, e);  // the auxiliaries of q again
  return k;
}

// K = −∂f/∂q and M at (q*, v = 0) (docs/models.md §10.1), the modes of K's
// symmetric part, and their position components at the crossings.
void linearize(Model& model, const std::vector<NodeRef>& crossings, const ModalOptions& options, bool fd_check,
               LinearizedModes& lm) {
  Evaluation e;
  allocate_evaluation(model, e);
  model.evaluate(0.0, lm.q, Vec::Zero(model.num_dofs()), kForce | kDfdq | kMass, e);
  const SparseMatrix k = -e.dfdq;
  lm.asymmetry = relative_asymmetry(k);
  const SparseMatrix k_sym = 0.5 * (k + SparseMatrix(k.transpose()));
  lm.modes = lowest_modes(k_sym, e.mass, model.fixed_dofs(), options);
  if (!lm.modes.ok) return;
  if (fd_check) {
    double outside = 0;
    const SparseMatrix k_fd = finite_difference_stiffness(model, lm.q, outside);
    const double norm = k_fd.norm();
    lm.fd.asymmetry = relative_asymmetry(k_fd);
    lm.fd.difference = SparseMatrix(k_fd - k).norm() / norm;
    lm.fd.outside_pattern = outside / norm;
    const ModalResult fd_modes =
        lowest_modes(0.5 * (k_fd + SparseMatrix(k_fd.transpose())), e.mass, model.fixed_dofs(), options);
    if (fd_modes.ok) lm.fd.eigenvalues = fd_modes.eigenvalues;
  }
  const int count = static_cast<int>(lm.modes.eigenvalues.size());
  lm.crossing_shapes.resize(3 * static_cast<Eigen::Index>(crossings.size()), count);
  for (size_t c = 0; c < crossings.size(); ++c) {
    const int x = crossing_position_dof(model, crossings[c]);
    lm.crossing_shapes.middleRows(3 * c, 3) = lm.modes.shapes.middleRows(x, 3);
  }
}

}  // namespace

LinearizedModes linearized_modes(Model& model, const std::vector<NodeRef>& crossings, const ModalOptions& options,
                                 double lean_m, bool fd_check) {
  LinearizedModes lm;
  lm.model = model.name();
  lm.q = model.initial_q();
  EquilibriumSolver equilibrium(model, {});
  EquilibriumOptions eo;
  eo.max_iterations = 200;
  eo.atol = 1e-12;                      // [N]; the weight of one crossing is ~2e-5 N
  eo.stop_requested = signal_received;  // a signal: Interrupted after the solve
  lm.equilibrium = equilibrium.solve(lm.q, eo);
  throw_if_interrupted();
  lm.route = "Newton from the rest state";
  if (!lm.equilibrium.converged) {
    const std::string first = lm.equilibrium.message;
    std::string how;
    const std::optional<Vec> settled = settle(model, model.initial_q(), how);
    if (!settled) {
      lm.equilibrium.message = "Newton from rest: " + first + "; " + how;
      return lm;
    }
    lm.q = *settled;
    lm.equilibrium = equilibrium.solve(lm.q, eo);
    throw_if_interrupted();
    lm.route = how + " from rest, then Newton (Newton from rest: " + first + ")";
    if (!lm.equilibrium.converged) return lm;
  }
  linearize(model, crossings, options, fd_check, lm);
  if (!lm.modes.ok || lm.modes.eigenvalues.front() >= 0 || lean_m <= 0) return lm;

  // The hang in the cloth's plane is unstable (ω² < 0: it buckles out of
  // plane). Lean every crossing out of plane by lean_m·(row / last row), let
  // the cloth settle into a stable hang, and take Newton's equilibrium there.
  lm.unstable_planar_hz = frequency_hz(lm.modes.eigenvalues.front());
  int last_row = 0;
  for (const NodeRef& n : crossings) last_row = std::max(last_row, n.j);
  Vec leaning = lm.q;
  for (const NodeRef& n : crossings)
    leaning[crossing_position_dof(model, n) + 1] += lean_m * n.j / std::max(last_row, 1);
  std::string how;
  const std::optional<Vec> settled = settle(model, leaning, how);
  if (!settled) {
    lm.equilibrium.converged = false;
    lm.equilibrium.message = "the planar hang is unstable and the leaning cloth did not settle: " + how;
    return lm;
  }
  lm.q = *settled;
  lm.equilibrium = equilibrium.solve(lm.q, eo);
  throw_if_interrupted();
  char lean[160];
  std::snprintf(lean, sizeof lean,
                "; the planar hang is unstable (lowest %.4g Hz): leaned %g m out of plane at the bottom row, ",
                lm.unstable_planar_hz, lean_m);
  lm.route += lean + how + ", then Newton";
  if (lm.equilibrium.converged) linearize(model, crossings, options, fd_check, lm);
  return lm;
}

namespace {

// modes.json of a run a signal ended in `stage` (driver/interrupted_record.h), with the
// yarn level's equilibrium and modes when they were reached; the Interrupted to pass on.
Interrupted interrupted_modes(const ModesConfig& c, const std::string& stage, const ModesResult& r) {
  Json j = Json::object();
  mark_interrupted(j, stage);
  j.set("scene", scene_json(c.scene_path, c.scene.text, c.scene, {}));
  j.set("continuum_parameters", c.fem_params ? c.fem_params->string() : "the scene's (first guess without a file)");
  if (!r.yarn.modes.eigenvalues.empty()) j.set("yarn", model_json(r.yarn, static_cast<int>(r.yarn.q.size())));
  j.set("created", utc_now());
  add_provenance(j);
  std::filesystem::create_directories(c.out_dir);
  write_file_atomically(c.out_dir / "modes.json", j.dump());
  return Interrupted{stage};
}

}  // namespace

ModesResult run_modes(const ModesConfig& c) {
  const Scene yarn_scene = modal_scene(c.scene);
  Scene fem_scene = yarn_scene;
  if (c.fem_params) fem_scene.fem.parameter_file = c.fem_params->string();
  (void)fem_material(fem_scene);  // a bad file: FemParameterError, before anything is written
  const std::vector<NodeRef> crossings = compared_crossings(fem_scene);
  std::unique_ptr<Model> yarn = make_model(yarn_scene, yarn_level_model(yarn_scene)),
                         fem = make_model(fem_scene, "fem");
  const int most = static_cast<int>(std::min(yarn->num_dofs() - yarn->fixed_dofs().size(),
                                             fem->num_dofs() - fem->fixed_dofs().size())) -
                   1;
  if (!(c.lean_m >= 0) || !std::isfinite(c.lean_m))
    throw std::invalid_argument("--lean: got " + std::to_string(c.lean_m) + ", expected a length >= 0 [m]");
  if (c.count < 1 || c.count > most)
    throw std::invalid_argument("--count: got " + std::to_string(c.count) + ", expected 1 … " + std::to_string(most) +
                                " (the free DoFs of the smaller model, less one)");

  ModalOptions options;
  options.count = c.count;
  ModesResult r;
  for (auto [model, out] : {std::pair{yarn.get(), &r.yarn}, std::pair{fem.get(), &r.fem}}) {
    if (c.progress)
      std::fprintf(stderr, "modes: %s model (%d DoFs): equilibrium, K, %d modes\n", model->name().c_str(),
                   model->num_dofs(), c.count);
    try {
      *out = linearized_modes(*model, crossings, options, c.lean_m, c.fd_check);
      throw_if_interrupted();  // a signal during the eigensolve
    } catch (const Interrupted&) {
      throw interrupted_modes(c, model->name() == "fem" ? "the continuum's modes" : "the yarn level's modes", r);
    }
    if (!out->equilibrium.converged)
      throw std::runtime_error("no " + model->name() + " equilibrium: " + out->equilibrium.message);
    if (!out->modes.ok) throw std::runtime_error(model->name() + " modes: " + out->modes.message);
    if (c.progress && !out->fd.eigenvalues.empty())
      std::fprintf(stderr,
                   "modes: %s: K by central differences of the full force: asymmetry %.3g, %.3g from the assembled "
                   "K (%.3g outside its pattern); lowest %.4g Hz (assembled %.4g Hz)\n",
                   model->name().c_str(), out->fd.asymmetry, out->fd.difference, out->fd.outside_pattern,
                   frequency_hz(out->fd.eigenvalues.front()), frequency_hz(out->modes.eigenvalues.front()));
    if (c.progress)
      std::fprintf(stderr, "modes: %s: equilibrium by %s: %d Newton iterations, residual %.3g N; asymmetry %.3g\n",
                   model->name().c_str(), out->route.c_str(), out->equilibrium.iterations, out->equilibrium.residual,
                   out->asymmetry);
  }
  r.mac = mac_matrix(r.yarn.crossing_shapes, r.fem.crossing_shapes);
  // How far apart the two equilibria are at the compared crossings.
  double sum = 0;
  for (const NodeRef& n : crossings) {
    const double d =
        (r.yarn.q.segment<3>(crossing_position_dof(*yarn, n)) - r.fem.q.segment<3>(crossing_position_dof(*fem, n)))
            .norm();
    sum += d * d;
    r.equilibrium_max_m = std::max(r.equilibrium_max_m, d);
  }
  r.equilibrium_rms_m = std::sqrt(sum / double(crossings.size()));
  r.pairs = match_modes(r.mac);

  // Output, only after everything succeeded.
  std::filesystem::create_directories(c.out_dir);
  const int n = c.count;
  std::vector<int> fem_partner(n, -1);
  std::vector<double> fem_sign(n, 1.0), yarn_sign(n, 1.0);
  for (const ModePair& p : r.pairs) {
    fem_partner[p.b] = p.a;
    if (r.yarn.crossing_shapes.col(p.a).dot(r.fem.crossing_shapes.col(p.b)) < 0) fem_sign[p.b] = -1.0;
  }
  CsvTable table(c.out_dir / "modes.csv", {"model", "mode", "frequency_hz", "eigenvalue_per_s2", "paired_mode",
                                           "paired_frequency_hz", "mac", "frequency_ratio_fem_to_yarn"});
  const auto& fy = r.yarn.modes.eigenvalues;
  const auto& ff = r.fem.modes.eigenvalues;
  for (const ModePair& p : r.pairs)
    table.row({"yarn", std::to_string(p.a), csv_number(frequency_hz(fy[p.a])), csv_number(fy[p.a]), std::to_string(p.b),
               csv_number(frequency_hz(ff[p.b])), csv_number(p.mac),
               csv_number(frequency_hz(ff[p.b]) / frequency_hz(fy[p.a]))});
  for (int b = 0; b < n; ++b) {
    const int a = fem_partner[b];
    table.row({"fem", std::to_string(b), csv_number(frequency_hz(ff[b])), csv_number(ff[b]), std::to_string(a),
               csv_number(frequency_hz(fy[a])), csv_number(r.mac(a, b)),
               csv_number(frequency_hz(ff[b]) / frequency_hz(fy[a]))});
  }
  std::vector<std::string> columns{"yarn_mode"};
  for (int b = 0; b < n; ++b) columns.push_back("fem_" + std::to_string(b));
  CsvTable mac(c.out_dir / "mac.csv", columns);
  for (int a = 0; a < n; ++a) {
    std::vector<std::string> row{std::to_string(a)};
    for (int b = 0; b < n; ++b) row.push_back(csv_number(r.mac(a, b)));
    mac.row(row);
  }
  write_file_atomically(c.out_dir / "modes_yarn.vtu", mode_vtu(*yarn, yarn_scene, r.yarn, yarn_sign));
  write_file_atomically(c.out_dir / "modes_fem.vtu", mode_vtu(*fem, fem_scene, r.fem, fem_sign));

  Json j = Json::object();
  j.set("scene", scene_json(c.scene_path, c.scene.text, c.scene, {}));
  j.set("linearized_about", "static equilibrium under gravity, wind off, v = 0 (Newton from the rest state)");
  j.set("continuum_parameters", c.fem_params ? c.fem_params->string() : "the scene's (first guess without a file)");
  j.set("compared_crossings", static_cast<int>(crossings.size()));
  j.set("equilibria_rms_distance_m", r.equilibrium_rms_m);
  j.set("equilibria_max_distance_m", r.equilibrium_max_m);
  j.set("yarn", model_json(r.yarn, yarn->num_dofs()));
  j.set("fem", model_json(r.fem, fem->num_dofs()));
  Json pairs = Json::array();
  for (const ModePair& p : r.pairs)
    pairs.push(Json::object()
                   .set("yarn_mode", p.a)
                   .set("fem_mode", p.b)
                   .set("mac", p.mac)
                   .set("yarn_hz", frequency_hz(fy[p.a]))
                   .set("fem_hz", frequency_hz(ff[p.b])));
  j.set("pairs", std::move(pairs));
  j.set("created", utc_now());
  add_provenance(j);
  table.commit();
  mac.commit();
  write_file_atomically(c.out_dir / "modes.json", j.dump());
  return r;
}

}  // namespace wl
