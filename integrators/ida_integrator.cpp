#include "integrators/ida_integrator.h"

#include <ida/ida_ls.h>

#include <cmath>

#include "integrators/sparse_solver.h"
#include "integrators/step_clock.h"

namespace wl {

IdaIntegrator::~IdaIntegrator() = default;

void IdaIntegrator::initialize(Model& model, double t0, const Vec& q0, const Vec& v0, const IntegratorOptions& opt) {
  StepClock clock(own_);
  // Release any previous run (memory before the objects it uses).
  mem_.reset();
  ls_.reset();
  bind(model, t0, q0, v0, opt);
  n_ = model.num_dofs();
  own_ = {};
  last_error_.clear();
  allocate_evaluation(model, ev_);

  // Consistent initial accelerations v′₀ = M⁻¹ f(t0, q0, v0) (pinned: 0).
  model.evaluate(t0, q_, v_, kForce | kMass, ev_);
  mass_ = ev_.mass;
  SparseSolver msolve(model.pattern(), fixed_);
  Vec a0 = Vec::Zero(n_);
  if (msolve.factorize(ev_.mass)) msolve.solve(ev_.force, a0);

  if (!ctx_) ctx_ = sun::make_context();
  y_ = sun::make_vector(2 * n_, ctx_.get());
  yp_ = sun::make_vector(2 * n_, ctx_.get());
  Eigen::Map<Vec> y0(sun::data(y_.get()), 2 * n_), yp0(sun::data(yp_.get()), 2 * n_);
  y0 << q_, v_;
  yp0 << v_, a0;

  mem_ = sun::IdaMemory(IDACreate(ctx_.get()));
  void* m = mem_.get();
  // J = [c_j I, −I ; −K, c_j M − D], pinned rows c_j I: α = c_j, β = 1, k = 1, m = c_j, d = 1, p = c_j.
  auto query = [this](double& t, const double*& y, ReducedLinearSolver::Coefficients& c) {
    N_Vector yy = nullptr;
    double cj = 0.0;
    if (IDAGetCurrentTime(mem_.get(), &t) < 0 || IDAGetCurrentY(mem_.get(), &yy) < 0 ||
        IDAGetCurrentCj(mem_.get(), &cj) < 0 || !yy)
      return false;
    y = sun::data(yy);
    c = {cj, 1.0, 1.0, cj, 1.0, cj, false};
    cj_setup_ = cj;
    IDAGetNumNonlinSolvConvFails(mem_.get(), &ncf_setup_);
    return true;
  };
  // IDA's own rule for matrix-based solvers: re-form when c_j moved outside
  // [0.6, 1/0.6]·c_j,setup (XRATE 0.25), and after a failed Newton iteration.
  auto stale = [this](const ReducedLinearSolver::Coefficients& at_setup) {
    double cj = at_setup.alpha;
    long ncf = 0;
    IDAGetCurrentCj(mem_.get(), &cj);
    IDAGetNumNonlinSolvConvFails(mem_.get(), &ncf);
    const double ratio = cj / at_setup.alpha;
    return ratio < 0.6 || ratio > 1.0 / 0.6 || ncf != ncf_setup_;
  };
  auto scale = [this]() {
    double cj = cj_setup_;
    IDAGetCurrentCj(mem_.get(), &cj);
    return 2.0 / (1.0 + cj / cj_setup_);
  };
  ls_ = std::make_unique<ReducedLinearSolver>(ctx_.get(), model, 0u, !model.mass_depends_on_q(), step_solver_options(),
                                              query, stale, scale);
  auto check = [&](int flag, const char* what) {
    if (flag < 0)
      throw std::runtime_error(std::string("ida: ") + what + " failed: " + sun::flag_name(IDAGetReturnFlagName(flag)));
  };
  check(IDASetErrHandlerFn(m, &IdaIntegrator::error_handler, this), "IDASetErrHandlerFn");
  check(IDAInit(m, &IdaIntegrator::residual, t0, y_.get(), yp_.get()), "IDAInit");
  check(IDASetUserData(m, this), "IDASetUserData");
  check(IDASStolerances(m, opt.rtol, opt.atol), "IDASStolerances");
  check(IDASetLinearSolver(m, ls_->get(), nullptr), "IDASetLinearSolver");
  check(IDASetInitStep(m, opt.dt), "IDASetInitStep");
  if (!opt.adaptive) check(IDASetMaxStep(m, opt.dt), "IDASetMaxStep");
  check(IDASetMinStep(m, opt.min_step), "IDASetMinStep");
  check(IDASetMaxNumSteps(m, 1000000), "IDASetMaxNumSteps");
}

int IdaIntegrator::residual(double t, N_Vector y, N_Vector yp, N_Vector r, void* self) {
  IdaIntegrator& s = sun::user_data_as<IdaIntegrator>(self);
  const int n = s.n_;
  Eigen::Map<const Vec> yy(sun::data(y), 2 * n), yd(sun::data(yp), 2 * n);
  Eigen::Map<Vec> rr(sun::data(r), 2 * n);
  if (!yy.allFinite()) return 1;  // recoverable: IDA retries with a smaller step
  const bool mq = s.model_->mass_depends_on_q();
  const Vec q = yy.head(n), v = yy.tail(n);
  s.model_->evaluate(t, q, v, kForce | (mq ? kMass : 0u), s.ev_);
  const SparseMatrix& M = mq ? s.ev_.mass : s.mass_;
  rr.head(n) = yd.head(n) - v;
  rr.tail(n) = M * yd.tail(n) - s.ev_.force;
  for (int i : s.fixed_) {  // pinned: q′ = 0, v′ = 0
    rr[i] = yd[i];
    rr[n + i] = yd[n + i];
  }
  return rr.allFinite() ? 0 : 1;
}

void IdaIntegrator::error_handler(int code, const char* module, const char* function, char* msg, void* self) {
  IdaIntegrator& s = sun::user_data_as<IdaIntegrator>(self);
  s.last_error_ = std::string(function ? function : "") + ": " + (msg ? msg : "");
}

void IdaIntegrator::update_stats() {
  void* m = mem_.get();
  long etf = 0, ncf = 0, res = 0, nni = 0;
  IDAGetNumErrTestFails(m, &etf);
  IDAGetNumNonlinSolvConvFails(m, &ncf);
  IDAGetNumResEvals(m, &res);
  IDAGetNumNonlinSolvIters(m, &nni);
  stats_.rejected_steps = etf + ncf;  // stats_.steps: the steps accepted by finish_step
  stats_.rhs_evals = res;
  stats_.jac_evals = ls_ ? ls_->setups() : 0;  // every setup evaluates ∂f/∂q, ∂f/∂v
  stats_.linear_setups = ls_ ? ls_->setups() : 0;
  stats_.linear_solves = ls_ ? ls_->solves() : 0;
  stats_.nonlinear_iters = nni;
  if (ls_) record_solver(ls_->sparse_solver());
  stats_.wall_s = own_.wall_s;
  stats_.cpu_s = own_.cpu_s;
}

StepResult IdaIntegrator::failure(int flag) {
  Outcome o = Outcome::diverged;
  if (flag == IDA_ERR_FAIL) o = Outcome::step_too_small;
  else if (flag == IDA_TOO_MUCH_WORK) o = Outcome::max_steps;
  Eigen::Map<const Vec> y(sun::data(y_.get()), 2 * n_);
  if (!y.allFinite() || flag == IDA_RES_FAIL || flag == IDA_REP_RES_ERR || flag == IDA_FIRST_RES_FAIL) o = Outcome::nan;
  const std::string flag_name = sun::flag_name(IDAGetReturnFlagName(flag));
  return {o, "IDA failed with " + flag_name + (last_error_.empty() ? "" : ": ") + last_error_, flag, flag_name};
}

StepResult IdaIntegrator::advance_to(double t_out) {
  if (!mem_.get()) return {Outcome::diverged, "ida: not initialized"};
  void* m = mem_.get();
  LibraryStepper ida;
  ida.set_stop_time = [m](double t_stop) { IDASetStopTime(m, t_stop); };
  ida.step = [this, m](double t_stop, double& t_reached) {
    return IDASolve(m, t_stop, &t_reached, y_.get(), yp_.get(), IDA_ONE_STEP);
  };
  ida.update_stats = [this] { update_stats(); };
  ida.failure = [this](int flag) { return failure(flag); };
  ida.y = sun::data(y_.get());
  return advance_library_steps(t_out, own_, ida);
}

}  // namespace wl
