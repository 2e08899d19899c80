// The modal solver (integrators/modal_solver.h) against a spectrum known in
// closed form: a string of n masses between two fixed ends, discretized with
// linear elements (stiffness k per element, consistent mass m/6·[2 1; 1 2]).
// Its modes are φ_j(i) = sin(jπi/(n+1)) with
//   ω_j² = 6k/m · (1 − cos θ_j)/(2 + cos θ_j),   θ_j = jπ/(n+1).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "driver/modal_match.h"
#include "integrators/modal_solver.h"

namespace {

using wl::SparseMatrix;

struct StringProblem {
  SparseMatrix k, m;
  std::vector<int> fixed;  // the two ends, DoFs 0 and n + 1
};

// n free masses: DoFs 0 … n + 1 with both ends fixed; element stiffness k, element mass m.
StringProblem string_problem(int n, double k, double m) {
  std::vector<Eigen::Triplet<double>> tk, tm;
  for (int e = 0; e <= n; ++e) {
    const int a = e, b = e + 1;
    for (auto [i, j, sk, sm] : {std::tuple{a, a, k, m / 3}, {b, b, k, m / 3}, {a, b, -k, m / 6}, {b, a, -k, m / 6}}) {
      tk.emplace_back(i, j, sk);
      tm.emplace_back(i, j, sm);
    }
  }
  StringProblem p{SparseMatrix(n + 2, n + 2), SparseMatrix(n + 2, n + 2), {0, n + 1}};
  p.k.setFromTriplets(tk.begin(), tk.end());
  p.m.setFromTriplets(tm.begin(), tm.end());
  return p;
}

double string_eigenvalue(int j, int n, double k, double m) {
  const double c = std::cos(j * std::numbers::pi / (n + 1));
  return 6 * k / m * (1 - c) / (2 + c);
}

TEST(ModalSolver, StringOfMassesHasItsAnalyticSpectrumAndShapes) {
  const int n = 300, count = 12;
  const double k = 250.0, m = 2e-3;
  const StringProblem p = string_problem(n, k, m);
  wl::ModalOptions o;
  o.count = count;
  const wl::ModalResult r = wl::lowest_modes(p.k, p.m, p.fixed, o);
  ASSERT_TRUE(r.ok) << r.message;
  ASSERT_EQ(static_cast<int>(r.eigenvalues.size()), count);
  Eigen::MatrixXd exact(n + 2, count);
  for (int j = 1; j <= count; ++j) {
    EXPECT_NEAR(r.eigenvalues[j - 1] / string_eigenvalue(j, n, k, m), 1.0, 1e-9) << "mode " << j;
    for (int i = 0; i < n + 2; ++i) exact(i, j - 1) = std::sin(j * std::numbers::pi * i / (n + 1));
  }
  // Shapes: zero on the fixed ends, M-normalized, and each parallel to its sine only.
  for (int j = 0; j < count; ++j) {
    EXPECT_EQ(r.shapes(0, j), 0.0);
    EXPECT_EQ(r.shapes(n + 1, j), 0.0);
    EXPECT_NEAR(r.shapes.col(j).dot(p.m * r.shapes.col(j)), 1.0, 1e-10);
  }
  const Eigen::MatrixXd mac = wl::mac_matrix(r.shapes, exact);
  EXPECT_LT((mac - Eigen::MatrixXd::Identity(count, count)).cwiseAbs().maxCoeff(), 1e-9);
}

TEST(ModalSolver, ShiftSelectsTheModesNearestIt) {
  const int n = 100;
  const double k = 1.0, m = 1.0;
  const StringProblem p = string_problem(n, k, m);
  wl::ModalOptions o;
  o.count = 4;
  o.shift = 0.5 * (string_eigenvalue(40, n, k, m) + string_eigenvalue(41, n, k, m));
  const wl::ModalResult r = wl::lowest_modes(p.k, p.m, p.fixed, o);
  ASSERT_TRUE(r.ok) << r.message;
  for (int j = 0; j < 4; ++j) EXPECT_NEAR(r.eigenvalues[j] / string_eigenvalue(39 + j, n, k, m), 1.0, 1e-9);
}

TEST(ModalSolver, TooManyModesIsAMessageNotACrash) {
  const StringProblem p = string_problem(5, 1.0, 1.0);
  wl::ModalOptions o;
  o.count = 5;
  const wl::ModalResult r = wl::lowest_modes(p.k, p.m, p.fixed, o);
  EXPECT_FALSE(r.ok);
  EXPECT_NE(r.message.find("at most 4"), std::string::npos) << r.message;
}

TEST(ModalMatch, MacIsOneForScaledCopiesZeroForOrthogonalShapesAndPairsByLargest) {
  Eigen::MatrixXd a(4, 3);
  a << 1, 0, 1, 0, 1, 1, 0, 0, 0, 0, 0, 1;
  const Eigen::MatrixXd b = -2.5 * a;
  const Eigen::MatrixXd mac = wl::mac_matrix(a, b);
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(mac(i, i), 1.0, 1e-15);
  EXPECT_EQ(mac(0, 1), 0.0);
  EXPECT_NEAR(mac(0, 2), 1.0 / 3.0, 1e-15);  // (1)² / (1 · 3)
  // Columns of b reversed: the pairs follow the shapes, not the order.
  const Eigen::MatrixXd reversed = b.rowwise().reverse();
  const std::vector<wl::ModePair> pairs = wl::match_modes(wl::mac_matrix(a, reversed));
  ASSERT_EQ(pairs.size(), 3u);
  for (int i = 0; i < 3; ++i) {
    EXPECT_EQ(pairs[i].a, i);
    EXPECT_EQ(pairs[i].b, 2 - i);
    EXPECT_NEAR(pairs[i].mac, 1.0, 1e-15);
  }
}

}  // namespace
