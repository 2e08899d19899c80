#include "integrators/sparse_solver.h"

#include <Eigen/CholmodSupport>
#include <Eigen/UmfPackSupport>
#include <algorithm>
#include <cmath>
#include <mutex>
#include <stdexcept>
#include <type_traits>

#include "integrators/amg_preconditioner.h"
#include "integrators/gmres.h"

#ifdef _OPENMP
#include <omp.h>
#endif

namespace wl {
namespace {

static_assert(std::is_same_v<std::int64_t, SuiteSparse_long>, "64-bit SuiteSparse interfaces expected");
using Matrix64 = Eigen::SparseMatrix<double, Eigen::ColMajor, std::int64_t>;

// auto: UMFPACK's LU below this many free DoFs. gmres is faster down to the
// smallest cloth measured (docs/design.md §11: the 9×9 yarn cloth, 341 DoFs,
// 1.1–1.8 against 2.9–3.2 ms CPU per step; the 17×17 continuum, 867 DoFs, 3.1–5.0
// against 4.9–5.5 ms); smaller systems, not measured, keep the direct solve.
constexpr int kSmallSystem = 300;
// auto: gmres for a measured ‖A − Aᵀ‖_F / ‖A‖_F below this.
constexpr double kNearlySymmetric = 1e-3;
// gmres: rebuild the preconditioner after a solve that took more Arnoldi
// steps than this, or once it has served kMaxReuse matrices.
// Measured on the 17×17 yarn cloth (docs/design.md §11): a fresh factor needs
// 4.4 iterations, one a step old about 22; refreshing every step, or after up to
// 5 or 8 matrices, was no faster.
constexpr int kRefactorIterations = 10;
constexpr int kMaxReuse = 3;
constexpr int kGmresRestart = 40;
constexpr int kGmresMaxIterations = 120;
// amg: a V-cycle is a weaker preconditioner than a factor; GMRES may take more
// steps. Rebuild the hierarchy once a solve needs more than this factor times
// the steps of the first solve after the build (or after kMaxReuse matrices).
constexpr int kAmgMaxIterations = 400;
constexpr double kAmgRefreshGrowth = 1.5;

std::string umfpack_status(int status) {
  switch (status) {
    case UMFPACK_WARNING_singular_matrix: return "singular step matrix (UMFPACK: exactly zero pivot)";
    case UMFPACK_ERROR_out_of_memory: return "UMFPACK ran out of memory";
    default: return "UMFPACK status " + std::to_string(status);
  }
}

// The fill-reducing ordering (METIS, inside CHOLMOD and UMFPACK) is made one at
// a time in the process: METIS keeps its random-number state process-wide, and
// with concurrent orderings the clone test's parallel runs differed from the
// serial ones in the last bits in about half of its repeats (none in 30 with
// the lock). Solvers in different threads (one per model clone, docs/design.md
// §3.4) thus stay bitwise reproducible; numeric factorizations still run concurrently.
std::mutex& ordering_mutex() {
  static std::mutex m;
  return m;
}

// While alive, the OpenMP regions the calling thread opens run on that thread
// alone (its max-active-levels ICV at 0; other threads keep theirs). CHOLMOD's
// supernodal loops name their own thread count, so OMP_NUM_THREADS does not
// hold them, and on small matrices waking the team costs more than the loops.
class OneThreadRegions {
 public:
  explicit OneThreadRegions(bool active) {
#ifdef _OPENMP
    if (active) {
      saved_ = omp_get_max_active_levels();
      omp_set_max_active_levels(0);
    }
#endif
  }
  ~OneThreadRegions() {
#ifdef _OPENMP
    if (saved_ >= 0) omp_set_max_active_levels(saved_);
#endif
  }
  OneThreadRegions(const OneThreadRegions&) = delete;
  OneThreadRegions& operator=(const OneThreadRegions&) = delete;

