// --time-steps controlled: its --rtol: a tolerance whose atol (10⁻³·rtol) is
// still a number > 0, refused with the value as given otherwise.
#include <gtest/gtest.h>

#include <stdexcept>

#include "driver/time_steps.h"

namespace wl {
namespace {

std::string refusal(double rtol) {
  try {
    parse_time_steps("--time-steps", "controlled", rtol);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "(accepted)";
}

TEST(TimeSteps, RefusesAnRtolWhoseAtolIsZeroStatingItsValue) {
  EXPECT_EQ(refusal(5e-324), "--rtol: got 4.94066e-324, expected a tolerance in (0, 1) whose atol = 1e-3·rtol is > 0");
  EXPECT_EQ(refusal(1e-7), "(accepted)");
  EXPECT_EQ(refusal(1e-300), "(accepted)");  // atol 1e-303: small, still a number > 0
  EXPECT_EQ(refusal(0.0), "--rtol: got 0, expected a tolerance in (0, 1) whose atol = 1e-3·rtol is > 0");
  EXPECT_EQ(refusal(1.0), "--rtol: got 1, expected a tolerance in (0, 1) whose atol = 1e-3·rtol is > 0");
}

}  // namespace
}  // namespace wl
