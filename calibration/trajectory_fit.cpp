#include "calibration/trajectory_fit.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <functional>
#include <limits>
#include <memory>

#include <ceres/ceres.h>
#include <Eigen/Sparse>

#include "calibration/fit_stopping.h"
#include "calibration/optimum_statistics.h"
#include "calibration/parallel_starts.h"
#include "calibration/scene_parameters.h"
#include "integrators/integrator.h"
#include "models/fem/fem_model.h"
#include "models/knit/knit_model.h"
#include "models/model_factory.h"
#include "models/scene/parameter_keys.h"
#include "models/yarn/yarn_model.h"

namespace wl {
namespace {

using SpMat = Eigen::SparseMatrix<double>;
using Clock = std::chrono::steady_clock;

// H_k per frame (3·points × DoFs) and which points it sees: a point the model
// cannot observe (a crossing outside the continuum's mesh) has zero rows and is
// not compared.
struct Observation {
  std::vector<SpMat> H;
  std::vector<std::vector<char>> seen;  // per frame, per point
  int min_seen = 0;                     // fewest points seen in a frame
};

// Whether the relaxed tile of a knit, its rest shape, depends on the parameter: the tile
// relaxes with stretch, bending, the stitch-length penalty and contact compression (not the
// roll, the mass or the loads; docs/models.md §11.3, §11.6).
bool shapes_knit_rest(const std::string& key) {
  auto ends_with = [&](const std::string& field) {
    return key.size() > field.size() && key.compare(key.size() - field.size(), field.size(), field) == 0;
  };
  return key == kStitchLengthStiffnessKey || key == kCompressionStiffnessKey ||
         (key.rfind("yarn_types.", 0) == 0 && (ends_with(kStretchModulusField) || ends_with(kBendingModulusField)));
}

// Every point seen in every frame, point k at the DoFs dof_of(k) … +2.
Observation direct(int n, const Model& model, size_t frames, const std::function<int(int)>& dof_of) {
  std::vector<Eigen::Triplet<double>> t;
  for (int k = 0; k < n; ++k)
    for (int c = 0; c < 3; ++c) t.emplace_back(3 * k + c, dof_of(k) + c, 1.0);
  SpMat h(3 * n, model.num_dofs());
  h.setFromTriplets(t.begin(), t.end());
  return {std::vector<SpMat>(frames, h), std::vector<std::vector<char>>(frames, std::vector<char>(n, 1)), n};
}

Observation observe(const Model& model, const std::string& name, const std::vector<TargetFrame>& frames) {
  const int n = static_cast<int>(frames.front().points.rows());
  auto mismatch = [&](const std::string& what, int count) {
    return TrajectoryFitError("the target has " + std::to_string(n) + " points per frame, the scene's " + name +
                              " model " + std::to_string(count) + " " + what + ": not a run of this scene");
  };
  if (const auto* knit = dynamic_cast<const KnitModel*>(&model)) {  // a knit's contact nodes (docs/models.md §11.1)
    const KnitGraph& g = knit->graph();
    if (g.num_nodes() != n) throw mismatch("nodes", g.num_nodes());
    return direct(n, model, frames.size(), [&](int k) { return g.node(k).x_dof; });
  }
  if (name == "yarn") {
    const auto& yarn = dynamic_cast<const YarnModel&>(model);
    if (yarn.grid().num_nodes() != n) throw mismatch("nodes", yarn.grid().num_nodes());
    return direct(n, model, frames.size(), [&](int k) { return yarn.grid().dofs(k).x; });
  }
  const auto& fem = dynamic_cast<const FemModel&>(model);
  if (frames.front().uv.empty()) {  // no material coordinates: a continuum run, observed at its vertices
    if (fem.mesh().num_vertices() != n) throw mismatch("vertices", fem.mesh().num_vertices());
    return direct(n, model, frames.size(), [](int k) { return 3 * k; });
  }
  // A yarn-level run: the continuum interpolated at each crossing's material point.
  Observation o;
  o.min_seen = n;
  for (const TargetFrame& f : frames) {
    std::vector<Eigen::Triplet<double>> t;
    std::vector<char> seen(n, 0);
    for (int k = 0; k < n; ++k) {
      std::array<int, 3> v;
      Vec3 w;
      if (!fem.surface_weights(f.uv[k], &v, &w)) continue;
      seen[k] = 1;
      for (int a = 0; a < 3; ++a)
        for (int c = 0; c < 3; ++c) t.emplace_back(3 * k + c, 3 * v[a] + c, w[a]);
    }
    o.min_seen = std::min(o.min_seen, static_cast<int>(std::count(seen.begin(), seen.end(), 1)));
    SpMat h(3 * n, model.num_dofs());
    h.setFromTriplets(t.begin(), t.end());
    o.H.push_back(std::move(h));
    o.seen.push_back(std::move(seen));
  }
  return o;
}

// One simulation at parameter values p: per frame the observed positions and
// their derivatives in p.
struct Simulation {
  bool ok = false;
  std::string message;
  std::vector<Vec> y;
  std::vector<Eigen::MatrixXd> dy;
};

class Simulator {
 public:
  Simulator(const Scene& scene, const std::vector<TargetFrame>& frames, const TrajectoryFitOptions& opt)
      : scene_(scene), frames_(frames), opt_(opt) {
    // The sensitivities are exact only with F_n and F_u differentiated (docs/models.md §3.6.1).
    scene_.exact_contact_jacobian = true;
    integrator_ = opt.integrator.empty() ? scene.integrator : opt.integrator;
    if (!make_integrator(integrator_)->offers_sensitivities())
      throw TrajectoryFitError("integrator '" + integrator_ +
                               "' offers no parameter sensitivities; use be-linear, be-newton or sdirk2");
    const std::unique_ptr<Model> model = make_model(scene, opt.model);
    const std::vector<std::string> keys = model->parameter_keys();
    for (const std::string& key : opt.free) {
      scene_parameter(scene, key);  // throws ParameterKeyError for an unknown key
      if (opt.model == "knit" && shapes_knit_rest(key))
        throw TrajectoryFitError("parameter '" + key +
                                 "': the knit's initial state, its relaxed rest shape (docs/models.md §11.3), "
                                 "depends on it, and the forward sensitivities start from dq/dp = 0 at t = 0; "
                                 "fit a knit's yarn density or knit.roll_stiffness_N (docs/calibration.md §8.1)");
      if (std::find(keys.begin(), keys.end(), key) == keys.end())
        throw TrajectoryFitError("parameter '" + key + "': the " + opt.model +
                                 " model of this scene does not depend on it (or it is zero)");
    }
    obs_ = observe(*model, opt.model, frames);
  }

