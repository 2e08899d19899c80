#include "integrators/reduced_linear_solver.h"

#include <algorithm>
#include <stdexcept>

namespace wl {

// The SUNLinearSolver operations; content points back to the (non-owned)
// ReducedLinearSolver, which owns the SUNLinearSolver.
struct ReducedLinearSolverOps {
  static ReducedLinearSolver& self(SUNLinearSolver s) { return sun::user_data_as<ReducedLinearSolver>(s->content); }
  static SUNLinearSolver_Type gettype(SUNLinearSolver) { return SUNLINEARSOLVER_MATRIX_EMBEDDED; }
  static SUNLinearSolver_ID getid(SUNLinearSolver) { return SUNLINEARSOLVER_CUSTOM; }
  static int initialize(SUNLinearSolver) { return SUNLS_SUCCESS; }
  static int setup(SUNLinearSolver s, SUNMatrix) {
    ReducedLinearSolver& r = self(s);
    r.last_flag_ = r.setup() ? SUNLS_SUCCESS : SUNLS_PACKAGE_FAIL_REC;
    return r.last_flag_;
  }
  static int solve(SUNLinearSolver s, SUNMatrix, N_Vector x, N_Vector b, double) {
    ReducedLinearSolver& r = self(s);
    r.last_flag_ = r.solve(sun::data(b), sun::data(x)) ? SUNLS_SUCCESS : SUNLS_PACKAGE_FAIL_REC;
    if (!r.resid_) r.resid_ = sun::Vector(N_VClone(x));
    if (r.resid_) N_VConst(0.0, r.resid_.get());
    return r.last_flag_;
  }
  // A direct solve: one "iteration", zero residual. SUNDIALS reads these for
  // solvers that are not SUNLINEARSOLVER_DIRECT (an iteration count of 0 would
  // make IDA take the residual vector as the solution).
  static int numiters(SUNLinearSolver) { return 1; }
  // ARKODE requires this op before it accepts a mass-times-vector routine;
  // a direct solver has no use for the product.
  static int setatimes(SUNLinearSolver, void*, SUNATimesFn) { return SUNLS_SUCCESS; }
  static double resnorm(SUNLinearSolver) { return 0.0; }
  static N_Vector resid(SUNLinearSolver s) { return self(s).resid_.get(); }
  static sunindextype lastflag(SUNLinearSolver s) { return self(s).last_flag_; }
  static int free(SUNLinearSolver s) {
    if (!s) return SUNLS_SUCCESS;
    s->content = nullptr;  // owned by the ReducedLinearSolver
    SUNLinSolFreeEmpty(s);
    return SUNLS_SUCCESS;
  }
};

ReducedLinearSolver::ReducedLinearSolver(SUNContext ctx, Model& model, unsigned filter, bool constant_mass,
                                         const SparseSolver::Options& solver, SetupQuery query, Staleness stale,
                                         SolutionScale scale)
    : model_(model),
      filter_(filter),
      constant_mass_(constant_mass),
      query_(std::move(query)),
      stale_(std::move(stale)),
      scale_(std::move(scale)),
      n_(model.num_dofs()),
      fixed_(model.fixed_dofs().begin(), model.fixed_dofs().end()),
      pinned_(model.num_dofs(), 0),
      s_(model.pattern()),
      solver_(model.pattern(), model.fixed_dofs(), solver) {
  for (int i : fixed_) pinned_[i] = 1;
  // Newton corrections (and ARKODE's exact-mass solves of a well-conditioned
  // M) need no iterative refinement: one forward/back substitution each.
  solver_.set_refinement_steps(0);
  allocate_evaluation(model, ev_);
  allocate_evaluation(model, mev_);
  SUNLinearSolver s = SUNLinSolNewEmpty(ctx);
  if (!s) throw std::runtime_error("SUNLinSolNewEmpty failed");
  ls_ = sun::LinearSolver(s);
  s->content = this;
  s->ops->gettype = &ReducedLinearSolverOps::gettype;
  s->ops->getid = &ReducedLinearSolverOps::getid;
  s->ops->initialize = &ReducedLinearSolverOps::initialize;
  s->ops->setup = &ReducedLinearSolverOps::setup;
  s->ops->solve = &ReducedLinearSolverOps::solve;
  s->ops->numiters = &ReducedLinearSolverOps::numiters;
  s->ops->setatimes = &ReducedLinearSolverOps::setatimes;
  s->ops->resnorm = &ReducedLinearSolverOps::resnorm;
  s->ops->resid = &ReducedLinearSolverOps::resid;
  s->ops->lastflag = &ReducedLinearSolverOps::lastflag;
  s->ops->free = &ReducedLinearSolverOps::free;
}

ReducedLinearSolver::~ReducedLinearSolver() = default;

bool ReducedLinearSolver::setup() {
  double t = 0.0;
  const double* y = nullptr;
  if (!query_(t, y, c_) || !y) return false;
  q_ = Eigen::Map<const Vec>(y, n_);
  v_ = Eigen::Map<const Vec>(y + n_, n_);
  if (!q_.allFinite() || !v_.allFinite()) return false;
  const bool need_k = c_.k != 0.0 && c_.beta != 0.0;
  const bool need_kb = c_.k != 0.0;  // K is also needed for the right-hand side
  const bool need_d = c_.d != 0.0;
  if (filter_ == 0 && !constant_mass_) {  // one evaluation for everything
    model_.evaluate(t, q_, v_, kMass | (need_kb ? kDfdq : 0u) | (need_d ? kDfdv : 0u), ev_);
    mass_ = &ev_.mass;
  } else {
    if (need_kb || need_d) model_.evaluate(t, q_, v_, (need_kb ? kDfdq : 0u) | (need_d ? kDfdv : 0u) | filter_, ev_);
    // The mass is never split between IMEX parts: evaluate it without the filter.
    if (!constant_mass_ || !have_mass_) model_.evaluate(t, q_, v_, kMass, mev_);
    have_mass_ = true;
    mass_ = &mev_.mass;
  }
  const long nnz = s_.nonZeros();
  const double* mv = mass_->valuePtr();
  const double* dv = ev_.dfdv.valuePtr();
  const double* kv = ev_.dfdq.valuePtr();
  double* sv = s_.valuePtr();
  const double kk = need_k ? c_.k * c_.beta / c_.alpha : 0.0;
  for (long p = 0; p < nnz; ++p) {
    double a = c_.m * mv[p];
    if (need_d) a -= c_.d * dv[p];
    if (need_k) a -= kk * kv[p];
    sv[p] = a;
  }
  ++setups_;
  factorized_ = s_.coeffs().allFinite() && solver_.factorize(s_);
  return factorized_;
}

bool ReducedLinearSolver::solve(const double* b, double* x) {
  // SUNDIALS never calls setup on a matrix-embedded solver: refactorize here.
  if ((!factorized_ || (stale_ && stale_(c_))) && !setup()) return false;
  const int n = n_;
  Eigen::Map<const Vec> bq(b, n), bv(b + n, n);
  Eigen::Map<Vec> xq(x, n), xv(x + n, n);
  // Pinned rows p·x = b; the known values enter the free rows below.
  wq_ = bq / c_.alpha;
  bool pinned_v = false;
  u_.setZero(n);
  for (int i : fixed_) {
    wq_[i] = bq[i] / c_.pinned;
    u_[i] = bv[i] / c_.pinned;
    pinned_v = pinned_v || u_[i] != 0.0;
  }
  // r = b_v (or M b_v on free columns) + k K w_q − (m M − d D) u on the free rows.
  if (c_.mass_times_bv) {
    xv_ = bv;
    for (int i : fixed_) xv_[i] = 0.0;
    r_ = *mass_ * xv_;
  } else {
    r_ = bv;
  }
  if (c_.k != 0.0) r_.noalias() += c_.k * (ev_.dfdq * wq_);
  if (pinned_v) {
    if (!c_.mass_times_bv) r_.noalias() -= c_.m * (*mass_ * u_);
    if (c_.d != 0.0) r_.noalias() += c_.d * (ev_.dfdv * u_);
  }
  if (!solver_.solve(r_, xv_)) return false;  // zero on pinned DoFs
  for (int i = 0; i < n; ++i) {
    if (pinned_[i]) {
      xq[i] = wq_[i];
      xv[i] = u_[i];
    } else {
      xv[i] = xv_[i];
      xq[i] = (bq[i] + c_.beta * xv_[i]) / c_.alpha;
    }
  }
  if (scale_) {
    const double f = scale_();
    if (f != 1.0) {
      xq *= f;
      xv *= f;
    }
  }
  ++solves_;
  return xq.allFinite() && xv.allFinite();
}

}  // namespace wl