 private:
  int saved_ = -1;
};

// CHOLMOD's LLᵀ whose solves reuse their workspace (cholmod_l_solve2): Eigen's
// solve() allocates and frees the solution in every call, once per GMRES
// iteration here. The same arithmetic as cholmod_l_solve.
class Cholesky : public Eigen::CholmodDecomposition<Matrix64, Eigen::Lower> {
 public:
  // A matrix that is not positive definite is an outcome the caller handles (factorize() reports
  // it, the solver falls back to LU), not a message. CHOLMOD prints nothing at print level 0: at 1
  // its error handler still prints that warning (CHOLMOD_NOT_POSDEF > 0), labelled "CHOLMOD error".
  Cholesky() { cholmod().print = 0; }
  Cholesky(const Cholesky&) = delete;
  Cholesky& operator=(const Cholesky&) = delete;
  ~Cholesky() {
    for (cholmod_dense** d : {&x_, &y_, &e_}) cholmod_l_free_dense(d, &cholmod());
  }
  // Bytes of the factor L (values and indices; 64-bit indices, cholmod_l).
  double factor_bytes() const {
    const cholmod_factor* f = m_cholmodFactor;
    if (!f) return 0.0;
    constexpr double word = sizeof(SuiteSparse_long);
    if (f->is_super) return 8.0 * f->xsize + word * (f->ssize + 3.0 * (f->nsuper + 1) + 2.0 * f->n);
    return (8.0 + word) * f->nzmax + word * (4.0 * f->n + 2.0);
  }
  // x = L⁻ᵀL⁻¹ b (permuted as factorized); b and x of the matrix's size.
  void solve_into(Eigen::Ref<const Vec> b, Eigen::Ref<Vec> x) {
    cholmod_dense bd{};
    bd.nrow = bd.nzmax = bd.d = static_cast<size_t>(b.size());
    bd.ncol = 1;
    bd.x = const_cast<double*>(b.data());
    bd.xtype = CHOLMOD_REAL;
    bd.dtype = CHOLMOD_DOUBLE;
    cholmod_l_solve2(CHOLMOD_A, m_cholmodFactor, &bd, nullptr, &x_, nullptr, &y_, &e_, &cholmod());
    x = Eigen::Map<const Vec>(static_cast<const double*>(x_->x), b.size());
  }

 private:
  cholmod_dense *x_ = nullptr, *y_ = nullptr, *e_ = nullptr;
};

// A by rows (compressed sparse rows, 32-bit indices) for GMRES's products:
// y_i = Σ_k a_ik x_k is one gather and one running sum per entry, where the
// column-major A x scatters into y (a load and a store per entry). On a
// structurally symmetric pattern row i holds column i's indices, and its
// values are A's transposed entries (`transpose`, the solver's map): no map
// of its own is kept.
class RowCopy {
 public:
  RowCopy(const Matrix64& a, const std::vector<int>& transpose) {
    const auto rows = static_cast<size_t>(a.rows());
    values_.resize(a.nonZeros());
    if (std::find(transpose.begin(), transpose.end(), -1) == transpose.end()) {
      auto narrow = [](std::int64_t i) { return static_cast<int>(i); };
      outer_.resize(rows + 1);
      inner_.resize(a.nonZeros());
      std::transform(a.outerIndexPtr(), a.outerIndexPtr() + rows + 1, outer_.begin(), narrow);
      std::transform(a.innerIndexPtr(), a.innerIndexPtr() + a.nonZeros(), inner_.begin(), narrow);
      from_ = &transpose;
      return;
    }
    outer_.assign(rows + 1, 0);
    for (std::int64_t k = 0; k < a.nonZeros(); ++k) ++outer_[a.innerIndexPtr()[k] + 1];
    for (size_t i = 0; i < rows; ++i) outer_[i + 1] += outer_[i];
    inner_.resize(a.nonZeros());
    own_from_.resize(a.nonZeros());
    std::vector<int> next(outer_.begin(), outer_.end() - 1);
    for (std::int64_t col = 0; col < a.cols(); ++col)  // columns in order: each row's come out sorted
      for (std::int64_t k = a.outerIndexPtr()[col]; k < a.outerIndexPtr()[col + 1]; ++k) {
        const int at = next[a.innerIndexPtr()[k]]++;
        inner_[at] = static_cast<int>(col);
        own_from_[at] = static_cast<int>(k);
      }
    from_ = &own_from_;
  }
  RowCopy(const RowCopy&) = delete;
  RowCopy& operator=(const RowCopy&) = delete;
  // Copies A's values (same pattern as at construction).
  void update(const Matrix64& a) {
    const double* v = a.valuePtr();
    const std::vector<int>& from = *from_;
    for (size_t k = 0; k < from.size(); ++k) values_[k] = v[from[k]];
  }
  double bytes() const {
    return 4.0 * outer_.size() + (4.0 + 8.0) * static_cast<double>(values_.size()) + 4.0 * own_from_.size();
  }
  void multiply(Eigen::Ref<const Vec> x, Eigen::Ref<Vec> y) const {
    for (size_t i = 0; i + 1 < outer_.size(); ++i) {
      double s = 0.0;
      for (int k = outer_[i]; k < outer_[i + 1]; ++k) s += values_[k] * x[inner_[k]];
      y[static_cast<Eigen::Index>(i)] = s;
    }
  }