  Simulation run(const std::vector<double>& p) {
    ++count_;
    Scene s = scene_;
    for (size_t k = 0; k < p.size(); ++k) set_scene_parameter(s, opt_.free[k], p[k]);
    Simulation sim;
    try {
      const std::unique_ptr<Model> model = make_model(s, opt_.model);
      const std::unique_ptr<Integrator> in = make_integrator(integrator_);
      in->track_sensitivities(opt_.free);
      in->on_step = [this](const StepRecord&) {
        if (stop_requested()) throw Stopped{};
      };
      IntegratorOptions io;  // the scene's step, or its error control when adaptive
      io.dt = s.dt_s;
      io.adaptive = s.adaptive;
      io.rtol = s.rtol;
      io.atol = s.atol;
      in->initialize(*model, 0.0, model->initial_q(), model->initial_v(), io);
      for (size_t k = 0; k < frames_.size(); ++k) {
        const StepResult r = in->advance_to(frames_[k].time);
        if (r.outcome != Outcome::ok) {
          sim.message = std::string(to_string(r.outcome)) + " at t = " + std::to_string(in->t()) + " s: " + r.message;
          return sim;
        }
        sim.y.push_back(obs_.H[k] * in->q());
        sim.dy.push_back(obs_.H[k] * in->dq_dp());
      }
    } catch (const std::invalid_argument& e) {  // parameter values the model rejects
      sim.message = e.what();
      return sim;
    } catch (const Stopped&) {
      sim.message = "interrupted";
      return sim;
    }
    sim.ok = true;
    return sim;
  }
  bool stop_requested() const { return opt_.stop_requested && opt_.stop_requested(); }

  const Observation& observation() const { return obs_; }
  int count() const { return count_; }

