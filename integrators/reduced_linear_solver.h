// A custom matrix-embedded SUNLinearSolver for the 2n×2n Newton systems that
// IDA and ARKODE form for a second-order system in y = (q, v). It never forms
// the block matrix: every solve is ONE n×n sparse solve with the
// backward-Euler-shaped matrix S = m·M − d·∂f/∂v − (k·β/α)·∂f/∂q on the free
// DoFs (integrators/sparse_solver.h, the method the run chose; symbolic
// analysis once, pinned DoFs eliminated).
//
// The block system, on the rows of free DoFs, is
//   [ α I      −β I        ] [x_q]   [b_q]
//   [ −k K     m M − d D   ] [x_v] = [b_v]        K = ∂f/∂q, D = ∂f/∂v, M = M(q)
// and on the rows of pinned DoFs p·x = b. From the q rows x_q = (b_q + β x_v)/α;
// substituted into the v rows:
//   (m M − d D − (kβ/α) K) x_v = b_v + k K (b_q/α)       (free rows).
// Pinned columns of K, D, M are moved to the right-hand side with the known
// pinned values. The callers' coefficients:
//   IDA  (J = ∂G/∂y + c_j ∂G/∂y′ for G = [q′ − v ; M v′ − f]):
//        α = c_j, β = 1, k = 1, m = c_j, d = 1, p = c_j
//        → (c_j M − D − K/c_j) x_v = b_v + K b_q / c_j
//   ARKODE with the block mass [I 0 ; 0 M] (A = M_blk − γ J_blk, J_blk = [0 I ; K D]):
//        α = 1, β = γ, k = γ, m = 1, d = γ, p = 1 → (M − γD − γ²K) x_v = b_v + γ K b_q
//   ARKODE explicit form y′ = (v, M(q)⁻¹ f) (A = I − γJ): the v rows are
//        multiplied by M, i.e. the same as above with b_v replaced by M b_v
//        (Coefficients::mass_times_bv), pinned mass columns absent.
//   ARKODE mass solve [I 0 ; 0 M] x = b: α = 1, β = 0, k = 0, m = 1, d = 0, p = 1.
// APPROXIMATION: the ∂M(q)/∂q terms (∂(M v′)/∂q in IDA, ∂(M⁻¹)/∂q·f in the
// explicit form) are neglected; M, K, D are taken at the state where the
// integrator asks for a setup (its current Newton iterate). The Newton
// iterations of IDA and ARKODE converge with this inexact Jacobian; they only
// need it to be close (the residual they drive to zero is exact).
//
// The SUNDIALS type is SUNLINEARSOLVER_MATRIX_EMBEDDED (IDASetLinearSolver /
// ARKStepSetLinearSolver with a NULL matrix). IDA and ARKODE never call setup
// on such a solver (their lsetup is disabled for matrix-embedded solvers,
// ida_ls.c/arkode_ls.c), so the solver decides itself when to refactorize:
// before every solve it asks the integrator's `Staleness` hook (e.g. "c_j
// changed by more than IDA's 25% rule", "a new step attempt began") and, if
// stale or never factorized, evaluates K, D, M at the integrator's current
// Newton iterate (SetupQuery) and refactorizes. SUNDIALS also treats such a
// solver as "iterative" in two places, handled here: it reads the iteration
// count (we report 1, so x is used), and some versions skip a solve whose
// right-hand side is below eplifac·(nonlinear tolerance) — the ARKODE adapter
// sets EpsLin tiny so every Newton correction is solved.
#pragma once
#include <functional>
#include <memory>
#include <span>
#include <vector>

#include "integrators/sparse_solver.h"
#include "integrators/sundials_handles.h"
#include "models/core/model.h"

namespace wl {

class ReducedLinearSolver {
 public:
  struct Coefficients {
    double alpha = 1.0, beta = 0.0, k = 0.0, m = 1.0, d = 0.0;
    double pinned = 1.0;         // diagonal of the pinned rows
    bool mass_times_bv = false;  // explicit form: the v rows were multiplied by M
  };
  // Where and how to form the matrix, asked at every setup: the time, the
  // state y = (q, v) (2n values) and the coefficients. Returns false on failure.
  using SetupQuery = std::function<bool(double& t, const double*& y, Coefficients& c)>;
  // Asked before every solve: must the matrix be re-formed now? Empty: only
  // the first solve factorizes (constant matrices, e.g. the mass).
  using Staleness = std::function<bool(const Coefficients& at_setup)>;
  // A factor applied to every solution (IDA's correction for a changed c_j), or empty.
  using SolutionScale = std::function<double()>;

  // `filter` restricts K and D to a term subset (kImplicitTerms for IMEX);
  // M is always the full mass. `constant_mass`: evaluate M once. `solver`:
  // the sparse solver's method and what the model says of the matrix.
  ReducedLinearSolver(SUNContext ctx, Model& model, unsigned filter, bool constant_mass,
                      const SparseSolver::Options& solver, SetupQuery query, Staleness stale = {},
                      SolutionScale scale = {});
  ~ReducedLinearSolver();
  ReducedLinearSolver(const ReducedLinearSolver&) = delete;
  ReducedLinearSolver& operator=(const ReducedLinearSolver&) = delete;

  SUNLinearSolver get() const { return ls_.get(); }
  // Forms and factorizes the matrix at the SetupQuery point.
  bool setup();
  // Solves the block system (refactorizing first if never done or stale).
  bool solve(const double* b, double* x);
  long setups() const { return setups_; }  // numeric factorizations (and Jacobian evaluations)
  long solves() const { return solves_; }
  const SparseMatrix& matrix() const { return s_; }  // the last factorized n×n matrix
  const SparseSolver& sparse_solver() const { return solver_; }

 private:
  Model& model_;
  unsigned filter_;
  bool constant_mass_, have_mass_ = false, factorized_ = false;
  SetupQuery query_;
  Staleness stale_;
  SolutionScale scale_;
  int n_;
  std::vector<int> fixed_;
  std::vector<char> pinned_;
  Evaluation ev_, mev_;  // K, D (and M) at the setup point; M when evaluated alone
  const SparseMatrix* mass_ = nullptr;
  SparseMatrix s_;  // m M − d D − (kβ/α) K
  SparseSolver solver_;
  Coefficients c_;
  Vec q_, v_, wq_, r_, xv_, u_;
  long setups_ = 0, solves_ = 0;
  int last_flag_ = 0;
  sun::Vector resid_;  // reported as the "residual" (never read for nonzero iterations)
  sun::LinearSolver ls_;

  friend struct ReducedLinearSolverOps;
};

}  // namespace wl
