// The lowest vibration modes of a linearized model (docs/models.md §10): the
// generalized symmetric eigenproblem K φ = ω² M φ on the free DoFs (the fixed
// DoFs removed), solved by Lanczos iteration (Spectra's SymGEigsShiftSolver)
// on the shift-inverted operator (K − σM)⁻¹M. (K − σM) is factorized once by
// the repository's SparseSolver (UMFPACK LU: K − σM may be indefinite). M must
// be symmetric positive definite on the free DoFs, K symmetric.
#pragma once
#include <span>
#include <string>
#include <vector>

#include "models/core/types.h"

namespace wl {

struct ModalOptions {
  int count = 10;      // modes wanted: those with ω² nearest the shift
  double shift = 0.0;  // σ [1/s²]; 0 gives the lowest modes of a stable K
  int max_restarts = 1000;
  double tolerance = 1e-10;  // Spectra's relative convergence tolerance of the Ritz values
};

struct ModalResult {
  bool ok = false;
  std::string message;              // why not, when !ok
  std::vector<double> eigenvalues;  // ω² [1/s²], ascending
  // Column k: φ_k on every DoF (zero on the fixed ones), normalized to φᵀMφ = 1.
  Eigen::MatrixXd shapes;
  long operator_products = 0;  // solves with the factorized K − σM
};

// Hz of an eigenvalue ω²: ω/2π, negative (−√|ω²|/2π) for an unstable direction.
double frequency_hz(double eigenvalue);

// `stiffness` and `mass` full-size and symmetric; `fixed` the DoFs removed.
ModalResult lowest_modes(const SparseMatrix& stiffness, const SparseMatrix& mass, std::span<const int> fixed,
                         const ModalOptions& options = {});

}  // namespace wl