 private:
  struct Stopped {};  // from a step callback, to end a simulation at once
  Scene scene_;       // a copy: the fit differentiates F_n and F_u in it
  const std::vector<TargetFrame>& frames_;
  const TrajectoryFitOptions& opt_;
  std::string integrator_;
  Observation obs_;
  int count_ = 0;
};

// RMS distance per frame over the points seen in it.
std::vector<double> frame_rms(const Simulation& sim, const std::vector<TargetFrame>& frames, const Observation& o) {
  std::vector<double> rms;
  for (size_t k = 0; k < frames.size(); ++k) {
    double sum = 0;
    int seen = 0;
    for (Eigen::Index i = 0; i < frames[k].points.rows(); ++i) {
      if (!o.seen[k][i]) continue;
      sum += (sim.y[k].segment<3>(3 * i) - frames[k].points.row(i).transpose()).squaredNorm();
      ++seen;
    }
    rms.push_back(std::sqrt(sum / std::max(seen, 1)));
  }
  return rms;
}

// The simulations a fit has at hand: the last one run and the one at the point
// Ceres last accepted, so that a rejected last trial step costs no rerun for the
// statistics and the final positions.
struct SimulationCache {
  Simulation last, accepted;
  std::vector<double> last_p, accepted_p;

  const Simulation& at(Simulator& sim, const std::vector<double>& p) {
    if (p == last_p && last.ok) return last;  // Ceres asks for the Jacobian at the point it just evaluated
    if (p == accepted_p && accepted.ok) {
      last = accepted;
    } else {
      last = sim.run(p);
    }
    last_p = p;
    return last;
  }
};

std::vector<double> exp_of(const double* theta, int n) {
  std::vector<double> p(n);
  for (int k = 0; k < n; ++k) p[k] = std::exp(theta[k]);
  return p;
}

// The residuals r = H_k q(t_k) − y_k over the points seen (zero rows for the
// others), frame after frame, and their Jacobian in θ = log p, dr/dθ = H_k (∂q/∂p) p.
Eigen::VectorXd residuals_of(const Simulation& sim, const std::vector<TargetFrame>& frames, const Observation& o) {
  Eigen::VectorXd r =
      Eigen::VectorXd::Zero(static_cast<Eigen::Index>(3 * frames.front().points.rows() * frames.size()));
  Eigen::Index row = 0;
  for (size_t f = 0; f < frames.size(); ++f)
    for (Eigen::Index i = 0; i < frames[f].points.rows(); ++i, row += 3)
      if (o.seen[f][i]) r.segment<3>(row) = sim.y[f].segment<3>(3 * i) - frames[f].points.row(i).transpose();
  return r;
}

Eigen::MatrixXd jacobian_of(const Simulation& sim, const std::vector<double>& p, const std::vector<TargetFrame>& frames,
                            const Observation& o) {
  const Eigen::Index n = static_cast<Eigen::Index>(p.size());
  Eigen::MatrixXd j =
      Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(3 * frames.front().points.rows() * frames.size()), n);
  const Eigen::VectorXd scale = Eigen::Map<const Eigen::VectorXd>(p.data(), n);
  Eigen::Index row = 0;
  for (size_t f = 0; f < frames.size(); ++f)
    for (Eigen::Index i = 0; i < frames[f].points.rows(); ++i, row += 3)
      if (o.seen[f][i]) j.middleRows<3>(row) = sim.dy[f].middleRows<3>(3 * i) * scale.asDiagonal();
  return j;
}

class TrajectoryCost final : public ceres::CostFunction {
 public:
  TrajectoryCost(Simulator& sim, const std::vector<TargetFrame>& frames, SimulationCache* cache, int n)
      : sim_(sim), frames_(frames), cache_(cache) {
    set_num_residuals(static_cast<int>(3 * frames.front().points.rows() * frames.size()));
    mutable_parameter_block_sizes()->push_back(n);
  }

  bool Evaluate(double const* const* x, double* residuals, double** jacobians) const override {
    const int n = parameter_block_sizes()[0], m = num_residuals();
    const std::vector<double> p = exp_of(x[0], n);
    const Simulation& last = cache_->at(sim_, p);
    if (!last.ok) return false;  // Ceres retries with a shorter step
    Eigen::Map<Eigen::VectorXd>(residuals, m) = residuals_of(last, frames_, sim_.observation());
    if (jacobians && jacobians[0])
      Eigen::Map<Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(jacobians[0], m, n) =
          jacobian_of(last, p, frames_, sim_.observation());
    return true;
  }

