// Fit of the continuum parameters to yarn-level response curves with Ceres
// (docs/calibration.md §4). The unknowns are θ = log p for the free [fem] keys,
// bounded; one residual block per test curve,
//   r_i = (R_fem(λ_i; p) − R_yarn(λ_i)) / (range_t·√n_t)   (or |R_yarn(λ_i)| for range_t: relative),
// range_t = max_i |R_yarn(λ_i)|, n_t the points of the curve, so every test
// weighs the same whatever its units and the cost is ½ Σ_t (relative RMS_t)².
// Jacobians are the exact IFT sensitivities of run_fem_test(). Several starts
// (the first guess, then seeded log-uniform draws within ×/÷ spread) are run and
// the best kept (concurrently, one thread per start); their spread is reported. At the optimum: ceres::Covariance
// (DENSE_SVD) scaled by the residual variance, correlations, the singular values
// of the weighted Jacobian and the parameters it barely moves or that end on a bound.
#pragma once
#include <functional>
#include <string>
#include <vector>

#include "calibration/virtual_tests.h"
#include "models/fem/fem_material.h"

namespace wl {

// The fittable [fem] keys (without the "fem." prefix) and their accessors.
const std::vector<std::string>& fittable_parameters();
double& material_value(FemMaterial& m, const std::string& key);
// The keys a test informs (a parameter no chosen test informs is left out of the fit).
std::vector<std::string> informed_parameters(TestKind kind, const FemMaterial& guess);

struct FitCurve {
  TestSpec test;
  std::vector<double> target;  // R_yarn at test.ladder
};

struct FitOptions {
  std::vector<std::string> free;  // keys (no prefix); empty = every key the curves inform
  int starts = 4;
  unsigned seed = 1;
  double start_spread = 3.0;  // starts drawn in [p/spread, p·spread]
  double bound_factor = 1e3;  // bounds p0/factor … p0·factor (the lock angle: (0, π/2))
  std::string loss = "none";  // "none", "huber", "cauchy" (scale 0.05: 5 % of a curve's range)
  // "range": r_i = (R_fem − R_yarn)/(range·√n); "relative": r_i = (R_fem − R_yarn)/(|R_yarn(λ_i)|·√n),
  // every point's relative error, so the small loads of a stiffening curve weigh as much as its top.
  std::string residuals = "range";
  int max_iterations = 100;
  bool progress = false;
  int threads = 0;  // starts run at once (0: one per hardware thread); the result does not depend on it
  // Asked after each Ceres iteration and before each curve evaluation: true ends
  // every start there (FitResult::interrupted); the command line asks whether
  // SIGINT or SIGTERM arrived. The continuum tests take their own hook.
  std::function<bool()> stop_requested;
};

struct FittedParameter {
  std::string key;                             // without prefix
  double start = 0, value = 0, std_error = 0;  // std_error NaN when the covariance is not available
  double lower = 0, upper = 0;
  bool at_bound = false;
  bool weakly_determined = false;  // its Jacobian column is < 1e-3 of the largest
  double start_spread = 0;         // max/min − 1 of the value over the starts that reached the best cost
};

struct StartOutcome {
  std::vector<double> start, value;
  double cost = 0;
  int iterations = 0;
  bool usable = false;
  std::string message;
};

struct FitResult {
  FemMaterial material;  // the guess with the fitted values
  std::vector<FittedParameter> parameters;
  std::vector<std::vector<double>> correlation;  // empty when the covariance is not available
  std::string covariance_message;                // why not
  std::vector<double> singular_values;           // of the weighted Jacobian in log parameters
  std::vector<double> relative_rms;              // per curve: RMS(R_fem − R_yarn)/range
  std::vector<std::vector<double>> fitted;       // per curve: R_fem at the ladder
  std::vector<StartOutcome> starts;
  int starts_at_best = 0;  // starts whose cost is within 0.1 % of the best (the others found other minima)
  double cost = 0;
  int iterations = 0;   // of the best start
  int evaluations = 0;  // curve evaluations over all starts
  double wall_s = 0, cpu_s = 0;
  bool converged = false;
  bool interrupted = false;  // stop_requested ended it: starts as far as they got, no optimum statistics
  std::string message;
};

// Continuum response of one test at material m (with sensitivities for `keys`, prefixed).
// Called from several threads at once when there are several starts (one
// thread per start): each call must depend on its arguments alone.
using ContinuumTest =
    std::function<ResponseCurve(const FemMaterial& m, const TestSpec& test, const std::vector<std::string>& keys)>;

FitResult fit_continuum(const std::vector<FitCurve>& curves, const FemMaterial& guess, const ContinuumTest& continuum,
                        const FitOptions& options);

}  // namespace wl
