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

void ArkodeIntegrator::initialize(Model& model, double t0, const Vec& q0, const Vec& v0, const IntegratorOptions& opt) {
  StepClock clock(own_);
  mem_.reset();
  mls_.reset();
  ls_.reset();
  bind(model, t0, q0, v0, opt);
  n_ = model.num_dofs();
  own_ = {};
  own_setups_ = own_solves_ = 0;
  attempts_setup_ = -1;
  last_error_.clear();
  allocate_evaluation(model, ev_);
  allocate_evaluation(model, mev_);
  mass_in_arkode_ = !model.mass_depends_on_q();
  msolver_.reset();
  mass_factored_ = false;
  if (mass_in_arkode_) {
    model.evaluate(t0, q_, v_, kMass, mev_);
    mass_ = mev_.mass;
  } else {
    // M(q) is symmetric positive definite: Cholesky (CHOLMOD), twice as fast
    // as LU for arkode-dirk on the yarn cloth; LU if Cholesky ever fails.
    msolver_ =
        std::make_unique<SparseSolver>(model.pattern(), fixed_, SparseSolver::Options{LinearSolverMethod::cholmod, {}});
  }

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
      throw std::runtime_error(name() + ": " + what + " failed: " + sun::flag_name(ARKStepGetReturnFlagName(flag)) +
                               (last_error_.empty() ? "" : " (" + last_error_ + ")"));
  };
  check(ARKStepSetErrHandlerFn(m, &ArkodeIntegrator::error_handler, this), "ARKStepSetErrHandlerFn");
  check(ARKStepSetUserData(m, this), "ARKStepSetUserData");
  check(ARKStepSStolerances(m, opt.rtol, opt.atol), "ARKStepSStolerances");
  if (variant_ != Variant::erk) {
    // A = M_blk − γ J (block mass) or I − γ J (explicit form, v rows × M(q)):
    // α = 1, β = γ, k = γ, m = 1, d = γ, pinned rows identity.
    const bool explicit_form = !mass_in_arkode_;
    auto query = [this, explicit_form](double& t, const double*& y, ReducedLinearSolver::Coefficients& c) {
      N_Vector yy = nullptr;
      double gamma = 0.0;
      if (ARKStepGetCurrentTime(mem_.get(), &t) < 0 || ARKStepGetCurrentState(mem_.get(), &yy) < 0 ||
          ARKStepGetCurrentGamma(mem_.get(), &gamma) < 0 || !yy)
        return false;
      y = sun::data(yy);
      c = {1.0, gamma, gamma, 1.0, gamma, 1.0, explicit_form};
      ARKStepGetNumStepAttempts(mem_.get(), &attempts_setup_);
      t_setup_ = t;
      return true;
    };
    // Re-form M − γJ at every implicit stage at fixed steps (J at the stage's
    // predicted state), at every new step attempt, and when γ changed by more than 20%
    // (ARKODE's dgmax). With ARKODE's default for matrix-based solvers (every
    // 20 steps) the Newton iteration on a linear problem stopped after one
    // iteration with a stale γ (its convergence-rate estimate is carried over
    // from exact steps) and the adaptive error fell to order ~2 (global error
    // ∝ tol^0.45 on the spring chain). Per stage rather than per step: on the
    // 17×17 hanging cloth at h = 1 ms, 179 instead of 261 Newton iterations
    // per 10 steps (yarn), 166 instead of 223 (FEM), fewer right-hand sides
    // (each an M(q) factorization for the yarn) than extra factorizations.
    // Adaptive steps are small where the Newton matrix matters (ARKODE
    // shrinks h on a convergence failure), so there it is re-formed per step
    // attempt only: at rtol 1e-8 on the 6×6 yarn cloth (2 Newton iterations
    // per stage) per-stage setups made arkode-dirk several times slower.
    const bool per_stage = !opt.adaptive;
    auto stale = [this, per_stage](const ReducedLinearSolver::Coefficients& at_setup) {
      long attempts = 0;
      double gamma = at_setup.beta, tc = t_setup_;
      ARKStepGetNumStepAttempts(mem_.get(), &attempts);
      ARKStepGetCurrentGamma(mem_.get(), &gamma);
      ARKStepGetCurrentTime(mem_.get(), &tc);
      return attempts != attempts_setup_ || (per_stage && tc != t_setup_) ||
             std::abs(gamma / at_setup.beta - 1.0) > 0.2;
    };
    const unsigned filter = variant_ == Variant::imex ? kImplicitTerms : 0u;
    ls_ = std::make_unique<ReducedLinearSolver>(ctx_.get(), model, filter, mass_in_arkode_, step_solver_options(),
                                                query, stale);
    check(ARKStepSetLinearSolver(m, ls_->get(), nullptr), "ARKStepSetLinearSolver");
    // A direct solve: rule out the "right-hand side already small, return 0"
    // shortcut SUNDIALS takes for iterative linear solvers (defensive: a
    // matrix-embedded solver counts as iterative in some SUNDIALS versions).
    check(ARKStepSetEpsLin(m, 1e-12), "ARKStepSetEpsLin");
    if (!opt.adaptive) check(ARKStepSetMaxNonlinIters(m, opt.newton_max_iters), "ARKStepSetMaxNonlinIters");
    // Initial Newton guess of each stage from the maximum-order interpolant of
    // the last step (ARKODE's predictor 1) instead of the last solution. On
    // the hanging cloth at h = 1 ms, Newton iterations per 10 steps (yarn /
    // FEM): trivial predictor, setup per step 302 / 282; predictor 1, per step
    // 261 / 223; predictor 1, per stage 179 / 166.
    check(ARKStepSetPredictorMethod(m, 1), "ARKStepSetPredictorMethod");
  }
  if (mass_in_arkode_) {
    auto query = [this](double& t, const double*& y, ReducedLinearSolver::Coefficients& c) {
      t = t_;
      y = sun::data(y_.get());  // constant M: any state will do
      c = {1.0, 0.0, 0.0, 1.0, 0.0, 1.0, false};
      return true;
    };
    mls_ = std::make_unique<ReducedLinearSolver>(ctx_.get(), model, 0u, true, SparseSolver::Options{}, query);
    check(ARKStepSetMassLinearSolver(m, mls_->get(), nullptr, SUNFALSE), "ARKStepSetMassLinearSolver");
    check(ARKStepSetMassTimes(m, nullptr, &ArkodeIntegrator::mass_times, this), "ARKStepSetMassTimes");
    check(ARKStepSetMassEpsLin(m, 1e-12), "ARKStepSetMassEpsLin");
  }
  if (opt.adaptive) check(ARKStepSetInitStep(m, opt.dt), "ARKStepSetInitStep");
  else check(ARKStepSetFixedStep(m, opt.dt), "ARKStepSetFixedStep");
  check(ARKStepSetMinStep(m, opt.min_step), "ARKStepSetMinStep");
  check(ARKStepSetMaxNumSteps(m, 1000000), "ARKStepSetMaxNumSteps");
}

