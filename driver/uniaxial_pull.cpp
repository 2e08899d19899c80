#include "driver/uniaxial_pull.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "calibration/equilibrium.h"
#include "driver/interrupted_record.h"
#include "models/knit/knit_model.h"
#include "models/knit/knit_rest_shape.h"
#include "models/model_factory.h"
#include "models/yarn/yarn_model.h"
#include "output/atomic_file.h"
#include "output/csv_table.h"
#include "output/json_writer.h"

namespace wl {
namespace {

// The grips: the position DoF x of each node of the near and far grip, and
// every sliding coordinate DoF of those nodes.
struct Grips {
  std::vector<int> near_x, far_x, coordinates;
  std::vector<int> all_x;  // x of every node
};

Grips knit_grips(const KnitModel& m, char direction) {
  const KnitGraph& g = m.graph();
  const int courses = g.layout().courses, wales = g.layout().wales;
  Grips grips;
  auto take = [&](int r, int c, std::vector<int>& x) {
    for (int s : {0, 1})
      for (int e : {0, 1}) {
        const KnitNode& n = g.node(g.contact_node(r, c, s, e));
        x.push_back(n.x_dof);
        for (int k : n.coord)
          if (is_dof(k)) grips.coordinates.push_back(k);
      }
  };
  for (const KnitNode& n : g.nodes()) grips.all_x.push_back(n.x_dof);
  if (direction == 'y')
    for (int c = 0; c < wales; ++c) take(-1, c, grips.near_x), take(courses - 1, c, grips.far_x);
  else
    for (int r = -1; r < courses; ++r) take(r, 0, grips.near_x), take(r, wales - 1, grips.far_x);
  return grips;
}

Grips woven_grips(const YarnModel& m, char direction) {
  const WovenGrid& g = m.grid();
  Grips grips;
  auto take = [&](int i, int j, std::vector<int>& x) {
    const NodeDofs& d = g.dofs(g.node(i, j));
    x.push_back(d.x);
    for (int k : {d.u, d.v})
      if (is_dof(k)) grips.coordinates.push_back(k);
  };
  for (int n = 0; n < g.num_nodes(); ++n) grips.all_x.push_back(g.dofs(n).x);
  if (direction == 'y')
    for (int i = 0; i < g.nu(); ++i) take(i, 0, grips.near_x), take(i, g.nv() - 1, grips.far_x);
  else
    for (int j = 0; j < g.nv(); ++j) take(0, j, grips.near_x), take(g.nu() - 1, j, grips.far_x);
  return grips;
}

// Total yarn length: the span of each yarn's coordinates (knit: course by
// course; woven: every warp and weft between the outer ring).
double yarn_length(const Model& model, const Vec& q) {
  if (const auto* k = dynamic_cast<const KnitModel*>(&model)) {
    double total = 0.0;
    for (int y = 0; y < static_cast<int>(k->graph().yarns().size()); ++y) total += k->yarn_length(q, y);
    return total;
  }
  const WovenGrid& g = dynamic_cast<const YarnModel&>(model).grid();
  return g.spacing() * (g.nv() * (g.nu() - 1) + g.nu() * (g.nv() - 1));
}

std::string pull_json(const Scene& scene, const PullConfig& config, const PullResult& r) {
  Json j = Json::object();
  j.set("scene", scene.source);
  j.set("cloth", scene.knit ? "knit" : "woven");
  j.set("direction", std::string(1, config.direction));
  j.set("grip_distance_m", r.grip_distance_m);
  j.set("grip_width_m", r.grip_width_m);
  j.set("yarn_length_m", r.yarn_length_m);
  j.set("yarn_length_per_area_per_m", r.yarn_length_per_area_per_m);
  j.set("complete", r.complete);
  j.set("message", r.message);
  if (!r.interrupted_in.empty()) mark_interrupted(j, r.interrupted_in);
  return j.dump() + "\n";
}

}  // namespace

PullResult run_pull(const Scene& scene_in, const PullConfig& config) {
  if (scene_in.pose != Scene::Pose::flat)
    throw std::invalid_argument("pull: the scene must be flat ([pose] kind = \"flat\"), got upright");
  if (config.direction != 'x' && config.direction != 'y')
    throw std::invalid_argument("pull: --direction must be x or y");
  if (config.strains.empty()) throw std::invalid_argument("pull: --strains: empty ladder");
  for (size_t k = 0; k < config.strains.size(); ++k)
    if (!(config.strains[k] > (k ? config.strains[k - 1] : 0.0)) || !std::isfinite(config.strains[k]))
      throw std::invalid_argument("pull: --strains must be finite, > 0 and increasing");
  Scene scene = scene_in;
  scene.pins.clear();
  scene.handles.clear();
  scene.obstacles.clear();
  scene.self_contact.enabled = false;
  TermSwitches& on = scene.terms;
  on.gravity = on.wind = on.handles = on.friction = on.inertia = false;
  scene.yarn_viscosity_Pa_s = 0.0;
  std::unique_ptr<Model> model = make_model(scene, yarn_level_model(scene));
  Grips grips;
  if (const auto* k = dynamic_cast<const KnitModel*>(model.get())) grips = knit_grips(*k, config.direction);
  else grips = woven_grips(dynamic_cast<const YarnModel&>(*model), config.direction);

  const int axis = config.direction == 'x' ? 0 : 1, across = 1 - axis;
  const Vec q0 = model->initial_q();
  auto mean = [&](const std::vector<int>& xs, int c) {
    double s = 0.0;
    for (int x : xs) s += q0[x + c];
    return s / static_cast<double>(xs.size());
  };
  PullResult out;
  out.grip_distance_m = mean(grips.far_x, axis) - mean(grips.near_x, axis);
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (int x : grips.far_x) lo = std::min(lo, q0[x + across]), hi = std::max(hi, q0[x + across]);
  out.grip_width_m = hi - lo;
  out.yarn_length_m = yarn_length(*model, q0);
  out.yarn_length_per_area_per_m = out.yarn_length_m / (out.grip_distance_m * out.grip_width_m);

  std::vector<int> held = grips.coordinates;
  if (config.hold_z)
    for (int x : grips.all_x) held.push_back(x + 2);
  for (const auto* xs : {&grips.near_x, &grips.far_x})
    for (int x : *xs)
      for (int c = 0; c < 3; ++c) held.push_back(x + c);
  EquilibriumSolver eq(*model, held);
  Evaluation eval;
  allocate_evaluation(*model, eval);
  EquilibriumOptions options;
  // Newton on the residual (docs/calibration.md §1); where its line search fails (a knit's free
  // edges: indefinite stiffness), energy descent to 10⁻⁹ of the stiffest yarn's k_s.
  options.descent_tolerance = kKnitRestTolerance * stiffest_yarn_N(scene);
  options.stop_requested = signal_received;
  Vec q = q0;
  double previous = 0.0;
  std::vector<double> ladder{0.0};
  ladder.insert(ladder.end(), config.strains.begin(), config.strains.end());
  for (double lambda : ladder) {
    if (signal_received()) {  // a rung whose warm start is its equilibrium asks no stop hook
      out.interrupted_in = "the strain " + csv_number(lambda) + " rung";
      out.complete = false;
      break;
    }
    // Warm start: the previous equilibrium stretched affinely from the near grip.
    const double base = mean(grips.near_x, axis), scale = (1.0 + lambda) / (1.0 + previous);
    for (int x : grips.all_x) q[x + axis] = base + (q[x + axis] - base) * scale;
    for (int x : grips.near_x) q[x + axis] = q0[x + axis];
    for (int x : grips.far_x) q[x + axis] = q0[x + axis] + lambda * out.grip_distance_m;
    const EquilibriumResult r = eq.solve(q, options);
    PullPoint point{lambda, 0.0, r.residual, r.iterations + r.descent_steps};
    if (!r.converged) {
      if (r.stopped) out.interrupted_in = "the strain " + csv_number(lambda) + " rung";
      out.complete = false;
      std::ostringstream why;
      why << "strain " << lambda << ": " << r.message;
      out.message = why.str();
      break;
    }
    model->evaluate(0.0, q, Vec::Zero(q.size()), kForce, eval);
    double pull = 0.0;
    for (int x : grips.far_x) pull -= eval.force[x + axis];
    point.force_per_width_N_per_m = pull / out.grip_width_m;
    out.points.push_back(point);
    previous = lambda;
  }
  return out;
}

PullResult pull_command(const Scene& scene, const PullConfig& config) {
  const PullResult r = run_pull(scene, config);
  std::filesystem::create_directories(config.out_dir);
  CsvTable csv(config.out_dir / "pull.csv", {"strain", "force_per_width_N_per_m", "newton_iterations", "residual_N"});
  for (const PullPoint& p : r.points)
    csv.row({csv_number(p.strain), csv_number(p.force_per_width_N_per_m), std::to_string(p.newton_iterations),
             csv_number(p.residual_N)});
  csv.commit();
  write_file_atomically(config.out_dir / "pull.json", pull_json(scene, config, r));
  if (!r.interrupted_in.empty()) throw Interrupted{r.interrupted_in};
  return r;
}

}  // namespace wl
