// OpenMP threads inside the sparse factorizations (SparseSolverOptions::
// threaded_min_free): CHOLMOD's supernodal loops with their threads give
// bitwise the factor and solution of the same factorization on one thread.
#include <gtest/gtest.h>

#ifdef _OPENMP
#include <omp.h>
#endif

#include <climits>

#include "integrators/sparse_solver.h"

namespace wl {
namespace {

// The 7-point Laplacian on an n³ grid plus a diagonal shift: SPD, with enough
// fill for CHOLMOD's supernodal factorization and its parallel loops.
SparseMatrix laplacian_3d(int n) {
  const int size = n * n * n;
  std::vector<Eigen::Triplet<double>> t;
  auto id = [n](int i, int j, int k) { return i + n * (j + n * k); };
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const int a = id(i, j, k);
        t.emplace_back(a, a, 6.1 + 0.01 * (a % 7));
        if (i + 1 < n) t.emplace_back(a, id(i + 1, j, k), -1.0), t.emplace_back(id(i + 1, j, k), a, -1.0);
        if (j + 1 < n) t.emplace_back(a, id(i, j + 1, k), -1.0), t.emplace_back(id(i, j + 1, k), a, -1.0);
        if (k + 1 < n) t.emplace_back(a, id(i, j, k + 1), -1.0), t.emplace_back(id(i, j, k + 1), a, -1.0);
      }
  SparseMatrix m(size, size);
  m.setFromTriplets(t.begin(), t.end());
  m.makeCompressed();
  return m;
}

TEST(SparseSolverThreads, CholmodWithThreadsIsBitwiseItsSerialRun) {
#ifdef _OPENMP
  if (omp_get_max_threads() < 2) omp_set_num_threads(2);
#endif
  const SparseMatrix a = laplacian_3d(14);
  const std::vector<int> fixed = {0, 5};
  Vec b(a.rows());
  for (Eigen::Index i = 0; i < b.size(); ++i) b[i] = std::sin(0.3 * i) + 0.1;
  Vec x_threads, x_serial;
  for (int min_free : {0, INT_MAX}) {
    SparseSolver solver(a, fixed, {LinearSolverMethod::cholmod, {}, min_free});
    ASSERT_TRUE(solver.factorize(a)) << solver.failure();
    ASSERT_TRUE(solver.solve(b, min_free == 0 ? x_threads : x_serial));
  }
  // A real solve: the residual on the free rows is at round-off.
  Vec r = b - a * x_serial;
  for (int i : fixed) r[i] = 0.0;
  EXPECT_LT(r.norm(), 1e-12 * b.norm());
  EXPECT_EQ(x_threads, x_serial);
}

}  // namespace
}  // namespace wl
