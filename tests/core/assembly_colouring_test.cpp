// The assembly's element colouring (models/core/assembly.cpp) has no colour
// limit: a term whose elements all share one DoF (a star of springs, as a
// scene crushed to a point makes of a knit's contacts) needs one colour per
// element, and its force and stiffness are still each element's sum.
#include <gtest/gtest.h>

#include "models/core/assembly.h"
#include "tests/support/test_models.h"

namespace wl {
namespace {

TEST(AssemblyColouring, AStarOfTwoHundredSpringsSharingOneDoFAssemblesExactly) {
  const int arms = 200;
  const double k = 3.0, rest = 1.0;
  std::vector<std::array<int, 2>> stencils;
  for (int a = 1; a <= arms; ++a) stencils.push_back({0, a});
  auto star = test::make_linear_spring_1d(stencils, k, rest);
  Assembly assembly(arms + 1, {star.get()});
  Vec q(arms + 1), v = Vec::Zero(arms + 1);
  q[0] = 0.25;
  for (int a = 1; a <= arms; ++a) q[a] = 0.01 * a;  // arm a stretched by q_a − q_0 − 1
  Vec f = Vec::Zero(arms + 1);
  SparseMatrix dfdq = assembly.pattern();
  AssemblyRequest request;
  request.dfdq = true;
  assembly.add_stage(0, q, v, Vec(), request, f, &dfdq, nullptr, nullptr);
  double hub = 0.0;
  for (int a = 1; a <= arms; ++a) {
    const double tension = k * (q[a] - q[0] - rest);
    hub += tension;
    EXPECT_DOUBLE_EQ(f[a], -tension) << "arm " << a;
    EXPECT_DOUBLE_EQ(dfdq.coeff(a, a), -k) << "arm " << a;
    EXPECT_DOUBLE_EQ(dfdq.coeff(0, a), k) << "arm " << a;
  }
  EXPECT_NEAR(f[0], hub, 1e-12 * arms * k);
  EXPECT_DOUBLE_EQ(dfdq.coeff(0, 0), -arms * k);
}

}  // namespace
}  // namespace wl
