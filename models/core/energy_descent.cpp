#include "models/core/energy_descent.h"

#include <Eigen/SparseCholesky>
#include <cmath>

namespace wl {

DescentResult descend_energy(Model& m, Vec& q, const std::vector<int>& held_dofs, double tol, int max_steps,
                             const std::function<bool()>& stop) {
  const int n = m.num_dofs();
  std::vector<char> held(n, 0);
  for (int d : held_dofs) held[d] = 1;
  for (int d : m.fixed_dofs()) held[d] = 1;
  std::vector<int> free;
  for (int d = 0; d < n; ++d)
    if (!held[d]) free.push_back(d);
  const int nf = static_cast<int>(free.size());
  std::vector<int> position(n, -1);
  for (int k = 0; k < nf; ++k) position[free[k]] = k;

  const Vec v = Vec::Zero(n);
  Evaluation eval;
  allocate_evaluation(m, eval);
  DescentResult out;
  out.energy_J = m.potential_energy(q);
  out.residual_N = INFINITY;
  double mu = 0.0;
  Eigen::SimplicialLDLT<SparseMatrix> solver;
  for (int step = 0; step < max_steps; ++step) {
    m.evaluate(0.0, q, v, kForce | kDfdq, eval);
    out.residual_N = 0.0;
    for (int d : free) out.residual_N = std::max(out.residual_N, std::abs(eval.force[d]));
    if (out.residual_N <= tol || (stop && stop())) break;
    std::vector<Eigen::Triplet<double>> entries;
    double diag = 0.0;
    for (int c = 0; c < eval.dfdq.outerSize(); ++c)
      for (SparseMatrix::InnerIterator it(eval.dfdq, c); it; ++it) {
        const int i = position[it.row()], j = position[it.col()];
        if (i < 0 || j < 0) continue;
        entries.emplace_back(i, j, -it.value());
        if (i == j) diag = std::max(diag, -it.value());
      }
    SparseMatrix A(nf, nf);
    A.setFromTriplets(entries.begin(), entries.end());
    Vec rhs(nf);
    for (int k = 0; k < nf; ++k) rhs[k] = eval.force[free[k]];
    bool stepped = false;
    for (int attempt = 0; attempt < 40 && !stepped; ++attempt) {
      SparseMatrix shifted = A;
      for (int k = 0; k < nf; ++k) shifted.coeffRef(k, k) += mu * std::max(diag, 1e-300);
      solver.compute(shifted);
      if (solver.info() == Eigen::Success) {
        const Vec dq = solver.solve(rhs);
        Vec trial = q;
        for (int k = 0; k < nf; ++k) trial[free[k]] += dq[k];
        const double e = trial.allFinite() && m.invalid_state(trial).empty() ? m.potential_energy(trial) : INFINITY;
        if (e <= out.energy_J) {
          q = trial;
          out.energy_J = e;
          stepped = true;
          ++out.steps;
          mu = mu > 1e-12 ? mu / 4.0 : 0.0;
          break;
        }
      }
      mu = mu > 0.0 ? mu * 8.0 : 1e-8;
    }
    if (!stepped) break;
  }
  return out;
}

}  // namespace wl