// Factorizes M(q) for the explicit form unless the last factorization was at
// this very q (the explicit and implicit IMEX parts of one stage share it).
// `mass` is M(q) when the caller already has it, else it is evaluated here.
bool ArkodeIntegrator::factor_mass_at(const Vec& q, double t, const SparseMatrix* mass) {
  if (mass_current(q)) return true;
  if (!mass) {
    model_->evaluate(t, q, vtmp_, kMass, mev_);
    mass = &mev_.mass;
  }
  ++own_setups_;
  mass_factored_ = msolver_->factorize(*mass);
  if (!mass_factored_ && msolver_->method() == LinearSolverMethod::cholmod) {
    msolver_ = std::make_unique<SparseSolver>(model_->pattern(), fixed_);
    mass_factored_ = msolver_->factorize(*mass);
  }
  mass_q_ = q;
  return mass_factored_;
}

// ydot = (v, g) where g = f_selected (mass given to ARKODE) or M(q)⁻¹ f_selected
// (explicit form); zero on pinned DoFs. `with_velocity` false gives the
// explicit IMEX part (0, g_explicit).
int ArkodeIntegrator::rhs(double t, N_Vector y, N_Vector ydot, unsigned filter, bool with_velocity) {
  const int n = n_;
  Eigen::Map<const Vec> yy(sun::data(y), 2 * n);
  Eigen::Map<Vec> yd(sun::data(ydot), 2 * n);
  if (!yy.allFinite()) return 1;  // recoverable: ARKODE retries with a smaller step
  qtmp_ = yy.head(n);
  vtmp_ = yy.tail(n);
  // Without an IMEX filter, M(q) comes with the same evaluation when needed.
  const bool with_mass = !mass_in_arkode_ && filter == 0 && !mass_current(qtmp_);
  model_->evaluate(t, qtmp_, vtmp_, kForce | filter | (with_mass ? kMass : 0u), ev_);
  if (with_velocity) yd.head(n) = vtmp_;
  else yd.head(n).setZero();
  if (!mass_in_arkode_) {
    if (!factor_mass_at(qtmp_, t, with_mass ? &ev_.mass : nullptr)) return 1;
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

// M_blk x = (x_q, M x_v), pinned rows identity.
int ArkodeIntegrator::mass_times(N_Vector x, N_Vector mx, double, void* self) {
  ArkodeIntegrator& s = sun::user_data_as<ArkodeIntegrator>(self);
  const int n = s.n_;
  Eigen::Map<const Vec> xx(sun::data(x), 2 * n);
  Eigen::Map<Vec> out(sun::data(mx), 2 * n);
  out.head(n) = xx.head(n);
  out.tail(n) = s.mass_ * xx.tail(n);
  for (int i : s.fixed_) out[n + i] = xx[n + i];
  return 0;
}

void ArkodeIntegrator::error_handler(int, const char*, const char* function, char* msg, void* self) {
  ArkodeIntegrator& s = sun::user_data_as<ArkodeIntegrator>(self);
  s.last_error_ = std::string(function ? function : "") + ": " + (msg ? msg : "");
}

void ArkodeIntegrator::update_stats() {
  void* m = mem_.get();
  long etf = 0, sfails = 0, nfe = 0, nfi = 0, nni = 0;
  ARKStepGetNumErrTestFails(m, &etf);
  ARKStepGetNumStepSolveFails(m, &sfails);
  ARKStepGetNumRhsEvals(m, &nfe, &nfi);
  if (ls_) ARKStepGetNumNonlinSolvIters(m, &nni);
  stats_.rejected_steps = etf + sfails;  // stats_.steps: the steps accepted by finish_step
  stats_.rhs_evals = nfe + nfi;
  stats_.jac_evals = ls_ ? ls_->setups() : 0;  // every Newton-matrix setup evaluates ∂f/∂q, ∂f/∂v
  stats_.linear_setups = (ls_ ? ls_->setups() : 0) + (mls_ ? mls_->setups() : 0) + own_setups_;
  stats_.linear_solves = (ls_ ? ls_->solves() : 0) + (mls_ ? mls_->solves() : 0) + own_solves_;
  stats_.nonlinear_iters = nni;
  if (ls_) record_solver(ls_->sparse_solver());
  stats_.wall_s = own_.wall_s;
  stats_.cpu_s = own_.cpu_s;
}

StepResult ArkodeIntegrator::failure(int flag) {
  Outcome o = Outcome::diverged;
  if (flag == ARK_ERR_FAILURE || flag == ARK_TOO_CLOSE) o = Outcome::step_too_small;
  else if (flag == ARK_TOO_MUCH_WORK) o = Outcome::max_steps;
  Eigen::Map<const Vec> y(sun::data(y_.get()), 2 * n_);
  if (!y.allFinite() || flag == ARK_RHSFUNC_FAIL || flag == ARK_REPTD_RHSFUNC_ERR || flag == ARK_FIRST_RHSFUNC_ERR ||
      flag == ARK_UNREC_RHSFUNC_ERR)
    o = Outcome::nan;
  const std::string flag_name = sun::flag_name(ARKStepGetReturnFlagName(flag));
  return {o, name() + " failed with " + flag_name + (last_error_.empty() ? "" : ": ") + last_error_, flag, flag_name};
}

StepResult ArkodeIntegrator::advance_to(double t_out) {
  if (!mem_.get()) return {Outcome::diverged, name() + ": not initialized"};
  void* m = mem_.get();
  LibraryStepper arkode;
  arkode.set_stop_time = [m](double t_stop) { ARKStepSetStopTime(m, t_stop); };
  arkode.step = [this, m](double t_stop, double& t_reached) {
    return ARKStepEvolve(m, t_stop, y_.get(), &t_reached, ARK_ONE_STEP);
  };
  arkode.update_stats = [this] { update_stats(); };
  arkode.failure = [this](int flag) { return failure(flag); };
  arkode.y = sun::data(y_.get());
  return advance_library_steps(t_out, own_, arkode);
}

}  // namespace wl
