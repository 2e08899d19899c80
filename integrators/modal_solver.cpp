#include "integrators/modal_solver.h"

#include <Spectra/MatOp/SparseSymMatProd.h>
#include <Spectra/SymGEigsShiftSolver.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <numeric>

#include "integrators/sparse_solver.h"

namespace wl {
namespace {

// y = (K − σM)⁻¹ x on the free DoFs, for Spectra's shift-invert mode: the
// operator factorizes K − σM with the repository's SparseSolver at set_shift().
class ShiftInvertOperator {
 public:
  using Scalar = double;
  ShiftInvertOperator(const SparseMatrix& k, const SparseMatrix& m, std::span<const int> fixed, std::vector<int> free)
      : k_(k), m_(m), fixed_(fixed.begin(), fixed.end()), free_(std::move(free)) {}
  Eigen::Index rows() const { return static_cast<Eigen::Index>(free_.size()); }
  Eigen::Index cols() const { return rows(); }
  void set_shift(double sigma) {
    SparseMatrix a = k_ - sigma * m_;
    a.makeCompressed();
    SparseSolverOptions o;
    o.method = LinearSolverMethod::umfpack;
    solver_ = std::make_unique<SparseSolver>(a, fixed_, o);
    if (!solver_->factorize(a)) failure_ = "K − σM could not be factorized: " + solver_->failure();
    b_ = Vec::Zero(k_.rows());
  }
  void perform_op(const double* x_in, double* y_out) const {
    for (size_t i = 0; i < free_.size(); ++i) b_[free_[i]] = x_in[i];
    solver_->solve(b_, x_);
    for (size_t i = 0; i < free_.size(); ++i) y_out[i] = x_[free_[i]];
    ++products_;
  }
  const std::string& failure() const { return failure_; }
  long products() const { return products_; }

 private:
  const SparseMatrix &k_, &m_;
  std::vector<int> fixed_, free_;
  std::unique_ptr<SparseSolver> solver_;
  std::string failure_;
  mutable Vec b_, x_;
  mutable long products_ = 0;
};

// The free rows and columns of a full-size matrix.
SparseMatrix restrict_to(const SparseMatrix& a, const std::vector<int>& free) {
  std::vector<int> reduced(a.rows(), -1);
  for (size_t i = 0; i < free.size(); ++i) reduced[free[i]] = static_cast<int>(i);
  std::vector<Eigen::Triplet<double>> t;
  for (int c = 0; c < a.outerSize(); ++c)
    for (SparseMatrix::InnerIterator it(a, c); it; ++it)
      if (reduced[it.row()] >= 0 && reduced[c] >= 0) t.emplace_back(reduced[it.row()], reduced[c], it.value());
  const int n = static_cast<int>(free.size());
  SparseMatrix r(n, n);
  r.setFromTriplets(t.begin(), t.end());
  return r;
}

}  // namespace

double frequency_hz(double eigenvalue) {
  const double w = std::sqrt(std::abs(eigenvalue)) / (2 * std::numbers::pi);
  return eigenvalue < 0 ? -w : w;
}

ModalResult lowest_modes(const SparseMatrix& stiffness, const SparseMatrix& mass, std::span<const int> fixed,
                         const ModalOptions& opt) {
  ModalResult r;
  const int n = static_cast<int>(stiffness.rows());
  std::vector<char> is_fixed(n, 0);
  for (int d : fixed) is_fixed[d] = 1;
  std::vector<int> free;
  for (int i = 0; i < n; ++i)
    if (!is_fixed[i]) free.push_back(i);
  const int nf = static_cast<int>(free.size());
  if (opt.count < 1 || opt.count >= nf) {
    r.message = "cannot find " + std::to_string(opt.count) + " modes of a system with " + std::to_string(nf) +
                " free DoFs (at most " + std::to_string(nf - 1) + ")";
    return r;
  }
  ShiftInvertOperator op(stiffness, mass, fixed, free);
  const SparseMatrix m_free = restrict_to(mass, free);
  Spectra::SparseSymMatProd<double> bop(m_free);
  // Lanczos basis: twice the wanted count plus a margin (Spectra's advice: ncv ≥ 2·nev).
  const int ncv = std::min(nf, std::max(2 * opt.count + 1, opt.count + 20));
  Spectra::SymGEigsShiftSolver<ShiftInvertOperator, Spectra::SparseSymMatProd<double>, Spectra::GEigsMode::ShiftInvert>
      eigs(op, bop, opt.count, ncv, opt.shift);
  if (!op.failure().empty()) {
    r.message = op.failure();
    return r;
  }
  eigs.init();
  const Eigen::Index converged =
      eigs.compute(Spectra::SortRule::LargestMagn, opt.max_restarts, opt.tolerance, Spectra::SortRule::SmallestAlge);
  r.operator_products = op.products();
  if (eigs.info() != Spectra::CompInfo::Successful || converged < opt.count) {
    r.message = "Lanczos iteration converged " + std::to_string(converged) + " of " + std::to_string(opt.count) +
                " modes after " + std::to_string(eigs.num_iterations()) + " restarts";
    return r;
  }
  const Vec values = eigs.eigenvalues();
  const Eigen::MatrixXd vectors = eigs.eigenvectors();
  r.eigenvalues.assign(values.data(), values.data() + values.size());
  r.shapes = Eigen::MatrixXd::Zero(n, values.size());
  for (Eigen::Index k = 0; k < values.size(); ++k) {
    const Vec phi = vectors.col(k);
    const double norm = std::sqrt(phi.dot(m_free * phi));  // Spectra's are B-normalized; keep it explicit
    for (int i = 0; i < nf; ++i) r.shapes(free[i], k) = phi[i] / norm;
  }
  r.ok = true;
  return r;
}

}  // namespace wl