 private:
  std::vector<int> outer_, inner_;
  std::vector<int> own_from_;  // row-order entry -> A's entry, where the pattern is not symmetric
  const std::vector<int>* from_ = nullptr;
  std::vector<double> values_;
};

}  // namespace

std::vector<std::string> linear_solver_names() { return {"auto", "umfpack", "cholmod", "gmres", "amg"}; }

const char* to_string(LinearSolverMethod m) {
  switch (m) {
    case LinearSolverMethod::automatic: return "auto";
    case LinearSolverMethod::umfpack: return "umfpack";
    case LinearSolverMethod::cholmod: return "cholmod";
    case LinearSolverMethod::gmres: return "gmres";
    case LinearSolverMethod::amg: return "amg";
  }
  return "?";
}

LinearSolverMethod parse_linear_solver(const std::string& name) {
  for (auto m : {LinearSolverMethod::automatic, LinearSolverMethod::umfpack, LinearSolverMethod::cholmod,
                 LinearSolverMethod::gmres, LinearSolverMethod::amg})
    if (name == to_string(m)) return m;
  throw std::invalid_argument("unknown linear solver '" + name + "'");
}

struct SparseSolver::Impl {
  Eigen::UmfPackLU<Matrix64> lu;
  Cholesky llt;
  bool lu_analyzed = false, llt_analyzed = false;
  Matrix64 sym;  // S = (A + Aᵀ)/2 on reduced_'s pattern (gmres's factor; amg forms S in hypre's storage)
  std::unique_ptr<Gmres> gmres;
  std::unique_ptr<RowCopy> rows;  // A by rows for GMRES's products, updated by factorize()
  std::unique_ptr<AmgPreconditioner> amg;
  enum class Precond { none, cholesky, lu, amg } precond = Precond::none;
  bool precond_current = false;  // built from the matrix last given to factorize()
  int reuses = 0, last_iterations = 0;
  int fresh_iterations = -1;  // amg: Arnoldi steps of the first solve after the build (−1: none yet)
};

SparseSolver::SparseSolver(const SparseMatrix& pattern, std::span<const int> fixed, Options options)
    : options_(std::move(options)), method_(options_.method), impl_(std::make_unique<Impl>()) {
  if (method_ == LinearSolverMethod::cholmod && !options_.asymmetric_terms.empty()) {
    std::string terms;
    for (const auto& t : options_.asymmetric_terms) terms += (terms.empty() ? "" : ", ") + t;
    throw std::invalid_argument("linear solver 'cholmod' needs a symmetric step matrix; this model's is not (terms: " +
                                terms + "); use auto, umfpack, gmres or amg");
  }
  if (method_ == LinearSolverMethod::amg && !amg_available())
    throw std::invalid_argument(
        "linear solver 'amg' needs hypre, and this weavelab was built without it "
        "(Debian libhypre-dev, then configure again)");
  const Index64 n = pattern.rows();
  std::vector<Index64> reduced_index(n, 0);
  for (int i : fixed) reduced_index[i] = -1;
  for (Index64 i = 0; i < n; ++i)
    if (reduced_index[i] == 0) {
      reduced_index[i] = static_cast<Index64>(free_.size());
      free_.push_back(static_cast<int>(i));
    }
  const Index64 m = static_cast<Index64>(free_.size());
  std::vector<Eigen::Triplet<double, Index64>> trip;
  for (Index64 col = 0; col < n; ++col) {
    const Index64 rc = reduced_index[col];
    if (rc < 0) continue;
    for (SparseMatrix::InnerIterator it(pattern, col); it; ++it) {
      const Index64 rr = reduced_index[it.row()];
      if (rr >= 0) trip.emplace_back(rr, rc, 0.0);
    }
  }
  reduced_.resize(m, m);
  reduced_.setFromTriplets(trip.begin(), trip.end());
  reduced_.makeCompressed();
  trip = {};
  // Map every reduced entry to its position in the full pattern's value array.
  value_map_.resize(reduced_.nonZeros());
  for (Index64 col = 0; col < n; ++col) {
    const Index64 rc = reduced_index[col];
    if (rc < 0) continue;
    Index64 k = reduced_.outerIndexPtr()[rc];
    for (int p = pattern.outerIndexPtr()[col]; p < pattern.outerIndexPtr()[col + 1]; ++p)
      if (reduced_index[pattern.innerIndexPtr()[p]] >= 0) value_map_[k++] = p;
  }
  // And to its transposed entry (−1 where the pattern lacks it), for ‖A − Aᵀ‖ and S.
  const Index64* outer = reduced_.outerIndexPtr();
  const Index64* inner = reduced_.innerIndexPtr();
  transpose_map_.resize(reduced_.nonZeros());
  for (Index64 col = 0; col < m; ++col)
    for (Index64 k = outer[col]; k < outer[col + 1]; ++k) {
      const Index64 row = inner[k];
      const Index64* hit = std::lower_bound(inner + outer[row], inner + outer[row + 1], col);
      transpose_map_[k] = hit != inner + outer[row + 1] && *hit == col ? static_cast<int>(hit - inner) : -1;
    }
  // The step matrix is structurally symmetric (full stencil blocks): UMFPACK's
  // symmetric strategy with a METIS nested-dissection ordering of A + Aᵀ gives
  // the least fill on these grids (measured on the 17×17 and 65×65 hanging
  // cloth: 9.1M LU entries at 65×65 against 12.2M for the unsymmetric COLAMD
  // strategy and far more for AMD).
  impl_->lu.umfpackControl()(UMFPACK_STRATEGY) = UMFPACK_STRATEGY_SYMMETRIC;
  impl_->lu.umfpackControl()(UMFPACK_ORDERING) = UMFPACK_ORDERING_METIS;
  // CHOLMOD: METIS ordering only (its default tries AMD first), supernodal or
  // simplicial by CHOLMOD's flop-count rule.
  impl_->llt.setMode(Eigen::CholmodAuto);
  impl_->llt.cholmod().nmethods = 1;
  impl_->llt.cholmod().method[0].ordering = CHOLMOD_METIS;
  impl_->llt.cholmod().postorder = 1;
  rb_.resize(m);
  rx_.resize(m);
}

SparseSolver::~SparseSolver() = default;

void SparseSolver::restart() {
  method_ = options_.method;
  stats_ = {};
  failure_.clear();
  impl_->lu_analyzed = false;
  impl_->precond = Impl::Precond::none;
  impl_->precond_current = false;
  impl_->reuses = impl_->last_iterations = 0;
  impl_->fresh_iterations = -1;
}

void SparseSolver::set_refinement_steps(int steps) { impl_->lu.umfpackControl()(UMFPACK_IRSTEP) = steps; }

std::string SparseSolver::description() const {
  switch (method_) {
    case LinearSolverMethod::umfpack: return "umfpack (LU, symmetric strategy, METIS)";
    case LinearSolverMethod::cholmod: return "cholmod (LLT, METIS)";
    case LinearSolverMethod::gmres:
      return "gmres (restart " + std::to_string(kGmresRestart) + ", relative residual 1e-10, preconditioner: " +
             (impl_->precond == Impl::Precond::lu ? "umfpack LU of A" : "cholmod LLT of (A + A^T)/2") +
             ", refreshed after " + std::to_string(kRefactorIterations) + " iterations or " +
             std::to_string(kMaxReuse) + " matrices)";
    case LinearSolverMethod::amg:
      return "amg (gmres restart " + std::to_string(kGmresRestart) +
             ", relative residual 1e-10, preconditioner: BoomerAMG V-cycle of (A + A^T)/2, " +
             std::to_string(impl_->amg ? impl_->amg->num_kinds() : 1) + " unknown kinds" +
             (stats_.amg_lu_fallbacks > 0 ? "; umfpack LU of A after " + std::to_string(stats_.amg_lu_fallbacks) +
                                                " fresh V-cycles that did not serve"
                                          : std::string()) +
             ")";
    case LinearSolverMethod::automatic: break;
  }
  return "auto (no matrix yet)";
}

void SparseSolver::choose_method() {
  if (method_ != LinearSolverMethod::automatic) return;
  const bool nearly_symmetric = options_.asymmetric_terms.empty() || stats_.max_asymmetry < kNearlySymmetric;
  if (amg_available() && num_free() >= kAmgMinFree && nearly_symmetric) method_ = LinearSolverMethod::amg;
  else if (options_.asymmetric_terms.empty()) method_ = LinearSolverMethod::cholmod;
  else if (num_free() < kSmallSystem || stats_.max_asymmetry >= kNearlySymmetric) method_ = LinearSolverMethod::umfpack;
  else method_ = LinearSolverMethod::gmres;
}

SparseSolver::Memory SparseSolver::memory() const {
  auto sparse_bytes = [](const Matrix64& m) {
    return (8.0 + 8.0) * static_cast<double>(m.nonZeros()) + 8.0 * (m.outerSize() + 1.0);
  };
  Memory mem;
  mem.matrices = sparse_bytes(reduced_) + sparse_bytes(impl_->sym) + 4.0 * (value_map_.size() + transpose_map_.size()) +
                 4.0 * free_.size() + (impl_->rows ? impl_->rows->bytes() : 0.0);
  if (impl_->amg) {
    const AmgPreconditioner::Statistics& a = impl_->amg->statistics();
    mem.preconditioner = (8.0 + 4.0) * static_cast<double>(a.hierarchy_nonzeros);
  } else if (impl_->llt_analyzed) {
    mem.preconditioner = impl_->llt.factor_bytes();
  }
  if (impl_->gmres) mem.krylov = 8.0 * num_free() * (2.0 * kGmresRestart + 3.0);
  return mem;
}

bool SparseSolver::factor_lu() const {
  if (!impl_->lu_analyzed) {
    std::lock_guard<std::mutex> one_ordering_at_a_time(ordering_mutex());
    impl_->lu.analyzePattern(reduced_);
    impl_->lu_analyzed = true;
  }
  impl_->lu.factorize(reduced_);
  ++stats_.factorizations;
  if (impl_->lu.info() == Eigen::Success) return true;
  failure_ = umfpack_status(impl_->lu.umfpackFactorizeReturncode());
  return false;
}

// LLᵀ of A (symmetric_part = false) or of S = (A + Aᵀ)/2.
bool SparseSolver::factor_cholesky(bool symmetric_part) const {
  const Matrix64* a = &reduced_;
  if (symmetric_part) {
    update_symmetric_part();
    a = &impl_->sym;
  }
  const int threaded_min = options_.threaded_min_free >= 0 ? options_.threaded_min_free : kThreadedMinFree;
  const OneThreadRegions serial(num_free() < threaded_min);
  if (!impl_->llt_analyzed) {
    std::lock_guard<std::mutex> one_ordering_at_a_time(ordering_mutex());
    impl_->llt.analyzePattern(*a);
    impl_->llt_analyzed = true;
  }
  impl_->llt.factorize(*a);
  ++stats_.factorizations;
  if (impl_->llt.info() == Eigen::Success) return true;
  failure_ = "step matrix not positive definite (CHOLMOD)";
  return false;
}

void SparseSolver::update_symmetric_part() const {
  Matrix64& s = impl_->sym;
  if (s.nonZeros() != reduced_.nonZeros()) s = reduced_;
  const double* av = reduced_.valuePtr();
  double* sv = s.valuePtr();
  for (size_t k = 0; k < transpose_map_.size(); ++k)
    sv[k] = 0.5 * (av[k] + (transpose_map_[k] >= 0 ? av[transpose_map_[k]] : 0.0));
}

bool SparseSolver::factor_amg() const {
  if (!impl_->amg) impl_->amg = std::make_unique<AmgPreconditioner>(dof_kinds_from_pattern(reduced_));
  impl_->fresh_iterations = -1;
  return impl_->amg->setup(reduced_, transpose_map_, failure_);
}

bool SparseSolver::factor_preconditioner() const {
  using P = Impl::Precond;
  if (method_ == LinearSolverMethod::amg) impl_->precond = factor_amg() ? P::amg : P::none;
  else impl_->precond = factor_cholesky(true) ? P::cholesky : factor_lu() ? P::lu : P::none;
  impl_->precond_current = true;
  impl_->reuses = 0;
  return impl_->precond != P::none;
}

bool SparseSolver::factorize(const SparseMatrix& a) {
  double* dst = reduced_.valuePtr();
  const double* src = a.valuePtr();
  for (size_t k = 0; k < value_map_.size(); ++k) dst[k] = src[value_map_[k]];
  ++stats_.updates;
  failure_.clear();
  if (!reduced_.coeffs().allFinite()) {
    failure_ = "non-finite entries in the step matrix";
    return false;
  }
  if (options_.method != LinearSolverMethod::cholmod) {  // ‖A − Aᵀ‖_F / ‖A‖_F
    double num = 0.0, den = 0.0;
    for (size_t k = 0; k < transpose_map_.size(); ++k) {
      const double d = dst[k] - (transpose_map_[k] >= 0 ? dst[transpose_map_[k]] : 0.0);
      num += d * d;
      den += dst[k] * dst[k];
    }
    // Each asymmetric pair is counted twice in num: ‖A − Aᵀ‖²_F.
    stats_.max_asymmetry = std::max(stats_.max_asymmetry, den > 0.0 ? std::sqrt(num / den) : 0.0);
  }
  choose_method();
  switch (method_) {
    case LinearSolverMethod::umfpack: return factor_lu();
    case LinearSolverMethod::cholmod:
      if (factor_cholesky(false)) return true;
      // auto on a symmetric but indefinite matrix: the LU serves.
      if (options_.method != LinearSolverMethod::automatic) return false;
      method_ = LinearSolverMethod::umfpack;
      return factor_lu();
    case LinearSolverMethod::gmres:
    case LinearSolverMethod::amg: {
      if (!impl_->gmres) impl_->gmres = std::make_unique<Gmres>(num_free(), kGmresRestart);
      if (!impl_->rows) impl_->rows = std::make_unique<RowCopy>(reduced_, transpose_map_);
      impl_->rows->update(reduced_);
      impl_->precond_current = false;
      ++impl_->reuses;
      const bool grown = impl_->precond == Impl::Precond::amg
                             ? impl_->last_iterations > kAmgRefreshGrowth * impl_->fresh_iterations
                             : impl_->last_iterations > kRefactorIterations;
      const bool stale = impl_->precond == Impl::Precond::none || grown || impl_->reuses > kMaxReuse;
      return !stale || factor_preconditioner();
    }
    case LinearSolverMethod::automatic: break;
  }
  return false;
}

bool SparseSolver::gmres_solve(const Vec& rb, Vec& rx, bool from_x) const {
  auto apply_a = [this](Eigen::Ref<const Vec> in, Eigen::Ref<Vec> out) { impl_->rows->multiply(in, out); };
  auto apply_p = [this](Eigen::Ref<const Vec> in, Eigen::Ref<Vec> out) {
    if (impl_->precond == Impl::Precond::cholesky) impl_->llt.solve_into(in, out);
    else if (impl_->precond == Impl::Precond::amg) impl_->amg->apply(in, out);
    else out = impl_->lu.solve(in);
  };
  const int max_iterations = method_ == LinearSolverMethod::amg ? kAmgMaxIterations : kGmresMaxIterations;
  for (int attempt = 0; attempt < 3; ++attempt) {
    if (attempt > 0 || !from_x) rx.setZero();
    const Gmres::Result r = impl_->gmres->solve(apply_a, apply_p, rb, rx, kGmresTolerance, max_iterations);
    stats_.krylov_iterations += r.iterations;
    impl_->last_iterations = r.iterations;
    if (impl_->fresh_iterations < 0) impl_->fresh_iterations = r.iterations;
    if (r.converged) return true;
    failure_ = "GMRES reached a relative residual of " + std::to_string(r.relative_residual) + " after " +
               std::to_string(r.iterations) + " iterations";
    // A kept preconditioner may have drifted too far: retry with a fresh one.
    // A fresh LLᵀ or V-cycle of S that does not serve (A far from symmetric;
    // restarted GMRES stalling under the V-cycle, as on a knit): with the LU of A.
    if (!impl_->precond_current) {
      if (!factor_preconditioner()) return false;
    } else if (impl_->precond != Impl::Precond::lu && factor_lu()) {
      if (impl_->precond == Impl::Precond::amg) ++stats_.amg_lu_fallbacks;
      impl_->precond = Impl::Precond::lu;
    } else {
      return false;
    }
  }
  return false;
}

bool SparseSolver::solve(const Vec& b, Vec& x, bool from_x) const {
  for (size_t i = 0; i < free_.size(); ++i) rb_[i] = b[free_[i]];
  from_x = from_x && x.size() == b.size() && x.allFinite();
  if (from_x)
    for (size_t i = 0; i < free_.size(); ++i) rx_[i] = x[free_[i]];
  bool ok = true;
  if (method_ == LinearSolverMethod::gmres || method_ == LinearSolverMethod::amg) ok = gmres_solve(rb_, rx_, from_x);
  else if (method_ == LinearSolverMethod::cholmod) impl_->llt.solve_into(rb_, rx_);
  else rx_ = impl_->lu.solve(rb_);
  ++stats_.solves;
  x.setZero(b.size());
  for (size_t i = 0; i < free_.size(); ++i) x[free_[i]] = rx_[i];
  return ok;
}

}  // namespace wl
