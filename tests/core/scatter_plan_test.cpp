// The assembly's scatter plans (models/core/assembly.h: per element its
// columns' starts and its rows' places in them) put every element's n×n
// block on its (row, column) entries: ∂f/∂q, ∂f/∂v and M of the hanging
// cloth (yarn and FEM) equal the dense sum of the elements' blocks formed
// here from the terms themselves, and a term with constants in its stencils
// leaves their rows and columns out. An evaluation holds only the matrices
// it is asked for (be-linear's one-pass step none beside A).
#include <gtest/gtest.h>

#include <array>

#include "models/core/assembly.h"
#include "tests/support/advanced_model.h"
#include "tests/support/test_models.h"

namespace wl {
namespace {

using Dense = Eigen::MatrixXd;

struct DenseSum {
  Dense dfdq, dfdv, mass;
  explicit DenseSum(int n) : dfdq(Dense::Zero(n, n)), dfdv(Dense::Zero(n, n)), mass(Dense::Zero(n, n)) {}
};

// Adds element e's blocks of `term` (local state ql, vl) at its stencil's DoFs.
void add_element(const Term& term, int e, const double* ql, const double* vl, DenseSum& sum) {
  const int n = term.stencil_size();
  std::vector<double> f(n, 0.0), k(n * n, 0.0), d(n * n, 0.0), m(n * n, 0.0);
  term.evaluate(e, ql, vl,
                ElementOutput{f.data(), k.data(), term.has_velocity_jacobian() ? d.data() : nullptr,
                              term.provides_mass() ? m.data() : nullptr});
  const auto s = term.stencil(e);
  for (int b = 0; b < n; ++b)
    for (int a = 0; a < n; ++a) {
      if (!is_dof(s[a]) || !is_dof(s[b])) continue;
      sum.dfdq(s[a], s[b]) += k[a + n * b];
      sum.dfdv(s[a], s[b]) += d[a + n * b];
      sum.mass(s[a], s[b]) += m[a + n * b];
    }
}

// Largest |assembled − reference| over the largest |reference|; the two sum
// the same blocks in different orders, so they agree to round-off.
double relative_distance(const SparseMatrix& assembled, const Dense& reference) {
  return (Dense(assembled) - reference).cwiseAbs().maxCoeff() / reference.cwiseAbs().maxCoeff();
}

void check_model(const std::string& model_name) {
  SCOPED_TRACE(model_name);
  Vec q, v;
  auto model = test::advanced_model(model_name, "", q, v);
  auto& terms = dynamic_cast<TermModel&>(*model);
  Evaluation ev;
  model->evaluate(0.02, q, v, kForce | kDfdq | kDfdv | kMass, ev);  // also prepares every term at (q, v)
  const int n = model->num_dofs();
  DenseSum sum(n);
  for (const auto& term : terms.terms()) {
    const int ns = term->stencil_size();
    std::vector<double> ql(ns), vl(ns);
    for (int e = 0; e < term->num_elements(); ++e) {
      terms.gather_local(*term, e, q, v, ql.data(), vl.data());
      add_element(*term, e, ql.data(), vl.data(), sum);
    }
  }
  EXPECT_LE(relative_distance(ev.dfdq, sum.dfdq), 1e-13);
  EXPECT_LE(relative_distance(ev.dfdv, sum.dfdv), 1e-13);
  EXPECT_LE(relative_distance(ev.mass, sum.mass), 1e-13);
  // Every matrix is there to be checked: not zero.
  EXPECT_GT(sum.dfdq.cwiseAbs().maxCoeff(), 0.0);
  EXPECT_GT(sum.dfdv.cwiseAbs().maxCoeff(), 0.0);
  EXPECT_GT(sum.mass.cwiseAbs().maxCoeff(), 0.0);
}

TEST(ScatterPlan, YarnBlocksLandOnTheirEntries) { check_model("yarn"); }

TEST(ScatterPlan, FemBlocksLandOnTheirEntries) { check_model("fem"); }

TEST(ScatterPlan, ConstantsRowsAndColumnsAreLeftOut) {
  // Springs 0–1, 1–2, 2–c0 and c1–0 (c: constants at 3.5 and −1.25), k = 2, rest 1.
  const std::vector<std::array<int, 2>> stencils = {{0, 1}, {1, 2}, {2, ~0}, {~1, 0}};
  auto springs = test::make_linear_spring_1d(stencils, 2.0, 1.0);
  Assembly assembly(3, {springs.get()});
  Vec q(3), v = Vec::Zero(3), constants(2);
  q << 0.1, 1.3, 2.2;
  constants << 3.5, -1.25;
  Vec f = Vec::Zero(3);
  SparseMatrix dfdq = assembly.pattern();
  AssemblyRequest request;
  request.dfdq = true;
  assembly.add_stage(0, q, v, constants, request, f, &dfdq, nullptr, nullptr);
  DenseSum sum(3);
  for (int e = 0; e < springs->num_elements(); ++e) {
    double ql[2], vl[2] = {0.0, 0.0};
    const auto s = springs->stencil(e);
    for (int a = 0; a < 2; ++a) ql[a] = is_dof(s[a]) ? q[s[a]] : constants[constant_slot(s[a])];
    add_element(*springs, e, ql, vl, sum);
  }
  EXPECT_EQ(Dense(dfdq), sum.dfdq);  // at most two blocks per entry: the same sums
  // A linear spring's ∂f/∂q by hand: −k on the diagonal per spring at a DoF, +k between two DoFs.
  Dense by_hand(3, 3);
  by_hand << -4.0, 2.0, 0.0, 2.0, -4.0, 2.0, 0.0, 2.0, -4.0;
  EXPECT_EQ(Dense(dfdq), by_hand);
}

TEST(EvaluationShape, OnlyTheMatricesAskedForAreHeld) {
  Vec q, v;
  auto model = test::advanced_model("yarn", "", q, v);
  const auto nnz = model->pattern().nonZeros();
  Evaluation step;
  SparseMatrix a = model->pattern();
  Vec r;
  const StepWeights w{.mass = 1.0, .dfdv = -1e-3, .dfdq = -1e-6, .rhs_dfdq = 1e-3, .w = &v};
  model->evaluate_step(0.02, q, v, w, step, a, r);
  EXPECT_EQ(step.force.size(), model->num_dofs());
  EXPECT_EQ(step.dfdq.nonZeros() + step.dfdv.nonZeros() + step.mass.nonZeros(), 0);
  Evaluation mass;
  model->evaluate(0.02, q, v, kMass, mass);
  EXPECT_EQ(mass.mass.nonZeros(), nnz);
  EXPECT_EQ(mass.dfdq.nonZeros() + mass.dfdv.nonZeros(), 0);
  EXPECT_GT(mass.mass.coeffs().cwiseAbs().maxCoeff(), 0.0);
  // Asked for more later, the same evaluation is given what it lacks.
  model->evaluate(0.02, q, v, kForce | kDfdq, mass);
  EXPECT_EQ(mass.dfdq.nonZeros(), nnz);
  EXPECT_EQ(mass.dfdv.nonZeros(), 0);
}

}  // namespace
}  // namespace wl
