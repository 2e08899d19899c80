// ReducedLinearSolver (one n×n solve for the 2n block Newton systems of IDA
// and ARKODE) against a dense LU of the assembled 2n×2n block matrix, for the
// coefficient sets the integrators use, with pinned DoFs carrying nonzero
// right-hand sides, on a damped 3-D spring net (K and D nonsymmetric-in-use,
// pinned corners coupled to free nodes).
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <random>

#include "integrators/reduced_linear_solver.h"
#include "tests/support/test_models.h"

namespace wl {
namespace {

using C = ReducedLinearSolver::Coefficients;

// The block matrix the integrators mean (see reduced_linear_solver.h):
// free rows [α I, −β I ; −k K, m M − d D]; explicit form: v rows
// [−k M_ff⁻¹K, I·m − d M_ff⁻¹ D] (here: multiplied back, see below); pinned rows p I.
Eigen::MatrixXd block_matrix(const C& c, const Eigen::MatrixXd& K, const Eigen::MatrixXd& D, const Eigen::MatrixXd& M,
                             std::span<const int> fixed) {
  const int n = static_cast<int>(K.rows());
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(2 * n, 2 * n);
  A.topLeftCorner(n, n) = c.alpha * Eigen::MatrixXd::Identity(n, n);
  A.topRightCorner(n, n) = -c.beta * Eigen::MatrixXd::Identity(n, n);
  A.bottomLeftCorner(n, n) = -c.k * K;
  A.bottomRightCorner(n, n) = c.m * M - c.d * D;
  for (int i : fixed) {
    A.row(i).setZero();
    A.row(n + i).setZero();
    A(i, i) = A(n + i, n + i) = c.pinned;
  }
  return A;
}

struct Fixture {
  test::SpringNet net{4, 5, 0.05, 0.01, 20.0, 0.3};
  Vec y;
  Evaluation ev;
  Eigen::MatrixXd K, D, M;
  Fixture() {
    const int n = net.num_dofs();
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(-0.01, 0.01);
    y.resize(2 * n);
    y << net.initial_q(), Vec::Zero(n);
    for (int i = 0; i < 2 * n; ++i) y[i] += u(rng);  // off rest: K not just the rest stiffness
    net.evaluate(0.0, y.head(n), y.tail(n), kForce | kDfdq | kDfdv | kMass, ev);
    K = Eigen::MatrixXd(ev.dfdq);
    D = Eigen::MatrixXd(ev.dfdv);
    M = Eigen::MatrixXd(ev.mass);
  }
};

Vec random_rhs(int size, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> g;
  Vec b(size);
  for (int i = 0; i < size; ++i) b[i] = g(rng);
  return b;
}

TEST(ReducedLinearSolver, SolvesTheBlockSystemsOfIdaAndArkode) {
  Fixture f;
  const int n = f.net.num_dofs();
  ASSERT_FALSE(f.net.fixed_dofs().empty());
  const double cj = 2.0e3, gamma = 3.0e-3;
  const std::vector<std::pair<const char*, C>> cases = {
      {"ida", {cj, 1.0, 1.0, cj, 1.0, cj, false}},
      {"arkode block mass", {1.0, gamma, gamma, 1.0, gamma, 1.0, false}},
      {"arkode mass solve", {1.0, 0.0, 0.0, 1.0, 0.0, 1.0, false}},
  };
  for (const auto& [label, c] : cases) {
    SUNContext ctx = nullptr;
    ASSERT_EQ(SUNContext_Create(nullptr, &ctx), 0);
    {
      const C coeff = c;
      ReducedLinearSolver ls(ctx, f.net, 0u, false, SparseSolver::Options{}, [&](double& t, const double*& y, C& out) {
        t = 0.0;
        y = f.y.data();
        out = coeff;
        return true;
      });
      ASSERT_TRUE(ls.setup()) << label;
      const Eigen::MatrixXd A = block_matrix(c, f.K, f.D, f.M, f.net.fixed_dofs());
      const Vec b = random_rhs(2 * n, 3);  // nonzero on pinned rows too
      Vec x(2 * n);
      ASSERT_TRUE(ls.solve(b.data(), x.data())) << label;
      const Vec x_ref = A.partialPivLu().solve(b);
      EXPECT_LT((x - x_ref).norm(), 1e-9 * x_ref.norm()) << label;
      EXPECT_LT((A * x - b).norm(), 1e-9 * b.norm()) << label;
      EXPECT_EQ(ls.setups(), 1);
      EXPECT_EQ(ls.solves(), 1);
    }
    SUNContext_Free(&ctx);
  }
}

// Explicit form y′ = (v, M⁻¹f) (M(q) not given to ARKODE): the Newton matrix
// I − γ [0 I ; M_ff⁻¹K M_ff⁻¹D] on the free rows.
TEST(ReducedLinearSolver, SolvesTheExplicitFormNewtonSystem) {
  Fixture f;
  const int n = f.net.num_dofs();
  const double gamma = 3.0e-3;
  const C c{1.0, gamma, gamma, 1.0, gamma, 1.0, true};
  std::vector<int> free;
  std::vector<char> pinned(n, 0);
  for (int i : f.net.fixed_dofs()) pinned[i] = 1;
  for (int i = 0; i < n; ++i)
    if (!pinned[i]) free.push_back(i);
  Eigen::MatrixXd Mff(free.size(), free.size());
  for (size_t a = 0; a < free.size(); ++a)
    for (size_t b = 0; b < free.size(); ++b) Mff(a, b) = f.M(free[a], free[b]);
  const Eigen::MatrixXd Minv = Mff.inverse();
  Eigen::MatrixXd A = Eigen::MatrixXd::Identity(2 * n, 2 * n);
  for (int i = 0; i < n; ++i)
    if (!pinned[i]) A(i, n + i) = -gamma;
  for (size_t a = 0; a < free.size(); ++a)
    for (int col = 0; col < n; ++col) {
      double jk = 0, jd = 0;
      for (size_t b = 0; b < free.size(); ++b) {
        jk += Minv(a, b) * f.K(free[b], col);
        jd += Minv(a, b) * f.D(free[b], col);
      }
      A(n + free[a], col) -= gamma * jk;
      A(n + free[a], n + col) -= gamma * jd;
    }
  SUNContext ctx = nullptr;
  ASSERT_EQ(SUNContext_Create(nullptr, &ctx), 0);
  {
    ReducedLinearSolver ls(ctx, f.net, 0u, false, SparseSolver::Options{}, [&](double& t, const double*& y, C& out) {
      t = 0.0;
      y = f.y.data();
      out = c;
      return true;
    });
    ASSERT_TRUE(ls.setup());
    const Vec b = random_rhs(2 * n, 5);
    Vec x(2 * n);
    ASSERT_TRUE(ls.solve(b.data(), x.data()));
    const Vec x_ref = A.partialPivLu().solve(b);
    EXPECT_LT((x - x_ref).norm(), 1e-9 * x_ref.norm());
  }
  SUNContext_Free(&ctx);
}

}  // namespace
}  // namespace wl
