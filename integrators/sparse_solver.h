// Sparse solver for the implicit step matrix with pinned DoFs removed
// (docs/design.md §6.3). The method is chosen by the matrix:
//   cholmod  CHOLMOD LLᵀ (supernodal or simplicial as CHOLMOD judges by the
//            flop count, METIS ordering): only for a matrix the model declares
//            symmetric; refused otherwise;
//   umfpack  UMFPACK LU (symmetric strategy, METIS ordering): any matrix;
//   gmres    restarted GMRES on the true matrix A, right-preconditioned by a
//            CHOLMOD factor of the symmetric part S = (A + Aᵀ)/2 (the LU of A
//            when S is not positive definite). The factor is kept over later
//            matrices and rebuilt when a solve needed more than kRefactorIterations
//            Arnoldi steps or kMaxReuse matrices have passed; a solve that does
//            not converge with a kept factor is retried with a fresh one.
//            Stops at ‖b − A x‖ ≤ kGmresTolerance ‖b‖.
//   amg      the same GMRES on A, right-preconditioned by one BoomerAMG V-cycle
//            of S (integrators/amg_preconditioner.h; hypre, optional at build
//            time: refused without it). The hierarchy is kept over later
//            matrices and rebuilt when a solve needed more than
//            kAmgRefreshGrowth times the Arnoldi steps of the first solve after
//            it was built, or kMaxReuse matrices have passed. Its memory is
//            O(nnz of A), where a factor's fill grows faster than the DoFs.
//   auto     cholmod for a symmetric matrix (umfpack when it is not positive
//            definite), umfpack below 300 free DoFs, gmres for larger nearly
//            symmetric ones (measured ‖A − Aᵀ‖_F / ‖A‖_F below kNearlySymmetric),
//            umfpack otherwise; from kAmgMinFree free DoFs on, where hypre is
//            built, amg for a symmetric or nearly symmetric matrix.
// The symbolic analyses are done once (at the first matrix, on real values).
// Sparse indices passed to SuiteSparse are 64-bit (umfpack_dl, cholmod_l).
#pragma once
#include <cstdint>
#include <limits>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "models/core/types.h"

namespace wl {

enum class LinearSolverMethod { automatic, umfpack, cholmod, gmres, amg };
// Names in documentation order: auto, umfpack, cholmod, gmres, amg (listed
// whether or not hypre is built; SparseSolver refuses amg without it).
std::vector<std::string> linear_solver_names();
const char* to_string(LinearSolverMethod m);
// Throws std::invalid_argument for an unknown name.
LinearSolverMethod parse_linear_solver(const std::string& name);

// Relative residual the gmres and amg methods reach (the direct methods reach ~1e-14).
constexpr double kGmresTolerance = 1e-10;
// Free DoFs from which CHOLMOD's supernodal factorization may use OpenMP
// threads: never by default. Its regions name a team of 4; on the 2-core
// machine one thread was faster at every size measured, 1 317 to 328 197
// DoFs (docs/design.md §11). A machine with more cores may set
// SparseSolverOptions::threaded_min_free.
constexpr int kThreadedMinFree = std::numeric_limits<int>::max();
// auto: amg (where hypre is built) from this many free DoFs on. The scale study
// (experiments/scale/RESULTS.md) has the woven cloth's amg step slower than the
// factor route's at 17×17 (1 317 DoFs), about even at 33×33 (5 189) and faster
// from 65×65 on; on the knitted stockinette (4 944 DoFs) amg needed more
// iterations and was slower.
// auto keeps the factor route up to the 65×65 class (20 613 DoFs), where the
// lab's studies and tests run, and takes amg from the 129×129 class
// (82 181 DoFs) on, where the factor's fill is what grows.
constexpr int kAmgMinFree = 50000;

struct SparseSolverOptions {
  LinearSolverMethod method = LinearSolverMethod::umfpack;
  // What the model says of the matrix (Model::asymmetric_terms()): empty =
  // symmetric; else the terms whose Jacobians break symmetry.
  std::vector<std::string> asymmetric_terms = {"unknown"};
  // OpenMP threads inside the factorizations only from this many free DoFs on
  // (kThreadedMinFree, measured: never); below, the regions CHOLMOD opens run
  // on the calling thread alone. Results are bitwise the same either way.
  int threaded_min_free = -1;  // −1: kThreadedMinFree
};

class SparseSolver {
 public:
  using Options = SparseSolverOptions;
  struct Statistics {
    long updates = 0;         // matrices given to factorize()
    long factorizations = 0;  // numeric factorizations (of A or of S)
    long solves = 0;
    long krylov_iterations = 0;
    long amg_lu_fallbacks = 0;   // amg: fresh V-cycles that did not serve, replaced by the LU of A
    double max_asymmetry = 0.0;  // max ‖A − Aᵀ‖_F / ‖A‖_F over the matrices seen
  };

