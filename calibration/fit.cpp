#include "calibration/fit.h"

#include "calibration/optimum_statistics.h"
#include "calibration/parallel_starts.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <ctime>
#include <limits>
#include <memory>
#include <numbers>
#include <random>
#include <sstream>
#include <stdexcept>
#include <thread>

#include <ceres/ceres.h>
#include <Eigen/SVD>

namespace wl {
namespace {

constexpr double kLockAngleMax = 0.999 * std::numbers::pi / 2;

std::vector<std::string> prefixed(const std::vector<std::string>& keys) {
  std::vector<std::string> out;
  for (const auto& k : keys) out.push_back("fem." + k);
  return out;
}

// One test curve: residuals and their Jacobian in θ = log p.
class CurveCost final : public ceres::CostFunction {
 public:
  CurveCost(const FitCurve& curve, const FemMaterial& base, const std::vector<std::string>& free,
            const ContinuumTest& continuum, bool relative, const std::function<bool()>& stop, int* evaluations)
      : curve_(curve),
        base_(base),
        free_(free),
        keys_(prefixed(free)),
        continuum_(continuum),
        stop_(stop),
        evaluations_(evaluations) {
    double range = 0.0;
    for (double r : curve.target) range = std::max(range, std::abs(r));
    if (!(range > 0)) throw std::invalid_argument(test_name(curve.test) + ": the target curve is zero");
    for (double r : curve.target) {
      const double scale = relative ? std::abs(r) : range;
      if (!(scale > 0)) throw std::invalid_argument(test_name(curve.test) + ": a zero response has no relative error");
      weight_.push_back(1.0 / (scale * std::sqrt(double(curve.target.size()))));
    }
    set_num_residuals(static_cast<int>(curve.target.size()));
    mutable_parameter_block_sizes()->push_back(static_cast<int>(free.size()));
  }

  bool Evaluate(double const* const* x, double* residuals, double** jacobians) const override {
    if (stop_ && stop_()) return false;  // the iteration callback then ends the solve
    FemMaterial m = base_;
    for (size_t k = 0; k < free_.size(); ++k) material_value(m, free_[k]) = std::exp(x[0][k]);
    if (!stretch_law_admissible(m)) return false;  // a non-convex stretch law: Ceres retries a smaller step
    const bool want_j = jacobians && jacobians[0];
    const ResponseCurve c = continuum_(m, curve_.test, want_j ? keys_ : std::vector<std::string>{});
    ++*evaluations_;
    if (!c.complete || c.points.size() != curve_.target.size()) return false;  // Ceres retries a smaller step
    const int n = static_cast<int>(free_.size());
    for (size_t i = 0; i < c.points.size(); ++i) {
      residuals[i] = weight_[i] * (c.points[i].response - curve_.target[i]);
      if (!want_j) continue;
      for (int k = 0; k < n; ++k)  // dr/dθ = w·dR/dp·p
        jacobians[0][i * n + k] = weight_[i] * c.sensitivities[i][k] * std::exp(x[0][k]);
    }
    return true;
  }

 private:
  const FitCurve& curve_;
  FemMaterial base_;
  std::vector<std::string> free_, keys_;
  const ContinuumTest& continuum_;
  const std::function<bool()>& stop_;
  int* evaluations_;
  std::vector<double> weight_;  // per point
};

// The stretch keys a stretch test along warp, weft or both informs: the stiffness, the quartic
// stiffening where the guess has it (the areal one acts in all three), and with both the coupling.
std::vector<std::string> stretch_keys(const FemMaterial& guess, bool warp, bool weft) {
  std::vector<std::string> keys;
  if (warp) keys.push_back("warp_stretch_N_per_m");
  if (weft) keys.push_back("weft_stretch_N_per_m");
  if (warp && weft && guess.stretch_coupling_N_per_m > 0) keys.push_back("stretch_coupling_N_per_m");
  if (warp && guess.warp_stretch_quartic_N_per_m > 0) keys.push_back("warp_stretch_quartic_N_per_m");
  if (weft && guess.weft_stretch_quartic_N_per_m > 0) keys.push_back("weft_stretch_quartic_N_per_m");
  if (guess.areal_stretch_quartic_N_per_m > 0) keys.push_back("areal_stretch_quartic_N_per_m");
  return keys;
}

// The progress line of each iteration (when `print`), the last accepted iterate θ and its cost
// (Ceres hands back the start when a stop ends the solve), and the end of the solve when `stop` says so.
class StartProgress final : public ceres::IterationCallback {
 public:
  StartProgress(int start, bool print, const std::function<bool()>& stop, const std::vector<double>& theta)
      : start_(start), print_(print), stop_(stop), theta_(theta) {}
  std::vector<double> accepted;  // empty before the first iteration
  double accepted_cost = 0.0;
  ceres::CallbackReturnType operator()(const ceres::IterationSummary& s) override {
    if (s.iteration == 0 || s.step_is_successful) {  // θ holds it (update_state_every_iteration)
      accepted = theta_;
      accepted_cost = s.cost;
    }
    if (print_)
      std::fprintf(stderr, "  fit start %d: iteration %d, cost %.6g, |gradient| %.3g\n", start_, s.iteration, s.cost,
                   s.gradient_max_norm);
    return stop_ && stop_() ? ceres::SOLVER_ABORT : ceres::SOLVER_CONTINUE;
  }

