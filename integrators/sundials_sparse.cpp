#include "integrators/sundials_sparse.h"

#include <sunlinsol/sunlinsol_klu.h>
#include <sunmatrix/sunmatrix_sparse.h>

#include <algorithm>
#include <memory>

#include "integrators/sparse_solver.h"

namespace wl::sun {

Matrix make_sparse_matrix(const SparseMatrix& pattern, SUNContext ctx) {
  SUNMatrix m = SUNSparseMatrix(pattern.rows(), pattern.cols(), std::max<long>(1, pattern.nonZeros()), CSC_MAT, ctx);
  if (!m) throw std::runtime_error("SUNSparseMatrix failed");
  Matrix owner(m);
  copy_to(pattern, m);
  return owner;
}

void copy_to(const SparseMatrix& a, SUNMatrix m) {
  sunindextype* ptr = SUNSparseMatrix_IndexPointers(m);
  sunindextype* idx = SUNSparseMatrix_IndexValues(m);
  double* val = SUNSparseMatrix_Data(m);
  const int nc = static_cast<int>(a.cols());
  for (int c = 0; c <= nc; ++c) ptr[c] = a.outerIndexPtr()[c];
  const long nnz = a.nonZeros();
  for (long k = 0; k < nnz; ++k) {
    idx[k] = a.innerIndexPtr()[k];
    val[k] = a.valuePtr()[k];
  }
}

// ---- the custom SUNLinearSolver around SparseSolver -------------------------

namespace {

struct UmfpackContent {
  SparseMatrix a;                        // CSC copy of the SUNMatrix
  std::unique_ptr<SparseSolver> solver;  // symbolic analysis on the first setup
  Vec b, x;
  long last_flag = 0;
};

UmfpackContent& content(SUNLinearSolver s) { return user_data_as<UmfpackContent>(s->content); }

SUNLinearSolver_Type umf_gettype(SUNLinearSolver) { return SUNLINEARSOLVER_DIRECT; }
SUNLinearSolver_ID umf_getid(SUNLinearSolver) { return SUNLINEARSOLVER_CUSTOM; }
int umf_initialize(SUNLinearSolver) { return SUNLS_SUCCESS; }

int umf_setup(SUNLinearSolver s, SUNMatrix m) {
  UmfpackContent& c = content(s);
  const long n = SUNSparseMatrix_Columns(m);
  const sunindextype* ptr = SUNSparseMatrix_IndexPointers(m);
  const sunindextype* idx = SUNSparseMatrix_IndexValues(m);
  const double* val = SUNSparseMatrix_Data(m);
  const long nnz = ptr[n];
  bool same = c.solver && c.a.cols() == n && c.a.nonZeros() == nnz;
  if (same)
    for (long k = 0; k <= n && same; ++k) same = c.a.outerIndexPtr()[k] == ptr[k];
  if (same)
    for (long k = 0; k < nnz && same; ++k) same = c.a.innerIndexPtr()[k] == idx[k];
  if (!same) {  // (re)build the pattern and the symbolic analysis
    c.a.resize(n, n);
    c.a.resizeNonZeros(nnz);
    for (long k = 0; k <= n; ++k) c.a.outerIndexPtr()[k] = static_cast<int>(ptr[k]);
    for (long k = 0; k < nnz; ++k) c.a.innerIndexPtr()[k] = static_cast<int>(idx[k]);
    std::fill(c.a.valuePtr(), c.a.valuePtr() + nnz, 0.0);
    c.solver = std::make_unique<SparseSolver>(c.a, std::span<const int>{});
  }
  std::copy(val, val + nnz, c.a.valuePtr());
  const bool ok = c.solver->factorize(c.a);
  c.last_flag = ok ? SUNLS_SUCCESS : SUNLS_PACKAGE_FAIL_REC;
  return static_cast<int>(c.last_flag);
}

int umf_solve(SUNLinearSolver s, SUNMatrix, N_Vector x, N_Vector b, double) {
  UmfpackContent& c = content(s);
  const long n = N_VGetLength(b);
  c.b = Eigen::Map<const Vec>(data(b), n);
  c.solver->solve(c.b, c.x);
  Eigen::Map<Vec>(data(x), n) = c.x;
  c.last_flag = c.x.allFinite() ? SUNLS_SUCCESS : SUNLS_PACKAGE_FAIL_REC;
  return static_cast<int>(c.last_flag);
}

sunindextype umf_lastflag(SUNLinearSolver s) { return content(s).last_flag; }

int umf_free(SUNLinearSolver s) {
  if (!s) return SUNLS_SUCCESS;
  delete &content(s);
  s->content = nullptr;
  SUNLinSolFreeEmpty(s);
  return SUNLS_SUCCESS;
}

}  // namespace

LinearSolver make_umfpack_solver(SUNContext ctx) {
  SUNLinearSolver s = SUNLinSolNewEmpty(ctx);
  if (!s) throw std::runtime_error("SUNLinSolNewEmpty failed");
  s->content = new UmfpackContent();
  s->ops->gettype = umf_gettype;
  s->ops->getid = umf_getid;
  s->ops->initialize = umf_initialize;
  s->ops->setup = umf_setup;
  s->ops->solve = umf_solve;
  s->ops->lastflag = umf_lastflag;
  s->ops->free = umf_free;
  return LinearSolver(s);
}

IntegratorOptions::SparseBackend resolve(IntegratorOptions::SparseBackend backend) {
  return backend == IntegratorOptions::SparseBackend::umfpack ? IntegratorOptions::SparseBackend::umfpack
                                                              : IntegratorOptions::SparseBackend::klu;
}

LinearSolver make_sparse_solver(IntegratorOptions::SparseBackend backend, N_Vector y, SUNMatrix a, SUNContext ctx) {
  if (resolve(backend) == IntegratorOptions::SparseBackend::klu) {
    SUNLinearSolver s = SUNLinSol_KLU(y, a, ctx);
    if (!s) throw std::runtime_error("SUNLinSol_KLU failed");
    return LinearSolver(s);
  }
  return make_umfpack_solver(ctx);
}

const char* backend_name(IntegratorOptions::SparseBackend backend) {
  return resolve(backend) == IntegratorOptions::SparseBackend::klu ? "klu" : "umfpack";
}

// ---- BlockSystem ------------------------------------------------------------

BlockSystem::BlockSystem(const SparseMatrix& pattern, std::span<const int> fixed)
    : n_(static_cast<int>(pattern.rows())), pinned_(pattern.rows(), 0) {
  for (int i : fixed) pinned_[i] = 1;
  const int n = n_;
  std::vector<Eigen::Triplet<double, int>> trip;
  for (int i = 0; i < n; ++i) {
    trip.emplace_back(i, i, 0.0);
    trip.emplace_back(i, n + i, 0.0);
    trip.emplace_back(n + i, n + i, 0.0);
  }
  for (int c = 0; c < n; ++c)
    for (SparseMatrix::InnerIterator it(pattern, c); it; ++it) {
      trip.emplace_back(n + it.row(), c, 0.0);
      trip.emplace_back(n + it.row(), n + c, 0.0);
    }
  j_.resize(2 * n, 2 * n);
  j_.setFromTriplets(trip.begin(), trip.end());
  j_.makeCompressed();
  auto slot = [&](int r, int c) {
    const int* b = j_.innerIndexPtr() + j_.outerIndexPtr()[c];
    const int* e = j_.innerIndexPtr() + j_.outerIndexPtr()[c + 1];
    return static_cast<int>(std::lower_bound(b, e, r) - j_.innerIndexPtr());
  };
  diag_qq_.resize(n);
  diag_qv_.resize(n);
  diag_vv_.resize(n);
  for (int i = 0; i < n; ++i) {
    diag_qq_[i] = slot(i, i);
    diag_qv_[i] = slot(i, n + i);
    diag_vv_[i] = slot(n + i, n + i);
  }
  const long nnz = pattern.nonZeros();
  slot_vq_.resize(nnz);
  slot_vv_.resize(nnz);
  row_of_.resize(nnz);
  for (int c = 0; c < n; ++c)
    for (int p = pattern.outerIndexPtr()[c]; p < pattern.outerIndexPtr()[c + 1]; ++p) {
      const int r = pattern.innerIndexPtr()[p];
      row_of_[p] = r;
      slot_vq_[p] = slot(n + r, c);
      slot_vv_[p] = slot(n + r, n + c);
    }
}

void BlockSystem::fill(double a_qq, double a_qv, double k, const SparseMatrix* K, double d, const SparseMatrix* D,
                       double m, const SparseMatrix* M, double pinned_diag) {
  double* val = j_.valuePtr();
  std::fill(val, val + j_.nonZeros(), 0.0);
  const double* kv = K ? K->valuePtr() : nullptr;
  const double* dv = D ? D->valuePtr() : nullptr;
  const double* mv = M ? M->valuePtr() : nullptr;
  for (size_t p = 0; p < row_of_.size(); ++p) {
    if (pinned_[row_of_[p]]) continue;
    if (kv) val[slot_vq_[p]] += k * kv[p];
    if (dv) val[slot_vv_[p]] += d * dv[p];
    if (mv) val[slot_vv_[p]] += m * mv[p];
  }
  for (int i = 0; i < n_; ++i) {
    if (pinned_[i]) {
      val[diag_qq_[i]] = pinned_diag;
      val[diag_vv_[i]] = pinned_diag;
    } else {
      val[diag_qq_[i]] += a_qq;
      val[diag_qv_[i]] += a_qv;
    }
  }
}

}  // namespace wl::sun
