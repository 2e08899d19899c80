#include "integrators/amg_preconditioner.h"

#include <algorithm>
#include <cstdlib>
#include <mutex>
#include <stdexcept>

#ifdef WEAVELAB_HAVE_HYPRE
#include <HYPRE.h>
#include <HYPRE_IJ_mv.h>
#include <HYPRE_parcsr_ls.h>
#include <_hypre_parcsr_ls.h>
#include <mpi.h>
#endif

namespace wl {

std::vector<int> dof_kinds_from_pattern(const Eigen::SparseMatrix<double, Eigen::ColMajor, std::int64_t>& a) {
  const std::int64_t n = a.cols();
  const std::int64_t* outer = a.outerIndexPtr();
  const std::int64_t* inner = a.innerIndexPtr();
  auto same_pattern = [&](std::int64_t c, std::int64_t d) {
    return outer[c + 1] - outer[c] == outer[d + 1] - outer[d] &&
           std::equal(inner + outer[c], inner + outer[c + 1], inner + outer[d]);
  };
  std::vector<int> kinds(static_cast<size_t>(n), 3);
  for (std::int64_t c = 0; c + 2 < n;) {
    if (same_pattern(c, c + 1) && same_pattern(c, c + 2)) {
      for (int k = 0; k < 3; ++k) kinds[static_cast<size_t>(c + k)] = k;
      c += 3;
    } else {
      ++c;
    }
  }
  return kinds;
}

#ifdef WEAVELAB_HAVE_HYPRE

bool amg_available() { return true; }

namespace {

// BoomerAMG settings: HMIS coarsening with extended+i interpolation (at most
// 4 entries per row), the pair hypre recommends for 3D-like problems; one
// sweep of hybrid l1 symmetric Gauss–Seidel down and up; one V-cycle from zero.
// Strength threshold 0.5 (hypre's advice for 3D; its 0.25 default is for 2D
// Laplacians).
constexpr int kCoarsenHmis = 10;
constexpr int kInterpExtPlusI = 6;
constexpr int kInterpMaxElements = 4;
constexpr int kRelaxL1SymmetricGs = 8;
constexpr double kStrongThreshold = 0.5;

std::mutex& hypre_mutex() {
  static std::mutex m;
  return m;
}

void finalize_hypre_and_mpi() {
  HYPRE_Finalize();
  int finalized = 0;
  MPI_Finalized(&finalized);
  if (!finalized) MPI_Finalize();
}

// MPI (when nobody initialized it) and hypre, once per process.
void initialize_hypre() {
  static std::once_flag once;
  std::call_once(once, [] {
    int initialized = 0;
    MPI_Initialized(&initialized);
    if (!initialized) {
      int provided = 0;
      MPI_Init_thread(nullptr, nullptr, MPI_THREAD_SERIALIZED, &provided);
    }
    HYPRE_Init();
    // Finalized at exit only where this process initialized MPI here.
    if (!initialized) std::atexit(finalize_hypre_and_mpi);
  });
}

double* vector_data(HYPRE_ParVector v) {
  return hypre_VectorData(hypre_ParVectorLocalVector(reinterpret_cast<hypre_ParVector*>(v)));
}

}  // namespace

struct AmgPreconditioner::Impl {
  HYPRE_IJMatrix ij = nullptr;
  HYPRE_ParCSRMatrix parcsr = nullptr;
  HYPRE_IJVector ij_b = nullptr, ij_x = nullptr;
  HYPRE_ParVector b = nullptr, x = nullptr;
  HYPRE_Solver amg = nullptr;
  int n = 0;

