// One V-cycle of algebraic multigrid (hypre's BoomerAMG) as the preconditioner
// of the step matrix's Krylov solve (integrators/sparse_solver.h, method amg;
// docs/design.md §6.3). hypre is optional at build time: without it
// amg_available() is false and AmgPreconditioner's constructor throws.
//
// The hierarchy is built from S = (A + Aᵀ)/2, formed straight into hypre's
// storage (no copy of S kept). Unknown-based systems AMG: each row carries a kind, and
// BoomerAMG measures strength, coarsens and interpolates within a kind only
// (HYPRE_BoomerAMGSetNumFunctions / SetDofFunc), so the x, y and z components
// of the nodes and the sliding coordinates, weakly coupled to the positions
// (docs/models.md §2.1), form separate hierarchies joined by the smoother.
// The kinds are read from the pattern (dof_kinds_from_pattern), not from a model.
//
// hypre is built on MPI: the first AmgPreconditioner initializes MPI (a
// singleton process, MPI_COMM_SELF) when nobody has, and finalizes it at exit.
// hypre's state is process-wide: setups and cycles run one at a time in the
// process (a mutex), so solvers in several threads stay correct but wait.
#pragma once
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "models/core/types.h"

namespace wl {

// True when weavelab was built with hypre (CMake found libhypre-dev).
bool amg_available();

// The kind of each row of a square matrix, for systems AMG: a run of three
// consecutive rows whose columns have the same sparsity pattern is a node's
// position (kinds 0, 1, 2: x, y, z; every stencil holds whole 3×3 blocks of
// positions, docs/models.md §2.1); every other row is kind 3 (a sliding
// coordinate, or a DoF not in such a run). Reads the pattern only.
std::vector<int> dof_kinds_from_pattern(const Eigen::SparseMatrix<double, Eigen::ColMajor, std::int64_t>& a);

class AmgPreconditioner {
 public:
  using Matrix64 = Eigen::SparseMatrix<double, Eigen::ColMajor, std::int64_t>;
  struct Statistics {
    int levels = 0;               // of the last hierarchy
    long hierarchy_nonzeros = 0;  // Σ over its levels of the entries of A_l and P_l (A_0 = S)
    long setups = 0;
  };

  // `kinds`: one per row (dof_kinds_from_pattern), or empty for scalar AMG.
  // Throws std::runtime_error when weavelab was built without hypre.
  explicit AmgPreconditioner(std::vector<int> kinds);
  ~AmgPreconditioner();
  AmgPreconditioner(const AmgPreconditioner&) = delete;
  AmgPreconditioner& operator=(const AmgPreconditioner&) = delete;

  // Builds the hierarchy of S = (A + Aᵀ)/2 on a's pattern: entry k of S is
  // (a_k + a_transpose[k])/2 (a_k/2 where transpose[k] is −1, no transposed
  // entry). Returns false with `failure` set when hypre reports an error.
  bool setup(const Matrix64& a, std::span<const int> transpose, std::string& failure);
  // out = one V-cycle from zero on S out = in (the preconditioner P⁻¹ in).
  void apply(Eigen::Ref<const Vec> in, Eigen::Ref<Vec> out);
  const Statistics& statistics() const { return stats_; }
  int num_kinds() const { return num_kinds_; }

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  std::vector<int> kinds_;
  int num_kinds_ = 1;
  Statistics stats_;
};

}  // namespace wl
