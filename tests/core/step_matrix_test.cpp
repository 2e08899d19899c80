// Model::evaluate_step (docs/design.md §3.3): the step matrix formed in one
// assembly pass equals M − hD − h²K formed here from the separately assembled
// M, ∂f/∂v and ∂f/∂q, and its right-hand side f + hKv, to round-off, on both
// models; so does the two-pass route of a model that needs the parts apart.
#include <gtest/gtest.h>

#include "tests/support/advanced_model.h"

namespace wl {
namespace {

constexpr double kH = 0.01;  // large enough that hD and h²K are far above the round-off of A

double max_abs(const SparseMatrix& m) {
  return Eigen::Map<const Vec>(m.valuePtr(), m.nonZeros()).cwiseAbs().maxCoeff();
}

void check_single_pass(const std::string& model_name, const std::string& extra_toml = "") {
  SCOPED_TRACE(model_name + extra_toml);
  Vec q, v;
  auto model = test::advanced_model(model_name, extra_toml, q, v);
  const double t = 0.02;

  Evaluation parts;  // with the step stiffness: a term that projects it does so in both routes
  model->evaluate(t, q, v, kForce | kDfdq | kStepStiffness | kDfdv | kMass, parts);
  const SparseMatrix expected = parts.mass - kH * parts.dfdv - kH * kH * parts.dfdq;
  const Vec expected_r = parts.force + kH * (parts.dfdq * v);
  // Every part matters: each is far above the tolerance, so a dropped term or
  // a wrong weight fails (the FEM's ∂f/∂v is wind's only, the smallest).
  const double scale = max_abs(parts.mass) + kH * max_abs(parts.dfdv) + kH * kH * max_abs(parts.dfdq);
  const double tol = 1e-13 * scale;
  EXPECT_GT(kH * max_abs(parts.dfdv), 1e3 * tol);
  EXPECT_GT(kH * kH * max_abs(parts.dfdq), 1e3 * tol);
  EXPECT_GT(max_abs(parts.mass), 1e3 * tol);
  const double r_scale = parts.force.cwiseAbs().maxCoeff() + kH * (parts.dfdq * v).cwiseAbs().maxCoeff();
  EXPECT_GT(kH * (parts.dfdq * v).cwiseAbs().maxCoeff(), 1e3 * 1e-13 * r_scale);

  auto check = [&](const StepWeights& w, const char* what) {
    SCOPED_TRACE(what);
    Evaluation scratch;
    SparseMatrix a = model->pattern();
    Vec r;
    model->evaluate_step(t, q, v, w, scratch, a, r);
    ASSERT_EQ(a.nonZeros(), expected.nonZeros());
    EXPECT_LE(max_abs(SparseMatrix(a - expected)), tol);
    EXPECT_LE((r - expected_r).cwiseAbs().maxCoeff(), 1e-13 * r_scale);
    EXPECT_TRUE(scratch.force == parts.force);  // the force is the same sum, in the same order
  };
  StepWeights w{.mass = 1.0, .dfdv = -kH, .dfdq = -kH * kH, .rhs_dfdq = kH, .w = &v};
  check(w, "mass assembled in the pass");
  w.constant_mass = &parts.mass;  // be-linear's route for a mass that does not depend on q
  check(w, "mass given");
}

TEST(StepMatrix, SinglePassEqualsPartsYarn) { check_single_pass("yarn"); }

TEST(StepMatrix, SinglePassEqualsPartsFem) { check_single_pass("fem"); }

// With exact_contact_jacobian the yarn model adds the contact chain after the
// stages and evaluates the parts apart (Model::evaluate_step's default).
TEST(StepMatrix, TwoPassRouteWithContactChain) { check_single_pass("yarn", "exact_contact_jacobian = true\n"); }

// The yarn stretch's step stiffness projected (docs/models.md §3.2): some
// segment of the hanging cloth is compressed, so the projection changes ∂f/∂q,
// and both routes form the same projected A.
TEST(StepMatrix, BothRoutesProjectTheStretchAlike) {
  for (const char* chain : {"", "exact_contact_jacobian = true\n"}) {
    const std::string toml = std::string(chain) + "[terms]\nstretch_step_hessian = \"projected\"\n";
    check_single_pass("yarn", toml);
    Vec q, v;
    auto model = test::advanced_model("yarn", toml, q, v);
    ASSERT_TRUE(model->projects_step_stiffness());
    Evaluation exact, projected;
    model->evaluate(0.02, q, v, kDfdq, exact);
    model->evaluate(0.02, q, v, kDfdq | kStepStiffness, projected);
    EXPECT_GT(max_abs(SparseMatrix(exact.dfdq - projected.dfdq)), 1e-6 * max_abs(exact.dfdq));
  }
}

}  // namespace
}  // namespace wl
