// Sparse direct linear solvers for the SUNDIALS adapters, on a CSC
// SUNSparseMatrix: SUNDIALS' own KLU, or a custom SUNLinearSolver around the
// project's SparseSolver (UMFPACK, symbolic analysis once per pattern).
// Also BlockSystem: the 2n×2n block pattern of a first-order system in
// y = (q, v) built from a model's pattern, and its fill.
#pragma once
#include <span>
#include <vector>

#include "integrators/integrator.h"
#include "integrators/sundials_handles.h"

namespace wl::sun {

// A CSC SUNSparseMatrix with the structure of `pattern` (values zero).
Matrix make_sparse_matrix(const SparseMatrix& pattern, SUNContext ctx);
// Writes the structure and values of `a` into `m` (same size and nnz).
// SUNDIALS zeroes the index arrays of sparse matrices before Jacobian calls,
// so the structure is rewritten every time.
void copy_to(const SparseMatrix& a, SUNMatrix m);

// The custom SUNLinearSolver around SparseSolver (UMFPACK).
LinearSolver make_umfpack_solver(SUNContext ctx);
// KLU or UMFPACK as `backend` asks (automatic = KLU: measured faster on a
// 4800-DoF spring net, ida 6.7 s vs 9.0 s CPU, arkode-dirk 92 s vs 100 s).
IntegratorOptions::SparseBackend resolve(IntegratorOptions::SparseBackend backend);
LinearSolver make_sparse_solver(IntegratorOptions::SparseBackend backend, N_Vector y, SUNMatrix a, SUNContext ctx);
const char* backend_name(IntegratorOptions::SparseBackend backend);

// J = [ a_qq·I        a_qv·I        ]   rows of pinned DoFs (both the q and the
//     [ k·K           d·D + m·M     ]   v row) hold only `pinned_diag` on the
// diagonal. K, D, M share the model pattern; a null matrix contributes zero.
class BlockSystem {
 public:
  BlockSystem(const SparseMatrix& pattern, std::span<const int> fixed);
  void fill(double a_qq, double a_qv, double k, const SparseMatrix* K, double d, const SparseMatrix* D, double m,
            const SparseMatrix* M, double pinned_diag);
  const SparseMatrix& matrix() const { return j_; }

 private:
  int n_;
  SparseMatrix j_;
  std::vector<char> pinned_;     // per DoF
  std::vector<int> diag_qq_, diag_qv_, diag_vv_;  // per DoF
  std::vector<int> slot_vq_, slot_vv_;            // per model pattern entry
  std::vector<int> row_of_;                       // per model pattern entry
};

}  // namespace wl::sun