  // `pattern` is the full matrix pattern; `fixed` the DoFs to eliminate.
  // Throws std::invalid_argument when `options.method` is cholmod and the
  // matrix is not declared symmetric, or amg without hypre.
  SparseSolver(const SparseMatrix& pattern, std::span<const int> fixed, Options options = {});
  ~SparseSolver();
  SparseSolver(const SparseSolver&) = delete;
  SparseSolver& operator=(const SparseSolver&) = delete;

  // Takes A (pattern()-shaped) restricted to the free DoFs as the matrix of
  // every later solve, and factorizes it as the method needs. Returns false
  // when it cannot be solved with (failure() says why).
  bool factorize(const SparseMatrix& a);
  // Solves A x = b with the matrix last given to factorize(), on the free DoFs
  // (x is zero on fixed DoFs), to the method's accuracy: direct, or
  // ‖b − A x‖ ≤ kGmresTolerance ‖b‖ on the free rows for gmres. Returns false
  // (failure() says why) when gmres does not get there. Const: what gmres
  // refreshes (its preconditioner) is a cache of the same matrix. With
  // `from_x`, gmres starts from the x given (a warm start: a nearby system's
  // solution, such as the previous step's); the direct methods ignore it.
  bool solve(const Vec& b, Vec& x, bool from_x = false) const;
  int num_free() const { return static_cast<int>(free_.size()); }
  // Starts over as a new solver on the same pattern would (method, statistics,
  // preconditioner, the value-dependent UMFPACK analysis), keeping the reduced
  // pattern and CHOLMOD's symbolic analysis, which read the pattern only.
  void restart();
  // UMFPACK's iterative refinement steps per solve (its default: up to 2).
  // Inside a Newton iteration the iteration itself refines: 0 saves the
  // residual and the extra triangular solves.
  void set_refinement_steps(int steps);

  LinearSolverMethod requested() const { return options_.method; }
  // The method in use (never automatic after the first factorize()).
  LinearSolverMethod method() const { return method_; }
  // Method, backend and ordering as recorded in run summaries.
  std::string description() const;
  const Statistics& statistics() const { return stats_; }
  // Bytes the solver holds now, by what holds them (the scale study's breakdown):
  // its copies of the matrix (A on the free DoFs, S, A by rows, index maps), the
  // preconditioner (CHOLMOD's factor L, or the AMG hierarchy counted as its
  // entries: 8 bytes a value, 4 an index; UMFPACK's LU is not counted) and
  // GMRES's bases.
  struct Memory {
    double matrices = 0.0, preconditioner = 0.0, krylov = 0.0;
  };
  Memory memory() const;
  const std::string& failure() const { return failure_; }

 private:
  struct Impl;
  using Index64 = std::int64_t;
  void choose_method();
  bool factor_preconditioner() const;
  bool factor_lu() const;
  bool factor_cholesky(bool symmetric_part) const;
  void update_symmetric_part() const;  // impl_->sym = (A + Aᵀ)/2
  bool factor_amg() const;
  bool gmres_solve(const Vec& rb, Vec& rx, bool from_x) const;

  Options options_;
  LinearSolverMethod method_;
  std::vector<int> free_;  // reduced index -> full index
  // 32-bit: the model's pattern has 32-bit indices (fewer than 2³¹ entries).
  std::vector<int> value_map_;      // reduced nnz -> full nnz
  std::vector<int> transpose_map_;  // reduced nnz -> nnz of the transposed entry (−1: none)
  Eigen::SparseMatrix<double, Eigen::ColMajor, Index64> reduced_;  // A on the free DoFs
  std::unique_ptr<Impl> impl_;
  mutable Statistics stats_;
  mutable std::string failure_;
  mutable Vec rb_, rx_;
};

}  // namespace wl
