#include "integrators/arkode_integrator.h"

#include <arkode/arkode_arkstep.h>

#include <cmath>

#include "integrators/step_clock.h"

namespace wl {

ArkodeIntegrator::~ArkodeIntegrator() = default;

std::string ArkodeIntegrator::name() const {
  switch (variant_) {
    case Variant::erk: return "arkode-erk";
    case Variant::dirk: return "arkode-dirk";
    case Variant::imex: return "arkode-imex";
  }
  return "arkode";
}

void ArkodeIntegrator::initialize(Model& model, double t0, const Vec& q0, const Vec& v0,
                                  const IntegratorOptions& opt) {
  StepClock clock(own_);
  mem_.reset();
  mls_.reset();
  ls_.reset();
  jac_.reset();
  mass_.reset();
  model_ = &model;
  opt_ = opt;
  t_ = t0;
  n_ = model.num_dofs();
  fixed_.assign(model.fixed_dofs().begin(), model.fixed_dofs().end());
  q_ = q0;
  v_ = v0;
  for (int i : fixed_) v_[i] = 0.0;
  stats_ = {};
  own_ = {};
  own_setups_ = own_solves_ = last_nni_ = 0;
  last_error_.clear();
  not_offered_.clear();
  allocate_evaluation(model, ev_);
  mass_in_arkode_ = !model.mass_depends_on_q();
  if (!mass_in_arkode_ && variant_ != Variant::erk) {
    not_offered_ = name() +
                   " is not offered for a model whose mass matrix depends on q (" + model.name() +
                   "): ARKODE accepts only a time-dependent mass matrix, and the Jacobian of the explicit form "
                   "y' = (v, M(q)^-1 f) contains M^-1 df/dq, which is dense, so no sparse direct solver applies "
                   "(use arkode-erk, ida or be-newton)";
    return;
  }
  if (!mass_in_arkode_) msolver_ = std::make_unique<SparseSolver>(model.pattern(), fixed_);
  const auto backend = sun::resolve(opt.sparse_backend);

  if (!ctx_) ctx_ = sun::make_context();
  y_ = sun::make_vector(2 * n_, ctx_.get());
  Eigen::Map<Vec>(sun::data(y_.get()), 2 * n_) << q_, v_;

  ARKRhsFn fe = nullptr, fi = nullptr;
  if (variant_ == Variant::erk) fe = &ArkodeIntegrator::rhs_full;
  if (variant_ == Variant::dirk) fi = &ArkodeIntegrator::rhs_full;
  if (variant_ == Variant::imex) {
    fe = &ArkodeIntegrator::rhs_explicit;
    fi = &ArkodeIntegrator::rhs_implicit;
  }
  mem_ = sun::ArkStepMemory(ARKStepCreate(fe, fi, t0, y_.get(), ctx_.get()));
  void* m = mem_.get();
  auto check = [&](int flag, const char* what) {
    if (flag < 0)
      throw std::runtime_error(name() + ": " + what + " failed: " + ARKStepGetReturnFlagName(flag));
  };
  check(ARKStepSetErrHandlerFn(m, &ArkodeIntegrator::error_handler, this), "ARKStepSetErrHandlerFn");
  check(ARKStepSetUserData(m, this), "ARKStepSetUserData");
  check(ARKStepSStolerances(m, opt.rtol, opt.atol), "ARKStepSStolerances");
  if (variant_ != Variant::erk) {
    jblock_ = std::make_unique<sun::BlockSystem>(model.pattern(), fixed_);
    jac_ = sun::make_sparse_matrix(jblock_->matrix(), ctx_.get());
    ls_ = sun::make_sparse_solver(backend, y_.get(), jac_.get(), ctx_.get());
    check(ARKStepSetLinearSolver(m, ls_.get(), jac_.get()), "ARKStepSetLinearSolver");
    check(ARKStepSetJacFn(m, &ArkodeIntegrator::jacobian), "ARKStepSetJacFn");
    // Re-form and refactorize M − γJ every step (J itself is reused as ARKODE
    // decides). With ARKODE's default (every 20 steps, or when γ changed by
    // 20%) the Newton iteration on a linear problem stops after one iteration
    // with a stale γ (its convergence-rate estimate is carried over from exact
    // steps), and the adaptive error fell to order ~2 (global error ∝ tol^0.45
    // on the spring chain); with one setup per step it is ∝ tol again.
    check(ARKStepSetLSetupFrequency(m, 1), "ARKStepSetLSetupFrequency");
  }
  if (mass_in_arkode_) {
    mblock_ = std::make_unique<sun::BlockSystem>(model.pattern(), fixed_);
    mass_ = sun::make_sparse_matrix(mblock_->matrix(), ctx_.get());
    mls_ = sun::make_sparse_solver(backend, y_.get(), mass_.get(), ctx_.get());
    check(ARKStepSetMassLinearSolver(m, mls_.get(), mass_.get(), SUNFALSE), "ARKStepSetMassLinearSolver");
    check(ARKStepSetMassFn(m, &ArkodeIntegrator::mass_fn), "ARKStepSetMassFn");
  }
  if (opt.adaptive) check(ARKStepSetInitStep(m, opt.dt), "ARKStepSetInitStep");
  else check(ARKStepSetFixedStep(m, opt.dt), "ARKStepSetFixedStep");
  check(ARKStepSetMinStep(m, opt.min_step), "ARKStepSetMinStep");
  check(ARKStepSetMaxNumSteps(m, 1000000), "ARKStepSetMaxNumSteps");
}

// ydot = (v, g) where g = f_selected (mass given to ARKODE) or M(q)⁻¹ f
// (mass depends on q, ERK only); zero on pinned DoFs. `with_velocity` false
// gives the explicit IMEX part (0, f_explicit).
int ArkodeIntegrator::rhs(double t, N_Vector y, N_Vector ydot, unsigned filter, bool with_velocity) {
  const int n = n_;
  Eigen::Map<const Vec> yy(sun::data(y), 2 * n);
  Eigen::Map<Vec> yd(sun::data(ydot), 2 * n);
  if (!yy.allFinite()) return 1;  // recoverable: ARKODE retries with a smaller step
  qtmp_ = yy.head(n);
  vtmp_ = yy.tail(n);
  const bool solve_mass = !mass_in_arkode_;
  model_->evaluate(t, qtmp_, vtmp_, kForce | filter | (solve_mass ? kMass : 0u), ev_);
  if (with_velocity) yd.head(n) = vtmp_;
  else yd.head(n).setZero();
  if (solve_mass) {
    ++own_setups_;
    if (!msolver_->factorize(ev_.mass)) return 1;
    msolver_->solve(ev_.force, acc_);
    ++own_solves_;
    yd.tail(n) = acc_;
  } else {
    yd.tail(n) = ev_.force;
  }
  for (int i : fixed_) yd[i] = yd[n + i] = 0.0;
  return yd.allFinite() ? 0 : 1;
}

int ArkodeIntegrator::rhs_full(double t, N_Vector y, N_Vector ydot, void* self) {
  return sun::user_data_as<ArkodeIntegrator>(self).rhs(t, y, ydot, 0u, true);
}
int ArkodeIntegrator::rhs_explicit(double t, N_Vector y, N_Vector ydot, void* self) {
  return sun::user_data_as<ArkodeIntegrator>(self).rhs(t, y, ydot, kExplicitTerms, false);
}
int ArkodeIntegrator::rhs_implicit(double t, N_Vector y, N_Vector ydot, void* self) {
  return sun::user_data_as<ArkodeIntegrator>(self).rhs(t, y, ydot, kImplicitTerms, true);
}

int ArkodeIntegrator::jacobian(double t, N_Vector y, N_Vector, SUNMatrix J, void* self, N_Vector, N_Vector,
                               N_Vector) {
  ArkodeIntegrator& s = sun::user_data_as<ArkodeIntegrator>(self);
  const int n = s.n_;
  Eigen::Map<const Vec> yy(sun::data(y), 2 * n);
  s.qtmp_ = yy.head(n);
  s.vtmp_ = yy.tail(n);
  const unsigned filter = s.variant_ == Variant::imex ? kImplicitTerms : 0u;
  s.model_->evaluate(t, s.qtmp_, s.vtmp_, kForce | kDfdq | kDfdv | filter, s.ev_);
  // ∂(v, f)/∂(q, v) = [0 I ; ∂f/∂q ∂f/∂v]; pinned rows zero.
  s.jblock_->fill(0.0, 1.0, 1.0, &s.ev_.dfdq, 1.0, &s.ev_.dfdv, 0.0, nullptr, 0.0);
  sun::copy_to(s.jblock_->matrix(), J);
  return s.jblock_->matrix().coeffs().allFinite() ? 0 : 1;
}

int ArkodeIntegrator::mass_fn(double t, SUNMatrix M, void* self, N_Vector, N_Vector, N_Vector) {
  ArkodeIntegrator& s = sun::user_data_as<ArkodeIntegrator>(self);
  s.model_->evaluate(t, s.q_, s.v_, kMass, s.ev_);  // constant M: any state will do
  // [I 0 ; 0 M], pinned rows identity.
  s.mblock_->fill(1.0, 0.0, 0.0, nullptr, 0.0, nullptr, 1.0, &s.ev_.mass, 1.0);
  sun::copy_to(s.mblock_->matrix(), M);
  return 0;
}

void ArkodeIntegrator::error_handler(int, const char*, const char* function, char* msg, void* self) {
  ArkodeIntegrator& s = sun::user_data_as<ArkodeIntegrator>(self);
  s.last_error_ = std::string(function ? function : "") + ": " + (msg ? msg : "");
}

void ArkodeIntegrator::update_stats() {
  void* m = mem_.get();
  long steps = 0, etf = 0, sfails = 0, nfe = 0, nfi = 0, nje = 0, nls = 0, nms = 0, nmsolve = 0, nni = 0;
  ARKStepGetNumSteps(m, &steps);
  ARKStepGetNumErrTestFails(m, &etf);
  ARKStepGetNumStepSolveFails(m, &sfails);
  ARKStepGetNumRhsEvals(m, &nfe, &nfi);
  if (ls_) {
    ARKStepGetNumJacEvals(m, &nje);
    ARKStepGetNumLinSolvSetups(m, &nls);
    ARKStepGetNumNonlinSolvIters(m, &nni);
  }
  if (mls_) {
    ARKStepGetNumMassSetups(m, &nms);
    ARKStepGetNumMassSolves(m, &nmsolve);
  }
  stats_.steps = steps;
  stats_.rejected_steps = etf + sfails;
  stats_.rhs_evals = nfe + nfi;
  stats_.jac_evals = nje;
  stats_.linear_setups = nls + nms + own_setups_;
  stats_.linear_solves = nni + nmsolve + own_solves_;  // direct solver: one solve per Newton iteration
  stats_.nonlinear_iters = nni;
  stats_.wall_s = own_.wall_s;
  stats_.cpu_s = own_.cpu_s;
}

StepResult ArkodeIntegrator::failure(int flag) {
  Outcome o = Outcome::diverged;
  if (flag == ARK_ERR_FAILURE || flag == ARK_TOO_CLOSE) o = Outcome::step_too_small;
  else if (flag == ARK_TOO_MUCH_WORK) o = Outcome::max_steps;
  Eigen::Map<const Vec> y(sun::data(y_.get()), 2 * n_);
  if (!y.allFinite() || flag == ARK_RHSFUNC_FAIL || flag == ARK_REPTD_RHSFUNC_ERR ||
      flag == ARK_FIRST_RHSFUNC_ERR || flag == ARK_UNREC_RHSFUNC_ERR)
    o = Outcome::nan;
  return {o, name() + " failed with " + ARKStepGetReturnFlagName(flag) + (last_error_.empty() ? "" : ": ") +
                 last_error_};
}

StepResult ArkodeIntegrator::advance_to(double t_out) {
  if (!not_offered_.empty()) return {Outcome::not_offered, not_offered_};
  if (!mem_.get()) return {Outcome::diverged, name() + ": not initialized"};
  StepResult result;
  {
    StepClock clock(own_);
    const double eps = 1e-12 * std::max(1.0, std::abs(t_out));
    if (t_out - t_ > eps) ARKStepSetStopTime(mem_.get(), t_out);
    while (t_out - t_ > eps) {
      if (stats_.steps >= opt_.max_steps) {
        result = {Outcome::max_steps, "step limit reached (" + std::to_string(opt_.max_steps) + " steps)"};
        break;
      }
      const double wall0 = clock.elapsed_wall();
      double tret = t_;
      const int flag = ARKStepEvolve(mem_.get(), t_out, y_.get(), &tret, ARK_ONE_STEP);
      update_stats();
      if (flag < 0) {
        result = failure(flag);
        break;
      }
      Eigen::Map<const Vec> y(sun::data(y_.get()), 2 * n_);
      const double h = tret - t_;
      t_ = tret;
      q_ = y.head(n_);
      v_ = y.tail(n_);
      result = check_state(q_, v_, opt_);
      if (result.outcome != Outcome::ok) break;
      model_->accept_step(t_, q_, v_, h);
      if (on_step) on_step({t_, h, static_cast<int>(stats_.nonlinear_iters - last_nni_), clock.elapsed_wall() - wall0});
      last_nni_ = stats_.nonlinear_iters;
    }
    if (result.outcome == Outcome::ok) t_ = t_out;
  }
  update_stats();
  return result;
}

}  // namespace wl