 private:
  int start_;
  bool print_;
  const std::function<bool()>& stop_;
  const std::vector<double>& theta_;
};

struct Run {
  std::unique_ptr<ceres::Problem> problem;
  std::vector<double> theta;
  ceres::Solver::Summary summary;
};

}  // namespace

const std::vector<std::string>& fittable_parameters() {
  static const std::vector<std::string> keys = [] {
    std::vector<std::string> k;
    for (const FemParameterKey& p : fem_parameter_keys())
      if (p.name != "areal_density_kg_per_m2") k.push_back(p.name);  // static tests cannot see mass
    return k;
  }();
  return keys;
}

double& material_value(FemMaterial& m, const std::string& key) {
  for (const FemParameterKey& p : fem_parameter_keys())
    if (key == p.name && key != "areal_density_kg_per_m2") return p.value(m);
  std::string known;
  for (const std::string& k : fittable_parameters()) known += (known.empty() ? "" : ", ") + k;
  throw std::invalid_argument("unknown FEM parameter '" + key + "', expected one of " + known);
}

std::vector<std::string> informed_parameters(TestKind kind, const FemMaterial& guess) {
  switch (kind) {
    case TestKind::uniaxial_warp: return stretch_keys(guess, true, false);
    case TestKind::uniaxial_weft: return stretch_keys(guess, false, true);
    case TestKind::biaxial: return stretch_keys(guess, true, true);
    case TestKind::shear: {
      std::vector<std::string> keys{"shear_N_per_m"};
      if (guess.shear_lock_angle_rad > 0 && guess.shear_lock_exponent > 0)
        keys.insert(keys.end(), {"shear_lock_angle_rad", "shear_lock_exponent"});
      for (size_t i = 0; i < guess.shear_knots_rad.size(); ++i) keys.push_back(shear_knot_key(int(i)));
      return keys;
    }
    case TestKind::bending_warp: return {"warp_bending_N_m"};
    case TestKind::bending_weft: return {"weft_bending_N_m"};
    case TestKind::bending_diagonal:
    case TestKind::bending_antidiagonal:
      // on the grid mesh the warp and weft hinges bend too (docs/calibration.md §2.1)
      if (guess.diagonal_bending_N_m > 0) return {"warp_bending_N_m", "weft_bending_N_m", "diagonal_bending_N_m"};
      return {"warp_bending_N_m", "weft_bending_N_m"};
    case TestKind::stretch_shear: {
      std::vector<std::string> keys = informed_parameters(TestKind::shear, guess);
      keys.insert(keys.begin(), "warp_stretch_N_per_m");
      return keys;
    }
    case TestKind::stretch_bending: return {"warp_stretch_N_per_m", "warp_bending_N_m"};
  }
  return {};
}

FitResult fit_continuum(const std::vector<FitCurve>& curves, const FemMaterial& guess, const ContinuumTest& continuum,
                        const FitOptions& opt) {
  const auto wall0 = std::chrono::steady_clock::now();
  const std::clock_t cpu0 = std::clock();
  if (curves.empty()) throw std::invalid_argument("no test curves to fit");

  // Free parameters: as given, else every key some curve informs (in the canonical order).
  std::vector<std::string> free = opt.free;
  if (free.empty())
    for (const std::string& key : fittable_parameters())
      for (const FitCurve& c : curves) {
        const auto inf = informed_parameters(c.test.kind, guess);
        if (std::find(inf.begin(), inf.end(), key) != inf.end()) {
          free.push_back(key);
          break;
        }
      }
  FemMaterial base = guess;
  const int n = static_cast<int>(free.size());
  std::vector<double> lower(n), upper(n), theta0(n);
  for (int k = 0; k < n; ++k) {
    const double p0 = material_value(base, free[k]);
    if (!(p0 > 0)) throw std::invalid_argument("FEM parameter '" + free[k] + "' has no positive start value");
    theta0[k] = std::log(p0);
    lower[k] = theta0[k] - std::log(opt.bound_factor);
    upper[k] = theta0[k] + std::log(opt.bound_factor);
    if (free[k] == "shear_lock_angle_rad") upper[k] = std::min(upper[k], std::log(kLockAngleMax));
  }

  if (opt.residuals != "range" && opt.residuals != "relative")
    throw std::invalid_argument("unknown residual scale '" + opt.residuals + "', expected range or relative");
  const bool relative = opt.residuals == "relative";
  FitResult result;
  // The starts: the first guess, then seeded draws (in start order, so the seed fixes them).
  const int num_starts = std::max(1, opt.starts);
  std::mt19937 rng(opt.seed);
  std::uniform_real_distribution<double> draw(-std::log(opt.start_spread), std::log(opt.start_spread));
  std::vector<std::vector<double>> start_theta(num_starts, theta0);
  for (int s = 1; s < num_starts; ++s)
    for (int k = 0; k < n; ++k) start_theta[s][k] = std::clamp(theta0[k] + draw(rng), lower[k], upper[k]);

  // Each start is its own Ceres problem: they run concurrently, one thread per
  // start up to the hardware's threads. Each start's path depends on nothing
  // but its own evaluations, so the result is that of running them in order.
  std::vector<Run> runs(num_starts);
  std::vector<StartOutcome> outcomes(num_starts);
  std::vector<int> evaluations(num_starts, 0);
  auto solve_start = [&](int s) {
    if (opt.stop_requested && opt.stop_requested()) return;  // not started (no start values in its outcome)
    Run& run = runs[s];
    run.theta = start_theta[s];
    StartOutcome& outcome = outcomes[s];
    for (int k = 0; k < n; ++k) outcome.start.push_back(std::exp(run.theta[k]));

    ceres::Problem::Options popt;
    popt.cost_function_ownership = ceres::TAKE_OWNERSHIP;
    popt.loss_function_ownership = ceres::TAKE_OWNERSHIP;
    run.problem = std::make_unique<ceres::Problem>(popt);
    for (const FitCurve& c : curves) {
      ceres::LossFunction* loss = nullptr;
      if (opt.loss == "huber") loss = new ceres::HuberLoss(0.05);
      else if (opt.loss == "cauchy") loss = new ceres::CauchyLoss(0.05);
      run.problem->AddResidualBlock(
          new CurveCost(c, base, free, continuum, relative, opt.stop_requested, &evaluations[s]), loss,
          run.theta.data());
    }
    for (int k = 0; k < n; ++k) {
      run.problem->SetParameterLowerBound(run.theta.data(), k, lower[k]);
      run.problem->SetParameterUpperBound(run.theta.data(), k, upper[k]);
    }
    ceres::Solver::Options so;
    so.linear_solver_type = ceres::DENSE_QR;
    so.max_num_iterations = opt.max_iterations;
    // Stop when an iteration lowers the cost by less than 1e-10 of itself or moves θ by
    // less than 1e-10 (docs/calibration.md §4): below that the curves' equilibrium
    // tolerance (1e-10) is all an evaluation resolves, and further steps are rejected.
    so.function_tolerance = 1e-10;
    so.gradient_tolerance = 1e-16;
    so.parameter_tolerance = 1e-10;
    so.num_threads = 1;  // Ceres' threads would sum the curves' costs in a varying order
    so.logging_type = ceres::SILENT;
    so.update_state_every_iteration = true;  // θ holds the last iterate when a stop ends the solve
    StartProgress progress(s + 1, opt.progress, opt.stop_requested, run.theta);
    so.callbacks.push_back(&progress);
    if (opt.progress) std::fprintf(stderr, "  fit start %d of %d\n", s + 1, num_starts);
    ceres::Solve(so, run.problem.get(), &run.summary);
    outcome.usable = run.summary.IsSolutionUsable();
    const bool stopped = !outcome.usable && !progress.accepted.empty();  // a stop or failure: as far as it got
    outcome.cost = stopped ? progress.accepted_cost : run.summary.final_cost;
    outcome.iterations = static_cast<int>(run.summary.iterations.size()) - 1;
    outcome.message = run.summary.message;
    for (int k = 0; k < n; ++k) outcome.value.push_back(std::exp(stopped ? progress.accepted[k] : run.theta[k]));
  };
  if (opt.loss != "none" && opt.loss != "huber" && opt.loss != "cauchy")
    throw std::invalid_argument("unknown loss '" + opt.loss + "', expected none, huber or cauchy");
  const int threads = opt.threads > 0 ? opt.threads : static_cast<int>(std::thread::hardware_concurrency());
  run_starts(num_starts, threads, solve_start);

  if (opt.stop_requested && opt.stop_requested()) {  // each start begun, as far as it got
    for (const StartOutcome& o : outcomes)
      if (!o.start.empty()) result.starts.push_back(o);
    for (int e : evaluations) result.evaluations += e;
    result.interrupted = true;
    result.message = "interrupted";
    result.material = base;
    return result;
  }
  Run best;
  double best_cost = std::numeric_limits<double>::infinity();
  for (int s = 0; s < num_starts; ++s) {
    result.starts.push_back(outcomes[s]);
    if (outcomes[s].usable && outcomes[s].cost < best_cost) {
      best_cost = outcomes[s].cost;
      best = std::move(runs[s]);
    }
  }
  if (!best.problem) {
    for (int e : evaluations) result.evaluations += e;
    result.message = "no start gave a usable solution: " + result.starts.front().message;
    result.material = base;
    return result;
  }
  result.converged = best.summary.termination_type == ceres::CONVERGENCE;
  result.message = best.summary.message;
  result.cost = best.summary.final_cost;
  result.iterations = static_cast<int>(best.summary.iterations.size()) - 1;
  result.material = base;
  for (int k = 0; k < n; ++k) material_value(result.material, free[k]) = std::exp(best.theta[k]);

  // Weighted Jacobian, singular values and covariance of θ at the optimum.
  const OptimumStatistics stats = optimum_statistics(*best.problem, best.theta.data(), n);
  for (int e : evaluations) result.evaluations += e;  // the statistics' evaluations of the best start included
  const Eigen::MatrixXd& J = stats.jacobian;
  const Eigen::MatrixXd& C = stats.covariance;
  result.singular_values = stats.singular_values;
  result.covariance_message = stats.covariance_message;
  const double max_col = J.colwise().norm().maxCoeff();

  for (const StartOutcome& s : result.starts)
    if (s.usable && s.cost <= best_cost * (1 + 1e-3) + 1e-20) ++result.starts_at_best;
  for (int k = 0; k < n; ++k) {
    FittedParameter p;
    p.key = free[k];
    p.start = std::exp(theta0[k]);
    p.value = std::exp(best.theta[k]);
    p.lower = std::exp(lower[k]);
    p.upper = std::exp(upper[k]);
    const double span = 1e-6 * (upper[k] - lower[k]);
    p.at_bound = best.theta[k] - lower[k] < span || upper[k] - best.theta[k] < span;
    p.weakly_determined = J.col(k).norm() < 1e-3 * max_col;
    const bool held =
        std::find(stats.unidentifiable.begin(), stats.unidentifiable.end(), k) != stats.unidentifiable.end();
    p.weakly_determined = p.weakly_determined || held;
    p.std_error =
        C.size() && !held ? p.value * std::sqrt(std::max(0.0, C(k, k))) : std::numeric_limits<double>::quiet_NaN();
    double lo = std::numeric_limits<double>::infinity(), hi = 0;
    for (const StartOutcome& s : result.starts)
      if (s.usable && s.cost <= best_cost * (1 + 1e-3) + 1e-20) {
        lo = std::min(lo, s.value[k]);
        hi = std::max(hi, s.value[k]);
      }
    p.start_spread = hi / lo - 1.0;
    result.parameters.push_back(p);
  }
  if (C.size()) result.correlation = stats.correlation();

  // Per-curve fit: R_fem at the ladder and the relative RMS.
  for (const FitCurve& c : curves) {
    const ResponseCurve r = continuum(result.material, c.test, {});
    ++result.evaluations;
    double range = 0, sum = 0;
    std::vector<double> values;
    for (size_t i = 0; i < c.target.size(); ++i) {
      range = std::max(range, std::abs(c.target[i]));
      const double v = i < r.points.size() ? r.points[i].response : std::numeric_limits<double>::quiet_NaN();
      values.push_back(v);
      sum += (v - c.target[i]) * (v - c.target[i]);
    }
    result.fitted.push_back(values);
    result.relative_rms.push_back(std::sqrt(sum / c.target.size()) / range);
  }
  result.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  result.cpu_s = double(std::clock() - cpu0) / CLOCKS_PER_SEC;
  return result;
}

}  // namespace wl
