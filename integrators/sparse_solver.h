// Sparse direct solver for the implicit step matrix with pinned DoFs removed.
// The symbolic analysis is done once per pattern (at the first factorize, on
// real values); every later factorize() reuses it.
// Backends: UMFPACK (general, the default since the yarn step matrix is not
// symmetric, docs/models.md §7.6) and CHOLMOD (symmetric positive definite).
#pragma once
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "models/core/types.h"

namespace wl {

class SparseSolver {
 public:
  enum class Backend { umfpack, cholmod };
  // `pattern` is the full matrix pattern; `fixed` the DoFs to eliminate.
  SparseSolver(const SparseMatrix& pattern, std::span<const int> fixed, Backend backend = Backend::umfpack);
  ~SparseSolver();
  SparseSolver(const SparseSolver&) = delete;
  SparseSolver& operator=(const SparseSolver&) = delete;

  // Numeric factorization of A restricted to the free DoFs. Returns false if singular.
  bool factorize(const SparseMatrix& a);
  // Solves A x = b on the free DoFs; x is zero on fixed DoFs.
  void solve(const Vec& b, Vec& x) const;
  int num_free() const { return static_cast<int>(free_.size()); }
  // UMFPACK's iterative refinement steps per solve (its default: up to 2).
  // Inside a Newton iteration the iteration itself refines: 0 saves the
  // residual and the extra triangular solves.
  void set_refinement_steps(int steps);
  Backend backend() const { return backend_; }

 private:
  struct Impl;
  Backend backend_;
  std::vector<int> free_;        // reduced index -> full index
  std::vector<int> value_map_;   // reduced nnz -> full nnz
  SparseMatrix reduced_;
  std::unique_ptr<Impl> impl_;
  bool analyzed_ = false;
  mutable Vec rb_, rx_;
};

}  // namespace wl