  void destroy_matrix() {
    if (amg) HYPRE_BoomerAMGDestroy(amg);
    if (ij) HYPRE_IJMatrixDestroy(ij);
    amg = nullptr;
    ij = nullptr;
    parcsr = nullptr;
  }
  void destroy_vectors() {
    if (ij_b) HYPRE_IJVectorDestroy(ij_b);
    if (ij_x) HYPRE_IJVectorDestroy(ij_x);
    ij_b = ij_x = nullptr;
    b = x = nullptr;
  }
  void make_vectors(int size) {
    destroy_vectors();
    n = size;
    for (auto [ij_v, par] : {std::pair{&ij_b, &b}, std::pair{&ij_x, &x}}) {
      HYPRE_IJVectorCreate(MPI_COMM_SELF, 0, size - 1, ij_v);
      HYPRE_IJVectorSetObjectType(*ij_v, HYPRE_PARCSR);
      HYPRE_IJVectorInitialize(*ij_v);
      HYPRE_IJVectorAssemble(*ij_v);
      void* object = nullptr;
      HYPRE_IJVectorGetObject(*ij_v, &object);
      *par = static_cast<HYPRE_ParVector>(object);
    }
  }
};

AmgPreconditioner::AmgPreconditioner(std::vector<int> kinds)
    : impl_(std::make_unique<Impl>()), kinds_(std::move(kinds)) {
  initialize_hypre();
  num_kinds_ = kinds_.empty() ? 1 : *std::max_element(kinds_.begin(), kinds_.end()) + 1;
}

AmgPreconditioner::~AmgPreconditioner() {
  std::lock_guard<std::mutex> one_at_a_time(hypre_mutex());
  impl_->destroy_matrix();
  impl_->destroy_vectors();
}

bool AmgPreconditioner::setup(const Matrix64& a, std::span<const int> transpose, std::string& failure) {
  std::lock_guard<std::mutex> one_at_a_time(hypre_mutex());
  const int n = static_cast<int>(a.rows());
  if (impl_->n != n) impl_->make_vectors(n);
  impl_->destroy_matrix();
  HYPRE_IJMatrixCreate(MPI_COMM_SELF, 0, n - 1, 0, n - 1, &impl_->ij);
  HYPRE_IJMatrixSetObjectType(impl_->ij, HYPRE_PARCSR);
  // S is symmetric: its column j, stored contiguously, is its row j. It is
  // handed to hypre a block of rows at a time, so only hypre holds all of it.
  const std::int64_t* outer = a.outerIndexPtr();
  const std::int64_t* inner = a.innerIndexPtr();
  const double* av = a.valuePtr();
  std::vector<HYPRE_Int> row_sizes(n), rows(n);
  for (int j = 0; j < n; ++j) {
    rows[j] = j;
    row_sizes[j] = static_cast<HYPRE_Int>(outer[j + 1] - outer[j]);
  }
  HYPRE_IJMatrixSetRowSizes(impl_->ij, row_sizes.data());
  HYPRE_IJMatrixInitialize(impl_->ij);
  constexpr std::int64_t kBlockEntries = 1 << 20;
  std::vector<HYPRE_Int> cols;
  std::vector<double> values;
  for (int j0 = 0; j0 < n;) {
    int j1 = j0 + 1;
    while (j1 < n && outer[j1 + 1] - outer[j0] <= kBlockEntries) ++j1;
    const std::int64_t begin = outer[j0], count = outer[j1] - begin;
    cols.resize(static_cast<size_t>(count));
    values.resize(static_cast<size_t>(count));
    for (std::int64_t k = begin; k < begin + count; ++k) {
      const int t = transpose[static_cast<size_t>(k)];
      cols[static_cast<size_t>(k - begin)] = static_cast<HYPRE_Int>(inner[k]);
      values[static_cast<size_t>(k - begin)] = 0.5 * (av[k] + (t >= 0 ? av[t] : 0.0));
    }
    HYPRE_IJMatrixSetValues(impl_->ij, j1 - j0, row_sizes.data() + j0, rows.data() + j0, cols.data(), values.data());
    j0 = j1;
  }
  HYPRE_IJMatrixAssemble(impl_->ij);
  void* object = nullptr;
  HYPRE_IJMatrixGetObject(impl_->ij, &object);
  impl_->parcsr = static_cast<HYPRE_ParCSRMatrix>(object);

  HYPRE_BoomerAMGCreate(&impl_->amg);
  HYPRE_Solver amg = impl_->amg;
  HYPRE_BoomerAMGSetPrintLevel(amg, 0);
  HYPRE_BoomerAMGSetMaxIter(amg, 1);
  HYPRE_BoomerAMGSetTol(amg, 0.0);
  HYPRE_BoomerAMGSetCoarsenType(amg, kCoarsenHmis);
  HYPRE_BoomerAMGSetInterpType(amg, kInterpExtPlusI);
  HYPRE_BoomerAMGSetPMaxElmts(amg, kInterpMaxElements);
  HYPRE_BoomerAMGSetRelaxType(amg, kRelaxL1SymmetricGs);
  HYPRE_BoomerAMGSetNumSweeps(amg, 1);
  HYPRE_BoomerAMGSetStrongThreshold(amg, kStrongThreshold);
  if (num_kinds_ > 1 && static_cast<int>(kinds_.size()) == n) {
    HYPRE_BoomerAMGSetNumFunctions(amg, num_kinds_);
    // hypre takes the array and frees it with the solver (host memory: free()).
    auto* dof_func = static_cast<HYPRE_Int*>(std::calloc(static_cast<size_t>(n), sizeof(HYPRE_Int)));
    std::copy(kinds_.begin(), kinds_.end(), dof_func);
    HYPRE_BoomerAMGSetDofFunc(amg, dof_func);
  }
  HYPRE_ClearAllErrors();
  HYPRE_BoomerAMGSetup(amg, impl_->parcsr, impl_->b, impl_->x);
  ++stats_.setups;
  if (HYPRE_GetError() != 0) {
    char message[256] = {};
    HYPRE_DescribeError(HYPRE_GetError(), message);
    failure = std::string("BoomerAMG setup failed: ") + message;
    HYPRE_ClearAllErrors();
    return false;
  }
  // The hierarchy's size from hypre's own data (serial: the off-diagonal parts are empty).
  auto* data = reinterpret_cast<hypre_ParAMGData*>(amg);
  stats_.levels = hypre_ParAMGDataNumLevels(data);
  stats_.hierarchy_nonzeros = 0;
  for (int l = 0; l < stats_.levels; ++l) {
    stats_.hierarchy_nonzeros += hypre_CSRMatrixNumNonzeros(hypre_ParCSRMatrixDiag(hypre_ParAMGDataAArray(data)[l]));
    if (l + 1 < stats_.levels)
      stats_.hierarchy_nonzeros += hypre_CSRMatrixNumNonzeros(hypre_ParCSRMatrixDiag(hypre_ParAMGDataPArray(data)[l]));
  }
  return true;
}

void AmgPreconditioner::apply(Eigen::Ref<const Vec> in, Eigen::Ref<Vec> out) {
  std::lock_guard<std::mutex> one_at_a_time(hypre_mutex());
  Eigen::Map<Vec>(vector_data(impl_->b), impl_->n) = in;
  Eigen::Map<Vec>(vector_data(impl_->x), impl_->n).setZero();
  HYPRE_BoomerAMGSolve(impl_->amg, impl_->parcsr, impl_->b, impl_->x);
  out = Eigen::Map<const Vec>(vector_data(impl_->x), impl_->n);
}

#else  // built without hypre

bool amg_available() { return false; }

struct AmgPreconditioner::Impl {};

AmgPreconditioner::AmgPreconditioner(std::vector<int> kinds) : kinds_(std::move(kinds)) {
  throw std::runtime_error("linear solver 'amg' needs hypre: weavelab was built without it (Debian libhypre-dev)");
}
AmgPreconditioner::~AmgPreconditioner() = default;
bool AmgPreconditioner::setup(const Matrix64&, std::span<const int>, std::string& failure) {
  failure = "built without hypre";
  return false;
}
void AmgPreconditioner::apply(Eigen::Ref<const Vec>, Eigen::Ref<Vec>) {}

#endif

}  // namespace wl
