#include "integrators/sparse_solver.h"

#include <Eigen/CholmodSupport>
#include <Eigen/UmfPackSupport>
#include <stdexcept>

namespace wl {

struct SparseSolver::Impl {
  Eigen::UmfPackLU<SparseMatrix> lu;
  Eigen::CholmodSupernodalLLT<SparseMatrix, Eigen::Lower> llt;
};

SparseSolver::SparseSolver(const SparseMatrix& pattern, std::span<const int> fixed, Backend backend)
    : backend_(backend), impl_(std::make_unique<Impl>()) {
  const int n = static_cast<int>(pattern.rows());
  std::vector<int> reduced_index(n, 0);
  for (int i : fixed) reduced_index[i] = -1;
  for (int i = 0; i < n; ++i)
    if (reduced_index[i] == 0) {
      reduced_index[i] = static_cast<int>(free_.size());
      free_.push_back(i);
    }
  const int m = static_cast<int>(free_.size());
  std::vector<Eigen::Triplet<double, int>> trip;
  for (int col = 0; col < n; ++col) {
    const int rc = reduced_index[col];
    if (rc < 0) continue;
    for (SparseMatrix::InnerIterator it(pattern, col); it; ++it) {
      const int rr = reduced_index[it.row()];
      if (rr < 0) continue;
      trip.emplace_back(rr, rc, 0.0);
    }
  }
  reduced_.resize(m, m);
  reduced_.setFromTriplets(trip.begin(), trip.end());
  reduced_.makeCompressed();
  // Map every reduced entry to its position in the full pattern's value array.
  value_map_.resize(reduced_.nonZeros());
  for (int col = 0; col < n; ++col) {
    const int rc = reduced_index[col];
    if (rc < 0) continue;
    int k = reduced_.outerIndexPtr()[rc];
    for (int p = pattern.outerIndexPtr()[col]; p < pattern.outerIndexPtr()[col + 1]; ++p)
      if (reduced_index[pattern.innerIndexPtr()[p]] >= 0) value_map_[k++] = p;
  }
  // The step matrix is structurally symmetric (full stencil blocks): UMFPACK's
  // symmetric strategy with a METIS nested-dissection ordering of A + Aᵀ gives
  // the least fill on these grids (measured on the 17×17 and 65×65 hanging
  // cloth: 9.1M LU entries at 65×65 against 12.2M for the unsymmetric COLAMD
  // strategy and far more for AMD). The analysis waits for the first numeric
  // values (factorize) and is then reused.
  impl_->lu.umfpackControl()(UMFPACK_STRATEGY) = UMFPACK_STRATEGY_SYMMETRIC;
  impl_->lu.umfpackControl()(UMFPACK_ORDERING) = UMFPACK_ORDERING_METIS;
  rb_.resize(m);
  rx_.resize(m);
}

SparseSolver::~SparseSolver() = default;

void SparseSolver::set_refinement_steps(int steps) { impl_->lu.umfpackControl()(UMFPACK_IRSTEP) = steps; }

bool SparseSolver::factorize(const SparseMatrix& a) {
  double* dst = reduced_.valuePtr();
  const double* src = a.valuePtr();
  for (size_t k = 0; k < value_map_.size(); ++k) dst[k] = src[value_map_[k]];
  if (!analyzed_) {
    if (backend_ == Backend::umfpack) impl_->lu.analyzePattern(reduced_);
    else impl_->llt.analyzePattern(reduced_);
    analyzed_ = true;
  }
  if (backend_ == Backend::umfpack) {
    impl_->lu.factorize(reduced_);
    return impl_->lu.info() == Eigen::Success;
  }
  impl_->llt.factorize(reduced_);
  return impl_->llt.info() == Eigen::Success;
}

void SparseSolver::solve(const Vec& b, Vec& x) const {
  for (size_t i = 0; i < free_.size(); ++i) rb_[i] = b[free_[i]];
  if (backend_ == Backend::umfpack) rx_ = impl_->lu.solve(rb_);
  else rx_ = impl_->llt.solve(rb_);
  x.setZero(b.size());
  for (size_t i = 0; i < free_.size(); ++i) x[free_[i]] = rx_[i];
}

}  // namespace wl
