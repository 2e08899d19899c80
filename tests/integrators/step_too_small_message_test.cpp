// The step_too_small outcome of our own adaptive method states both steps with
// their significant digits, also at the microsecond scale a stiff scene works at.
#include <gtest/gtest.h>

#include <regex>

#include "integrators/integrator.h"
#include "tests/support/test_models.h"

namespace wl {
namespace {

// A chain of period 2π·10⁻⁸ s: error control at rtol 10⁻¹⁰ asks for steps far below 5·10⁻⁷ s.
TEST(StepTooSmallMessage, StatesTheStepAndTheMinimumWithTheirDigits) {
  test::SpringChain chain(4, 1.0, 1e16, 1.0, -1.0);
  Vec q0 = chain.initial_q();
  q0[2] += 0.3;
  chain.set_initial(q0, chain.initial_v());
  IntegratorOptions opt;
  opt.adaptive = true;
  opt.rtol = 1e-10;
  opt.atol = 1e-12;
  opt.dt = 5e-7;
  opt.min_step = 5e-7;
  auto integ = make_integrator("sdirk2");
  integ->initialize(chain, 0.0, chain.initial_q(), chain.initial_v(), opt);
  const StepResult r = integ->advance_to(1e-3);
  ASSERT_EQ(r.outcome, Outcome::step_too_small) << r.message;
  std::smatch m;
  ASSERT_TRUE(std::regex_search(r.message, m, std::regex("^step ([^ ]+) s below the minimum 5e-07 s"))) << r.message;
  const double step = std::stod(m[1]);
  EXPECT_GT(step, 0.0) << r.message;
  EXPECT_LT(step, 5e-7) << r.message;
}

}  // namespace
}  // namespace wl
