// The step matrix solvers (integrators/sparse_solver.h) against UMFPACK's LU
// on the step matrices of the shipped 17×17 hanging cloth (yarn and FEM), on
// a strongly non-symmetric variant, over consecutive steps (gmres keeping its
// preconditioner), and as whole be-linear trajectories; the amg route
// (hypre's BoomerAMG, optional at build time: those tests skip, saying so,
// where it is not built).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "integrators/amg_preconditioner.h"
#include "integrators/backward_euler.h"
#include "integrators/sparse_solver.h"
#include "models/model_factory.h"
#include "models/scene/scene.h"

namespace wl {
namespace {

Scene hanging_cloth() { return load_scene(std::string(WEAVELAB_SOURCE_DIR) + "/experiments/scenes/hanging_wind.toml"); }

// Steps of be-linear (UMFPACK) from the scene's start; the step matrix of the last one.
struct StepMatrices {
  std::unique_ptr<Model> model;
  std::vector<SparseMatrix> a;
  StepMatrices(const Scene& scene, const std::string& model_name, int steps) : model(make_model(scene, model_name)) {
    BackwardEuler be(BackwardEuler::Variant::linear);
    IntegratorOptions opt;
    opt.dt = scene.dt_s;
    opt.linear_solver = LinearSolverMethod::umfpack;
    be.initialize(*model, 0.0, model->initial_q(), model->initial_v(), opt);
    for (int k = 0; k < steps; ++k) {
      EXPECT_EQ(be.step(opt.dt).outcome, Outcome::ok);
      a.push_back(be.step_matrix());
    }
  }
};

Vec random_rhs(int n, unsigned seed) {
  srand(seed);
  return Vec::Random(n);
}

// ‖b − A x‖ / ‖b‖ on the free rows.
double relative_residual(const SparseMatrix& a, const Vec& x, const Vec& b, std::span<const int> fixed) {
  Vec r = b - a * x;
  Vec bf = b;
  for (int i : fixed) r[i] = bf[i] = 0.0;
  return r.norm() / bf.norm();
}

// Solves with `method` and with UMFPACK; returns ‖x − x_umfpack‖ / ‖x_umfpack‖ and checks the residual.
double distance_to_umfpack(const Model& model, const SparseMatrix& a, LinearSolverMethod method, double residual_tol) {
  const Vec b = random_rhs(model.num_dofs(), 3);
  SparseSolver ref(model.pattern(), model.fixed_dofs());
  SparseSolver s(model.pattern(), model.fixed_dofs(), {method, model.asymmetric_terms()});
  Vec x_ref, x;
  EXPECT_TRUE(ref.factorize(a));
  EXPECT_TRUE(ref.solve(b, x_ref));
  EXPECT_TRUE(s.factorize(a)) << s.failure();
  EXPECT_TRUE(s.solve(b, x)) << s.failure();
  EXPECT_LE(relative_residual(a, x, b, model.fixed_dofs()), residual_tol) << to_string(method);
  for (int i : model.fixed_dofs()) EXPECT_EQ(x[i], 0.0);
  return (x - x_ref).norm() / x_ref.norm();
}

TEST(SparseSolver, YarnStepMatrixEverySolverAgreesWithUmfpack) {
  StepMatrices m(hanging_cloth(), "yarn", 3);
  EXPECT_EQ(m.model->asymmetric_terms(), (std::vector<std::string>{"inertia", "friction", "wind"}));
  EXPECT_LE(distance_to_umfpack(*m.model, m.a.back(), LinearSolverMethod::gmres, kGmresTolerance), 1e-8);
  EXPECT_LE(distance_to_umfpack(*m.model, m.a.back(), LinearSolverMethod::automatic, kGmresTolerance), 1e-8);
}

TEST(SparseSolver, FemStepMatrixEverySolverAgreesWithUmfpack) {
  Scene scene = hanging_cloth();
  StepMatrices with_wind(scene, "fem", 3);
  EXPECT_EQ(with_wind.model->asymmetric_terms(), std::vector<std::string>{"wind"});
  EXPECT_LE(distance_to_umfpack(*with_wind.model, with_wind.a.back(), LinearSolverMethod::gmres, kGmresTolerance),
            1e-8);
  // Without wind every FEM term is a potential's: symmetric, and Cholesky applies.
  scene.terms.wind = false;
  StepMatrices still(scene, "fem", 3);
  ASSERT_TRUE(still.model->asymmetric_terms().empty());
  for (auto method : {LinearSolverMethod::cholmod, LinearSolverMethod::automatic})
    EXPECT_LE(distance_to_umfpack(*still.model, still.a.back(), method, 1e-12), 1e-10) << to_string(method);
}

TEST(SparseSolver, StronglyNonSymmetricMatrixGoesToLuOrConvergedGmres) {
  StepMatrices m(hanging_cloth(), "yarn", 1);
  // A + c (B − Bᵀ) with B the strictly lower part of A: ‖A − Aᵀ‖ / ‖A‖ of order 0.1.
  const SparseMatrix& a = m.a.back();
  SparseMatrix lower = a.triangularView<Eigen::StrictlyLower>();
  SparseMatrix skew = lower - SparseMatrix(lower.transpose());
  SparseMatrix b = a + 0.1 * (a.norm() / skew.norm()) * skew;
  b.makeCompressed();
  ASSERT_EQ(b.nonZeros(), a.nonZeros());
  EXPECT_LE(distance_to_umfpack(*m.model, b, LinearSolverMethod::gmres, kGmresTolerance), 1e-8);
  SparseSolver s(m.model->pattern(), m.model->fixed_dofs(), {LinearSolverMethod::automatic, {"test"}});
  ASSERT_TRUE(s.factorize(b));
  EXPECT_GT(s.statistics().max_asymmetry, 1e-2);
  EXPECT_EQ(s.method(), LinearSolverMethod::umfpack);
}

TEST(SparseSolver, CholmodOnANonSymmetricModelIsRefused) {
  StepMatrices m(hanging_cloth(), "yarn", 1);
  try {
    SparseSolver s(m.model->pattern(), m.model->fixed_dofs(),
                   {LinearSolverMethod::cholmod, m.model->asymmetric_terms()});
    FAIL() << "cholmod accepted a non-symmetric step matrix";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("inertia, friction, wind"), std::string::npos) << e.what();
  }
  EXPECT_THROW(parse_linear_solver("cholesky"), std::invalid_argument);
}

TEST(SparseSolver, GmresKeepsItsPreconditionerOverSteps) {
  StepMatrices m(hanging_cloth(), "yarn", 8);
  SparseSolver s(m.model->pattern(), m.model->fixed_dofs(), {LinearSolverMethod::gmres, m.model->asymmetric_terms()});
  const Vec b = random_rhs(m.model->num_dofs(), 5);
  for (const SparseMatrix& a : m.a) {
    ASSERT_TRUE(s.factorize(a)) << s.failure();
    Vec x;
    ASSERT_TRUE(s.solve(b, x)) << s.failure();
    EXPECT_LE(relative_residual(a, x, b, m.model->fixed_dofs()), kGmresTolerance);
  }
  EXPECT_EQ(s.statistics().updates, 8);
  EXPECT_LT(s.statistics().factorizations, 8);
  EXPECT_GT(s.statistics().krylov_iterations, 8);
}

// A warm start (solve(b, x, true)): from the solution itself GMRES takes no
// iteration and returns it unchanged; from a nearby x fewer than from zero, to
// the same tolerance; without the flag the x given is ignored.
TEST(SparseSolver, GmresWarmStartFromANearbySolutionTakesFewerIterations) {
  StepMatrices m(hanging_cloth(), "yarn", 2);
  const SparseMatrix& a = m.a.back();
  const int n = m.model->num_dofs();
  SparseSolver s(m.model->pattern(), m.model->fixed_dofs(), {LinearSolverMethod::gmres, m.model->asymmetric_terms()});
  const Vec b = random_rhs(n, 7);
  ASSERT_TRUE(s.factorize(a)) << s.failure();
  Vec x;
  ASSERT_TRUE(s.solve(b, x)) << s.failure();
  const long cold = s.statistics().krylov_iterations;
  ASSERT_GT(cold, 1);

  Vec same = x;
  ASSERT_TRUE(s.solve(b, same, true)) << s.failure();
  EXPECT_EQ(s.statistics().krylov_iterations, cold);
  EXPECT_EQ((same - x).norm(), 0.0);

  Vec nearby = x + 1e-6 * x.norm() / std::sqrt(double(n)) * random_rhs(n, 8);
  ASSERT_TRUE(s.solve(b, nearby, true)) << s.failure();
  const long warm = s.statistics().krylov_iterations - cold;
  EXPECT_GE(warm, 1);
  EXPECT_LT(warm, cold);
  EXPECT_LE(relative_residual(a, nearby, b, m.model->fixed_dofs()), kGmresTolerance);

  Vec ignored = Vec::Constant(n, 1e3);
  ASSERT_TRUE(s.solve(b, ignored)) << s.failure();
  EXPECT_EQ((ignored - x).norm(), 0.0);
}

// be-linear trajectories of the yarn cloth with each solver: positions within
// 1e-9 m of UMFPACK's after 30 steps (the cloth is 16 mm wide; one step moves
// it by about 1e-5 m), and a rerun bitwise identical.
Vec trajectory(LinearSolverMethod method) {
  const Scene scene = hanging_cloth();
  auto model = make_model(scene, "yarn");
  BackwardEuler be(BackwardEuler::Variant::linear);
  IntegratorOptions opt;
  opt.dt = scene.dt_s;
  opt.linear_solver = method;
  be.initialize(*model, 0.0, model->initial_q(), model->initial_v(), opt);
  EXPECT_EQ(be.advance_to(30 * opt.dt).outcome, Outcome::ok);
  return be.q();
}

TEST(SparseSolver, TrajectoriesAgreeAndRerunsAreBitwiseIdentical) {
  const Vec ref = trajectory(LinearSolverMethod::umfpack);
  const Vec gmres = trajectory(LinearSolverMethod::gmres);
  EXPECT_LE((gmres - ref).lpNorm<Eigen::Infinity>(), 1e-9);
  EXPECT_GT((gmres - ref).lpNorm<Eigen::Infinity>(), 0.0);  // a different solver indeed ran
  const Vec again = trajectory(LinearSolverMethod::gmres);
  EXPECT_EQ((again - gmres).lpNorm<Eigen::Infinity>(), 0.0);
}

// A matrix that is not positive definite is an outcome factorize() reports (and
// automatic falls back to LU on), not a message: CHOLMOD's printing stays silent
// (at its print level 1 it printed this warning as "CHOLMOD error: ...").
// Dense, so that CHOLMOD chooses its supernodal LLᵀ (a simplicial LDLᵀ would
// factorize it): 0.01 everywhere plus I, with −1 at the last diagonal entry.
TEST(SparseSolver, CholeskyOfAnIndefiniteMatrixReportsItWithoutPrinting) {
  const int n = 300;
  Eigen::MatrixXd dense = Eigen::MatrixXd::Constant(n, n, 0.01) + Eigen::MatrixXd::Identity(n, n);
  dense(n - 1, n - 1) = -1.0;
  const SparseMatrix a = dense.sparseView();
  SparseSolver s(a, {}, {LinearSolverMethod::cholmod, {}});
  testing::internal::CaptureStdout();
  testing::internal::CaptureStderr();
  const bool factorized = s.factorize(a);
  const std::string out = testing::internal::GetCapturedStdout(), err = testing::internal::GetCapturedStderr();
  EXPECT_FALSE(factorized);
  EXPECT_NE(s.failure().find("not positive definite"), std::string::npos) << s.failure();
  EXPECT_EQ(out, "");
  EXPECT_EQ(err, "");
}

constexpr const char* kNoHypre = "weavelab built without hypre (Debian libhypre-dev): the amg route is not built";

TEST(SparseSolver, AmgSolvesTheYarnAndFemStepMatricesLikeUmfpack) {
  if (!amg_available()) GTEST_SKIP() << kNoHypre;
  Scene scene = hanging_cloth();
  StepMatrices yarn(scene, "yarn", 3);
  EXPECT_LE(distance_to_umfpack(*yarn.model, yarn.a.back(), LinearSolverMethod::amg, kGmresTolerance), 1e-8);
  StepMatrices fem(scene, "fem", 3);
  EXPECT_LE(distance_to_umfpack(*fem.model, fem.a.back(), LinearSolverMethod::amg, kGmresTolerance), 1e-8);
  SparseSolver s(yarn.model->pattern(), yarn.model->fixed_dofs(),
                 {LinearSolverMethod::amg, yarn.model->asymmetric_terms()});
  ASSERT_TRUE(s.factorize(yarn.a.back())) << s.failure();
  Vec x;
  ASSERT_TRUE(s.solve(random_rhs(yarn.model->num_dofs(), 4), x)) << s.failure();
  EXPECT_EQ(s.method(), LinearSolverMethod::amg);
  EXPECT_EQ(s.statistics().factorizations, 0);  // no factor: the hierarchy only
  EXPECT_GT(s.statistics().krylov_iterations, 1);
  EXPECT_NE(s.description().find("BoomerAMG"), std::string::npos) << s.description();
}

// The be-linear step with amg is the direct solver's to the Krylov tolerance:
// positions within 1e-9 m of UMFPACK's after 30 steps, as gmres above.
TEST(SparseSolver, AmgTrajectoryAgreesWithUmfpack) {
  if (!amg_available()) GTEST_SKIP() << kNoHypre;
  const Vec ref = trajectory(LinearSolverMethod::umfpack);
  const Vec amg = trajectory(LinearSolverMethod::amg);
  EXPECT_LE((amg - ref).lpNorm<Eigen::Infinity>(), 1e-9);
  EXPECT_GT((amg - ref).lpNorm<Eigen::Infinity>(), 0.0);
}

// The unknown kinds read from the 17×17 yarn cloth's pattern are its DoF
// layout (docs/models.md §2.1): 289 nodes' x, y, z and the 2·15·15 sliding
// coordinates of the interior nodes.
TEST(SparseSolver, AmgUnknownKindsOfTheYarnPatternAreItsDofLayout) {
  auto model = make_model(hanging_cloth(), "yarn");
  const Eigen::SparseMatrix<double, Eigen::ColMajor, std::int64_t> pattern = model->pattern();
  const std::vector<int> kinds = dof_kinds_from_pattern(pattern);
  ASSERT_EQ(kinds.size(), size_t(1317));
  for (int kind : {0, 1, 2}) EXPECT_EQ(std::count(kinds.begin(), kinds.end(), kind), 289) << kind;
  EXPECT_EQ(std::count(kinds.begin(), kinds.end(), 3), 2 * 15 * 15);
}

// auto: amg from kAmgMinFree free DoFs on where hypre is built (else the
// symmetric matrix keeps cholmod), cholmod just below. A shifted 1D Laplacian.
SparseMatrix shifted_laplacian(int n) {
  std::vector<Eigen::Triplet<double>> t;
  for (int i = 0; i < n; ++i) {
    t.emplace_back(i, i, 3.0);
    if (i > 0) t.emplace_back(i, i - 1, -1.0);
    if (i + 1 < n) t.emplace_back(i, i + 1, -1.0);
  }
  SparseMatrix a(n, n);
  a.setFromTriplets(t.begin(), t.end());
  return a;
}

TEST(SparseSolver, AutoPicksAmgFromItsSizeOn) {
  for (int n : {kAmgMinFree - 1, kAmgMinFree}) {
    const SparseMatrix a = shifted_laplacian(n);
    SparseSolver s(a, {}, {LinearSolverMethod::automatic, {}});
    ASSERT_TRUE(s.factorize(a)) << s.failure();
    const bool large = n >= kAmgMinFree;
    EXPECT_EQ(s.method(), large && amg_available() ? LinearSolverMethod::amg : LinearSolverMethod::cholmod) << n;
    Vec x;
    const Vec b = Vec::Ones(n);
    ASSERT_TRUE(s.solve(b, x)) << s.failure();
    EXPECT_LE((b - a * x).norm() / b.norm(), large ? kGmresTolerance : 1e-14) << n;
  }
}

// be-linear on the stockinette with amg: at t = 0.003 s restarted GMRES
// stalls under a fresh V-cycle (its 400 steps end far above the tolerance),
// and the route takes the LU of A for that matrix, as the gmres route
// does when its LLᵀ of S does not serve, instead of ending the run. The
// trajectory stays UMFPACK's to the Krylov tolerance.
TEST(SparseSolver, AmgTakesTheLuWhereItsVCycleStallsOnAKnit) {
  if (!amg_available()) GTEST_SKIP() << kNoHypre;
  const Scene scene = load_scene(std::string(WEAVELAB_SOURCE_DIR) + "/experiments/scenes/knit_stockinette.toml");
  auto model = make_model(scene, "knit");
  auto run = [&](LinearSolverMethod method, long* fallbacks) {
    BackwardEuler be(BackwardEuler::Variant::linear);
    IntegratorOptions opt;
    opt.dt = scene.dt_s;
    opt.linear_solver = method;
    be.initialize(*model, 0.0, model->initial_q(), model->initial_v(), opt);
    EXPECT_EQ(be.advance_to(8 * opt.dt).outcome, Outcome::ok) << to_string(method);
    if (fallbacks) *fallbacks = be.solver().statistics().amg_lu_fallbacks;
    return Vec(be.q());
  };
  long fallbacks = 0;
  const Vec amg = run(LinearSolverMethod::amg, &fallbacks);
  const Vec ref = run(LinearSolverMethod::umfpack, nullptr);
  EXPECT_GE(fallbacks, 1);
  EXPECT_LE((amg - ref).lpNorm<Eigen::Infinity>(), 1e-9);
}

// A pattern holding an entry whose transpose it lacks (and a fixed DoF): the
// row copy GMRES multiplies with keeps its own map from rows to A's entries,
// and the amg route's S its half of the lone entry; both reach their
// tolerance, near UMFPACK's solution.
TEST(SparseSolver, StructurallyNonSymmetricPatternSolves) {
  const int n = 400;
  std::vector<Eigen::Triplet<double>> t;
  for (int i = 0; i < n; ++i) {
    t.emplace_back(i, i, 4.0 + 0.01 * i);
    if (i > 0) t.emplace_back(i, i - 1, -1.0);
    if (i + 1 < n) t.emplace_back(i, i + 1, -1.0);
  }
  t.emplace_back(n - 1, 0, 0.3);  // (0, n − 1) is not in the pattern
  SparseMatrix a(n, n);
  a.setFromTriplets(t.begin(), t.end());
  a.makeCompressed();
  const std::vector<int> fixed = {7};
  const Vec b = random_rhs(n, 11);
  SparseSolver ref(a, fixed);
  Vec x_ref;
  ASSERT_TRUE(ref.factorize(a));
  ASSERT_TRUE(ref.solve(b, x_ref));
  std::vector<LinearSolverMethod> methods = {LinearSolverMethod::gmres};
  if (amg_available()) methods.push_back(LinearSolverMethod::amg);
  for (LinearSolverMethod method : methods) {
    SparseSolver s(a, fixed, {method, {"test"}});
    ASSERT_TRUE(s.factorize(a)) << s.failure();
    Vec x;
    ASSERT_TRUE(s.solve(b, x)) << s.failure();
    EXPECT_LE(relative_residual(a, x, b, fixed), 1.01 * kGmresTolerance) << to_string(method);
    EXPECT_LE((x - x_ref).norm() / x_ref.norm(), 1e-9) << to_string(method);
    EXPECT_GT(s.statistics().krylov_iterations, 0) << to_string(method);
  }
}

TEST(SparseSolver, AmgWithoutHypreIsRefused) {
  if (amg_available()) GTEST_SKIP() << "weavelab built with hypre: amg is available";
  const SparseMatrix a = shifted_laplacian(10);
  try {
    SparseSolver s(a, {}, {LinearSolverMethod::amg, {}});
    FAIL() << "amg accepted without hypre";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("libhypre-dev"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace wl
