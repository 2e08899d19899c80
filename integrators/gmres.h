// Restarted GMRES with right preconditioning (Saad, Iterative Methods for
// Sparse Linear Systems, Alg. 9.5; docs/design.md §6.3). It solves A x = b
// for the true matrix A, with a preconditioner P ≈ A applied as z = P⁻¹ w, and
// stops when the TRUE relative residual ‖b − A x‖ / ‖b‖ ≤ tol: with right
// preconditioning the residual GMRES minimizes is the residual of A itself.
// The workspace is allocated once (no allocation per solve).
#pragma once
#include <functional>

#include "models/core/types.h"

namespace wl {

class Gmres {
 public:
  // y = A x and z = P⁻¹ w on vectors of length n.
  using Apply = std::function<void(Eigen::Ref<const Vec> in, Eigen::Ref<Vec> out)>;
  Gmres(int n, int restart);

  struct Result {
    bool converged = false;
    int iterations = 0;              // Arnoldi steps (one A product and one P⁻¹ solve each)
    double relative_residual = 0.0;  // ‖b − A x‖ / ‖b‖ at exit, recomputed from x
  };
  // Starts from the x given (e.g. zero or the previous solution).
  Result solve(const Apply& a, const Apply& precond, const Vec& b, Vec& x, double tol, int max_iters);

 private:
  int n_, m_;
  Eigen::MatrixXd v_, z_, h_;  // Krylov basis, preconditioned basis, Hessenberg matrix
  Vec cs_, sn_, g_, y_, w_, r_;
};

}  // namespace wl
