#include "bench/step_timing.h"

#include <time.h>

#include <algorithm>
#include <stdexcept>

#include "driver/memory_estimate.h"
#include "integrators/backward_euler.h"
#include "integrators/sparse_solver.h"
#include "models/model_factory.h"

namespace wl::bench {

double process_cpu_s() {
  timespec ts{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

namespace {

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

}  // namespace

double Timing::wall_ms() const { return 1e3 * median(wall); }
double Timing::cpu_ms() const { return 1e3 * median(cpu); }
double Timing::mean_wall_ms() const {
  double s = 0.0;
  for (double w : wall) s += w;
  return wall.empty() ? 0.0 : 1e3 * s / wall.size();
}

Figures measure(const Scene& scene, const std::string& model_name, const std::string& integrator, int warmup, int steps,
                bool parts, LinearSolverMethod method) {
  Figures fig;
  fig.model = model_name;
  fig.parts = parts;
  auto model = make_model(scene, model_name);
  const std::unique_ptr<Integrator> named = make_integrator(integrator);
  auto* backward_euler = dynamic_cast<BackwardEuler*>(named.get());
  if (!backward_euler)
    throw std::invalid_argument("option '--integrator': got '" + integrator +
                                "', expected a backward Euler method (be-linear, be-newton)");
  BackwardEuler& be = *backward_euler;
  IntegratorOptions opt;
  opt.dt = scene.dt_s;
  opt.linear_solver = method;
  be.initialize(*model, 0.0, model->initial_q(), model->initial_v(), opt);
  fig.dofs = model->num_dofs();
  fig.nnz = static_cast<long>(model->pattern().nonZeros());
  auto checked_step = [&]() {
    const StepResult r = be.step(opt.dt);
    if (r.outcome != Outcome::ok)
      throw std::runtime_error(model_name + " step at t = " + std::to_string(be.t()) + " s failed (" +
                               to_string(r.outcome) + "): " + r.message);
  };
  for (int k = 0; k < warmup; ++k) checked_step();

  const SparseMatrix& a = be.step_matrix();
  SparseSolver solver(model->pattern(), model->fixed_dofs());
  SparseSolver reference(model->pattern(), model->fixed_dofs(), {LinearSolverMethod::cholmod, {}});
  SparseMatrix sym = model->pattern();
  auto form_sym = [&] { sym = 0.5 * (a + SparseMatrix(a.transpose())); };  // same pattern: A is structurally symmetric
  const Vec b = Vec::Ones(fig.dofs);
  Vec x;
  Evaluation ev;
  allocate_evaluation(*model, ev);
  if (parts && warmup > 0) {  // symbolic analyses (and first numeric factorizations), untimed
    solver.factorize(a);
    solver.solve(b, x);
    form_sym();
    reference.factorize(sym);
    reference.solve(b, x);
  }
  const SparseSolver::Statistics before = be.solver().statistics();
  for (int k = 0; k < steps; ++k) {
    fig.step.time(checked_step);
    if (!parts) continue;
    fig.factor_solve.time([&] {
      if (!solver.factorize(a)) throw std::runtime_error(model_name + ": " + solver.failure());
      solver.solve(b, x);
    });
    form_sym();
    fig.cholmod_reference.time([&] {
      if (!reference.factorize(sym)) throw std::runtime_error(model_name + ": (A + Aᵀ)/2: " + reference.failure());
      reference.solve(b, x);
    });
    fig.assembly.time([&] { model->evaluate(be.t(), be.q(), be.v(), kForce | kDfdq | kDfdv | kMass, ev); });
  }
  fig.steps = steps;
  const SparseSolver::Statistics& after = be.solver().statistics();
  fig.solver = be.solver().description();
  fig.factorizations_per_step = double(after.factorizations - before.factorizations) / steps;
  fig.krylov_per_step = double(after.krylov_iterations - before.krylov_iterations) / steps;
  fig.peak_mb = peak_resident_bytes() / 1e6;
  return fig;
}

}  // namespace wl::bench