 private:
  Simulator& sim_;
  const std::vector<TargetFrame>& frames_;
  SimulationCache* cache_;
};

// Per iteration: the cost, the accepted point's simulation kept, progress, and
// the flat-cost rule (fit_stopping.h) over the accepted iterations' costs.
class WindowProgress final : public ceres::IterationCallback {
 public:
  WindowProgress(const Simulator& sim, SimulationCache* cache, const double* theta, int n, int residuals, bool print,
                 const FlatCostRule& flat, std::vector<double>* history)
      : sim_(sim),
        cache_(cache),
        theta_(theta),
        n_(n),
        residuals_(residuals),
        print_(print),
        flat_(flat),
        history_(history),
        t0_(Clock::now()) {}
  ceres::CallbackReturnType operator()(const ceres::IterationSummary& s) override {
    if (sim_.stop_requested()) return ceres::SOLVER_ABORT;
    history_->push_back(s.cost);
    // θ holds the accepted point (update_state_every_iteration), whose Jacobian Ceres has just asked for.
    if ((s.iteration == 0 || s.step_is_successful) && cache_->last.ok && exp_of(theta_, n_) == cache_->last_p) {
      cache_->accepted = cache_->last;
      cache_->accepted_p = cache_->last_p;
    }
    if (print_)
      std::fprintf(stderr, "  fit iteration %d: cost %.6g (RMS %.4g mm), %d simulations, %.0f s\n", s.iteration, s.cost,
                   1e3 * std::sqrt(2.0 * s.cost / residuals_ * 3.0), sim_.count(),
                   std::chrono::duration<double>(Clock::now() - t0_).count());
    if (s.iteration > 0 && !s.step_is_successful) return ceres::SOLVER_CONTINUE;
    accepted_.push_back(s.cost);
    if (auto why = flat_cost_reason(accepted_, flat_)) {
      stop_reason_ = *why;
      return ceres::SOLVER_TERMINATE_SUCCESSFULLY;
    }
    return ceres::SOLVER_CONTINUE;
  }
  const std::string& stop_reason() const { return stop_reason_; }

 private:
  const Simulator& sim_;
  SimulationCache* cache_;
  const double* theta_;
  int n_;
  int residuals_;
  bool print_;
  FlatCostRule flat_;
  std::vector<double>* history_;
  std::vector<double> accepted_;  // the cost at the start and after each accepted step
  std::string stop_reason_;
  Clock::time_point t0_;
};

double largest(const std::vector<double>& x) {
  return x.empty() ? std::numeric_limits<double>::quiet_NaN() : *std::max_element(x.begin(), x.end());
}

// What a stage's start tells before the solver runs (docs/calibration.md §7.1):
// the free keys the frames do not depend on there (held for the stage), and the
// residual noise σ (fit_stopping.h) from one more simulation a step of
// kNoiseProbeStep in θ along the other keys away.
struct StartProbe {
  std::vector<int> frozen;  // indices into the free keys
  double noise = 0.0;       // 0 when the probe does not simulate
};

constexpr double kNoiseProbeStep = 1e-6;

StartProbe probe_start(Simulator& sim, const Simulation& first, const std::vector<TargetFrame>& frames,
                       const std::vector<double>& theta, const std::vector<double>& upper, bool hold) {
  const int n = static_cast<int>(theta.size());
  const std::vector<double> p0 = exp_of(theta.data(), n);
  const Eigen::VectorXd r0 = residuals_of(first, frames, sim.observation());
  const Eigen::MatrixXd j0 = jacobian_of(first, p0, frames, sim.observation());
  StartProbe probe;
  if (hold) probe.frozen = unidentifiable_columns(j0);
  if (static_cast<int>(probe.frozen.size()) == n) return probe;
  std::vector<double> theta1 = theta;
  Eigen::VectorXd step = Eigen::VectorXd::Zero(n);
  for (int k = 0; k < n; ++k) {
    if (std::find(probe.frozen.begin(), probe.frozen.end(), k) != probe.frozen.end()) continue;
    theta1[k] += theta[k] + kNoiseProbeStep <= upper[k] ? kNoiseProbeStep : -kNoiseProbeStep;
    step[k] = theta1[k] - theta[k];
  }
  const std::vector<double> p1 = exp_of(theta1.data(), n);
  const Simulation second = sim.run(p1);
  if (second.ok)
    probe.noise = residual_noise(r0, j0, residuals_of(second, frames, sim.observation()),
                                 jacobian_of(second, p1, frames, sim.observation()), step);
  return probe;
}

ceres::Solver::Options solver_options(const TrajectoryFitOptions& opt) {
  ceres::Solver::Options so;
  so.linear_solver_type = ceres::DENSE_QR;
  so.max_num_iterations = opt.max_iterations;
  so.function_tolerance = 1e-12;
  so.gradient_tolerance = 1e-14;
  so.parameter_tolerance = 1e-10;
  so.num_threads = 1;
  so.logging_type = ceres::SILENT;
  so.update_state_every_iteration = true;  // for WindowProgress; the iterates are the same either way
  return so;
}

// Why a stage stopped, in words a user can act on.
std::string stop_message(const ceres::Solver::Summary& summary, const WindowProgress& progress, int max_iterations,
                         int frames) {
  if (summary.termination_type == ceres::USER_SUCCESS) return progress.stop_reason();
  if (summary.termination_type != ceres::NO_CONVERGENCE) return summary.message;
  return "stopped at its iteration cap (" + std::to_string(max_iterations) + " iterations over " +
         std::to_string(frames) +
         " frames) with the cost still falling: not converged. Raise --max-iterations, fit a growing window "
         "(--growing-window, shorter first stages), or free fewer keys (--free)";
}

// The fitted keys' values at θ with their bounds, standard errors and identifiability.
std::vector<TrajectoryFitParameter> fitted_parameters(const TrajectoryFitOptions& opt, const std::vector<double>& p0,
                                                      const std::vector<double>& theta,
                                                      const std::vector<double>& lower,
                                                      const std::vector<double>& upper, const OptimumStatistics& stats,
                                                      const std::vector<int>& frozen) {
  const int n = static_cast<int>(theta.size());
  const std::vector<double> p = exp_of(theta.data(), n);
  std::vector<TrajectoryFitParameter> out;
  for (int k = 0; k < n; ++k) {
    TrajectoryFitParameter fp;
    fp.key = opt.free[k];
    fp.start = p0[k];
    fp.value = p[k];
    fp.lower = std::exp(lower[k]);
    fp.upper = std::exp(upper[k]);
    const double span = 1e-6 * (upper[k] - lower[k]);
    fp.at_bound = theta[k] - lower[k] < span || upper[k] - theta[k] < span;
    const auto held = [k](const std::vector<int>& v) { return std::find(v.begin(), v.end(), k) != v.end(); };
    fp.identifiable = !held(stats.unidentifiable);
    fp.frozen = held(frozen);
    // Delta method: σ_p = p·σ_θ.
    fp.std_error = stats.covariance.size() && fp.identifiable
                       ? fp.value * std::sqrt(std::max(0.0, stats.covariance(k, k)))
                       : std::numeric_limits<double>::quiet_NaN();
    out.push_back(fp);
  }
  return out;
}

// One plain fit of `frames` from p_start, θ = log p bounded to [lower, upper];
// the covariance and identifiability only with `statistics`. Its stages hold
// this one fit.
TrajectoryFitResult fit_frames(const Scene& scene, const std::vector<TargetFrame>& frames,
                               const TrajectoryFitOptions& opt, const std::vector<double>& p_start,
                               const std::vector<double>& lower, const std::vector<double>& upper, bool statistics) {
  const auto wall0 = Clock::now();
  const std::clock_t cpu0 = std::clock();
  Simulator sim(scene, frames, opt);
  const int n = static_cast<int>(opt.free.size());
  std::vector<double> theta(n);
  for (int k = 0; k < n; ++k) theta[k] = std::clamp(std::log(p_start[k]), lower[k], upper[k]);
  const std::vector<double> p0 = exp_of(theta.data(), n);

  TrajectoryFitResult result;
  result.observed_points = sim.observation().min_seen;
  for (const TargetFrame& f : frames) result.times.push_back(f.time);
  TrajectoryFitStage stage;
  stage.frames = static_cast<int>(frames.size());
  stage.start = p_start;
  auto finish = [&] {
    stage.simulations = result.simulations = sim.count();
    stage.start_rms = largest(result.start_rms);
    stage.final_rms = largest(result.final_rms);
    stage.wall_s = result.wall_s = std::chrono::duration<double>(Clock::now() - wall0).count();
    stage.cpu_s = result.cpu_s = double(std::clock() - cpu0) / CLOCKS_PER_SEC;
    stage.converged = result.converged;
    stage.at_cap = result.at_cap;
    stage.message = result.message;
    stage.iterations = result.iterations;
    result.stages = {stage};
    return result;
  };
  // The start's per-frame distance (also Ceres's first evaluation, from the cache).
  SimulationCache cache;
  const Simulation& first = cache.at(sim, p0);
  if (!first.ok) {
    result.interrupted = sim.stop_requested();
    result.message = result.interrupted ? "interrupted" : "the start does not simulate: " + first.message;
    return finish();
  }
  result.start_rms = frame_rms(first, frames, sim.observation());
  result.start_positions = first.y;
  const StartProbe probe = opt.hold_untold || opt.flat_cost.window > 0
                               ? probe_start(sim, first, frames, theta, upper, opt.hold_untold)
                               : StartProbe{};
  stage.residual_noise = probe.noise;
  for (int k : probe.frozen) {
    stage.frozen.push_back(opt.free[k]);
    if (opt.progress)
      std::fprintf(stderr, "fit: '%s' held at its start %g: the %zu frames do not depend on it there\n",
                   opt.free[k].c_str(), p0[k], frames.size());
  }

  ceres::Problem problem;
  auto* cost = new TrajectoryCost(sim, frames, &cache, n);
  problem.AddResidualBlock(cost, nullptr, theta.data());
  for (int k = 0; k < n; ++k) {
    problem.SetParameterLowerBound(theta.data(), k, lower[k]);
    problem.SetParameterUpperBound(theta.data(), k, upper[k]);
  }
  FlatCostRule flat = opt.flat_cost;
  flat.residual_noise = probe.noise;
  WindowProgress progress(sim, &cache, theta.data(), n, cost->num_residuals(), opt.progress, flat, &stage.cost_history);
  if (static_cast<int>(probe.frozen.size()) == n) {
    result.message = "no fitted key moves the observed points at the start: nothing to fit over these frames";
  } else {
    if (!probe.frozen.empty()) problem.SetManifold(theta.data(), new ceres::SubsetManifold(n, probe.frozen));
    ceres::Solver::Options so = solver_options(opt);
    so.callbacks.push_back(&progress);
    ceres::Solver::Summary summary;
    ceres::Solve(so, &problem, &summary);
    if (!probe.frozen.empty()) problem.SetManifold(theta.data(), nullptr);  // the statistics see every key
    result.converged =
        summary.termination_type == ceres::CONVERGENCE || summary.termination_type == ceres::USER_SUCCESS;
    result.at_cap = summary.termination_type == ceres::NO_CONVERGENCE;
    result.message = stop_message(summary, progress, opt.max_iterations, stage.frames);
    result.iterations = static_cast<int>(summary.iterations.size()) - 1;
  }
  if (sim.stop_requested()) {
    result.interrupted = true;
    result.converged = result.at_cap = false;
    result.message = "interrupted";
  }
  OptimumStatistics stats;
  if (statistics && !result.interrupted) {
    stats = optimum_statistics(problem, theta.data(), n);
    result.covariance_message = stats.covariance_message;
    if (stats.covariance.size()) result.correlation = stats.correlation();
  }
  result.parameters = fitted_parameters(opt, p0, theta, lower, upper, stats, probe.frozen);
  const std::vector<double> p = exp_of(theta.data(), n);
  stage.value = p;
  const Simulation& last = cache.at(sim, p);
  if (last.ok) {
    result.final_rms = frame_rms(last, frames, sim.observation());
    result.final_positions = last.y;
  }
  return finish();
}

std::string joined(const std::vector<int>& v) {
  std::string s;
  for (int x : v) s += (s.empty() ? "" : ",") + std::to_string(x);
  return s;
}

}  // namespace

void check_window(const std::vector<int>& window, int frames) {
  bool ok = !window.empty() && window.front() >= 1 && window.back() == frames;
  for (size_t k = 1; k < window.size(); ++k) ok = ok && window[k] > window[k - 1];
  if (!ok)
    throw TrajectoryFitError("--growing-window: got " + joined(window) +
                             ", expected increasing frame counts >= 1 ending at the number of fitted frames (" +
                             std::to_string(frames) + ")");
}

TrajectoryFitResult fit_trajectory(const Scene& scene, const std::vector<TargetFrame>& target,
                                   const TrajectoryFitOptions& options) {
  const auto wall0 = Clock::now();
  const std::clock_t cpu0 = std::clock();
  if (options.free.empty()) throw TrajectoryFitError("no parameter to fit: name at least one key with --free");
  TrajectoryFitOptions opt = options;
  if (opt.model.empty()) opt.model = yarn_level_model(scene);
  try {
    check_model_for_scene(scene, opt.model);
  } catch (const std::invalid_argument& e) {
    throw TrajectoryFitError(e.what());
  }
  if (!(opt.bound_factor > 1.0 && std::isfinite(opt.bound_factor)))
    throw TrajectoryFitError("bound factor: got " + std::to_string(opt.bound_factor) +
                             ", expected a finite number > 1");
  std::vector<TargetFrame> frames;
  for (const TargetFrame& f : target)
    if (f.time > 0.0) frames.push_back(f);
  if (frames.empty()) throw TrajectoryFitError("the target has no frame after t = 0");
  if (frames.back().time > scene.duration_s * (1 + 1e-12) + 1e-12)
    throw TrajectoryFitError("the target's frames reach t = " + std::to_string(frames.back().time) +
                             " s, beyond the scene's duration " + std::to_string(scene.duration_s) + " s");
  const int count = static_cast<int>(frames.size());
  const std::vector<int> window = opt.window.empty() ? std::vector<int>{count} : opt.window;
  check_window(window, count);

  const int n = static_cast<int>(opt.free.size());
  std::vector<double> lower(n), upper(n), p0(n);
  for (int k = 0; k < n; ++k) {
    const auto it = opt.start.find(opt.free[k]);
    p0[k] = it != opt.start.end() ? it->second : scene_parameter(scene, opt.free[k]);
    if (!(p0[k] > 0.0) || !std::isfinite(p0[k]))
      throw TrajectoryFitError("parameter '" + opt.free[k] + "' starts at " + std::to_string(p0[k]) +
                               ": a fitted parameter must start finite and > 0 (it is fitted as log p)");
    lower[k] = std::log(p0[k]) - std::log(opt.bound_factor);
    upper[k] = std::log(p0[k]) + std::log(opt.bound_factor);
  }
  for (const auto& [key, value] : opt.start)
    if (std::find(opt.free.begin(), opt.free.end(), key) == opt.free.end())
      throw TrajectoryFitError("--start names '" + key + "', which is not among the fitted keys (--free)");

  // The growing window: each stage starts where the one before ended.
  TrajectoryFitResult result;
  std::vector<TrajectoryFitStage> stages;
  std::vector<double> p = p0;
  for (size_t s = 0; s < window.size(); ++s) {
    const bool last = s + 1 == window.size();
    if (opt.progress && window.size() > 1)
      std::fprintf(stderr, "fit stage %zu of %zu: the first %d frames\n", s + 1, window.size(), window[s]);
    result = fit_frames(scene, std::vector<TargetFrame>(frames.begin(), frames.begin() + window[s]), opt, p, lower,
                        upper, last);
    stages.push_back(result.stages.front());
    if (result.interrupted) {
      result.message = "interrupted in stage " + std::to_string(s + 1) + " (" + std::to_string(window[s]) + " frames)";
      break;
    }
    if (result.final_rms.empty()) {  // it did not simulate: the stages after it cannot start
      if (!last) {
        result.converged = false;
        result.message =
            "stage " + std::to_string(s + 1) + " (" + std::to_string(window[s]) + " frames): " + result.message;
      }
      break;
    }
    p = result.stages.front().value;
  }
  result.stages = stages;
  result.iterations = result.simulations = 0;
  for (const TrajectoryFitStage& st : stages) {
    result.iterations += st.iterations;
    result.simulations += st.simulations;
  }
  for (int k = 0; k < static_cast<int>(result.parameters.size()); ++k) result.parameters[k].start = p0[k];
  result.wall_s = std::chrono::duration<double>(Clock::now() - wall0).count();
  result.cpu_s = double(std::clock() - cpu0) / CLOCKS_PER_SEC;
  return result;
}

std::vector<TrajectoryFitResult> fit_trajectories(const Scene& scene, const std::vector<TargetFrame>& target,
                                                  const std::vector<TrajectoryFitOptions>& fits, int threads) {
  std::vector<TrajectoryFitResult> results(fits.size());
  run_starts(static_cast<int>(fits.size()), threads,
             [&](int k) { results[k] = fit_trajectory(scene, target, fits[k]); });
  return results;
}

}  // namespace wl
