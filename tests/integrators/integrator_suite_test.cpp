// One value-parameterised suite instantiated for every integrator name
// (docs/design.md §10): convergence order against the closed-form
// solution of a linear mass–spring chain, energy behaviour, failure as an
// outcome, pinned DoFs, statistics and step callbacks.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "integrators/integrator.h"
#include "tests/support/fd_check.h"
#include "tests/support/test_models.h"

namespace wl {
namespace {

// The method's declared capabilities; the tests below check that each holds.
IntegratorCapabilities capabilities_of(const std::string& name) { return make_integrator(name)->capabilities(); }

// A chain of 4 unit masses, k = 1 N/m, L = 1 m, g = −1 m/s², displaced.
std::unique_ptr<test::SpringChain> make_chain(double k = 1.0) {
  auto chain = std::make_unique<test::SpringChain>(4, 1.0, k, 1.0, -1.0);
  Vec q0 = chain->initial_q(), v0 = chain->initial_v();
  q0[2] += 0.3;
  q0[4] -= 0.2;
  v0[3] = 0.5;
  chain->set_initial(q0, v0);
  return chain;
}

struct RunResult {
  StepResult result;
  double t = 0.0;
  Vec q, v;
  IntegratorStats stats;
  long callbacks = 0;
};

RunResult run(const std::string& name, Model& model, double t_end, IntegratorOptions opt, int outputs = 1) {
  auto integ = make_integrator(name);
  RunResult r;
  integ->on_step = [&](const StepRecord&) { ++r.callbacks; };
  integ->initialize(model, 0.0, model.initial_q(), model.initial_v(), opt);
  for (int k = 1; k <= outputs && r.result.outcome == Outcome::ok; ++k)
    r.result = integ->advance_to(t_end * k / outputs);
  r.t = integ->t();
  r.q = integ->q();
  r.v = integ->v();
  r.stats = integ->stats();
  return r;
}

double chain_error(test::SpringChain& chain, const RunResult& r, double t) {
  Vec qe, ve;
  chain.exact_state(t, qe, ve);
  return (r.q - qe).norm();
}

class IntegratorSuite : public ::testing::TestWithParam<std::string> {};

TEST_P(IntegratorSuite, ObservedOrderMatchesMethodOrder) {
  const IntegratorCapabilities cap = capabilities_of(GetParam());
  auto chain = make_chain();
  const double T = 2.0;
  if (cap.fixed_step_order == 0)
    GTEST_SKIP() << GetParam() << " has no fixed-step mode (see AdaptiveErrorFollowsTolerance)";
  const double h0 = cap.fixed_step_order == 1 ? T / 200 : T / 20;
  std::vector<double> hs, errs;
  for (int k = 0; k < 3; ++k) {
    IntegratorOptions opt;
    opt.dt = h0 / (1 << k);
    auto r = run(GetParam(), *chain, T, opt);
    ASSERT_EQ(r.result.outcome, Outcome::ok) << r.result.message;
    hs.push_back(opt.dt);
    errs.push_back(chain_error(*chain, r, T));
  }
  // Least-squares slope of log error against log h.
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (size_t i = 0; i < hs.size(); ++i) {
    const double x = std::log(hs[i]), y = std::log(errs[i]);
    sx += x, sy += y, sxx += x * x, sxy += x * y;
  }
  const double n = hs.size();
  const double order = (n * sxy - sx * sy) / (n * sxx - sx * sx);
  std::printf("[ order ] %-12s observed %.3f (expected %d), errors %.3e %.3e %.3e\n", GetParam().c_str(), order,
              cap.fixed_step_order, errs[0], errs[1], errs[2]);
  EXPECT_NEAR(order, cap.fixed_step_order, 0.3);
}

TEST_P(IntegratorSuite, AdaptiveErrorFollowsTolerance) {
  const IntegratorCapabilities cap = capabilities_of(GetParam());
  if (!cap.controls_error) GTEST_SKIP() << GetParam() << " is fixed-step only";
  auto chain = make_chain();
  const double T = 10.0;
  std::vector<double> errs;
  for (double tol : {1e-5, 1e-7, 1e-9}) {
    IntegratorOptions opt;
    opt.adaptive = true;
    opt.rtol = tol;
    opt.atol = tol * 1e-2;
    auto r = run(GetParam(), *chain, T, opt, 10);
    ASSERT_EQ(r.result.outcome, Outcome::ok) << r.result.message;
    errs.push_back(chain_error(*chain, r, T));
  }
  std::printf("[ tol   ] %-12s errors at rtol 1e-5, 1e-7, 1e-9: %.3e %.3e %.3e\n", GetParam().c_str(), errs[0], errs[1],
              errs[2]);
  // Error roughly proportional to the tolerance: each 100× tighter tolerance
  // gives at least 10× less error.
  for (size_t i = 1; i < errs.size(); ++i) EXPECT_LT(errs[i], errs[i - 1] / 10) << "tolerance step " << i;
  EXPECT_LT(errs.back(), 1e-5);
}

TEST_P(IntegratorSuite, EnergyBehaviour) {
  const IntegratorCapabilities cap = capabilities_of(GetParam());
  auto chain = make_chain();
  const double period = 2 * M_PI / chain->max_frequency();  // shortest period
  // Oscillation energy above the static equilibrium (gravity offsets the total).
  const double Eeq = chain->equilibrium_energy();
  const double E0 = chain->total_energy(chain->initial_q(), chain->initial_v()) - Eeq;
  ASSERT_GT(E0, 0.05);
  IntegratorOptions opt;
  opt.dt = period / 50;
  if (cap.energy == EnergyBehaviour::follows_tolerance) {
    opt.adaptive = true;
    opt.rtol = 1e-9;
    opt.atol = 1e-11;
    opt.dt = 1e-3;
  }
  const int cycles = cap.energy == EnergyBehaviour::bounded ? 200 : 20;
  auto integ = make_integrator(GetParam());
  integ->initialize(*chain, 0.0, chain->initial_q(), chain->initial_v(), opt);
  std::vector<double> es;
  const int samples = cycles * 4;
  for (int k = 1; k <= samples; ++k) {
    auto r = integ->advance_to(k * cycles * period / samples);
    ASSERT_EQ(r.outcome, Outcome::ok) << r.message;
    es.push_back(chain->total_energy(integ->q(), integ->v()) - Eeq);
  }
  const double emin = *std::min_element(es.begin(), es.end());
  const double emax = *std::max_element(es.begin(), es.end());
  const double elast = es.back();
  bool monotone = true;
  for (size_t i = 1; i < es.size(); ++i) monotone = monotone && es[i] <= es[i - 1] + 1e-12 * E0;
  auto mean = [&](size_t b, size_t e) {
    double m = 0;
    for (size_t i = b; i < e; ++i) m += es[i];
    return m / double(e - b);
  };
  switch (cap.energy) {
    case EnergyBehaviour::dissipative:
      // Backward Euler loses energy, monotonically, by a visible amount; the
      // L-stable second-order SDIRK too, by less (its damping per step is
      // O((ωh)⁴) against backward Euler's O((ωh)²)).
      EXPECT_TRUE(monotone);
      std::printf("[ energy ] %-12s E(20 periods)/E0 = %.6f\n", GetParam().c_str(), elast / E0);
      // Measured at h = T_min/50 over 20 periods: be 0.6–0.7, sdirk2 1 − 1.2e-5
      // (the trapezoidal rule, A- but not L-stable, would lose nothing).
      EXPECT_LT(elast, (cap.fixed_step_order == 1 ? 0.8 : 1.0 - 2e-6) * E0) << "E0 " << E0;
      if (cap.fixed_step_order == 2) {
        EXPECT_GT(elast, (1.0 - 1e-3) * E0) << "second order damps like a first-order method";
      }
      break;
    case EnergyBehaviour::bounded: {
      // Symplectic Euler: the energy oscillates within O(h) of E0 and does not
      // drift over 200 periods of the fastest mode.
      EXPECT_LT(emax, 1.15 * E0) << "E0 " << E0;
      EXPECT_GT(emin, 0.85 * E0) << "E0 " << E0;
      const size_t tenth = es.size() / 10;
      EXPECT_NEAR(mean(es.size() - tenth, es.size()), mean(0, tenth), 0.02 * E0);
      break;
    }
    case EnergyBehaviour::follows_tolerance: EXPECT_LT(std::abs(elast - E0), 1e-6 * E0) << "E0 " << E0; break;
  }
}

TEST_P(IntegratorSuite, ExplicitPastStepLimitFailsAsOutcomeImplicitStaysBounded) {
  const IntegratorCapabilities cap = capabilities_of(GetParam());
  auto chain = make_chain(1e4);  // ω_max = 200 rad/s: explicit limit h ≈ 1e-2 s
  IntegratorOptions opt;
  opt.dt = 0.05;
  opt.runaway_speed = 1e3;
  auto r = run(GetParam(), *chain, 20.0, opt);
  if (cap.explicit_method) {
    EXPECT_TRUE(r.result.outcome == Outcome::diverged || r.result.outcome == Outcome::nan)
        << to_string(r.result.outcome) << ": " << r.result.message;
    EXPECT_FALSE(r.result.message.empty());
  } else {
    EXPECT_EQ(r.result.outcome, Outcome::ok) << r.result.message;
    EXPECT_TRUE(r.q.allFinite());
    // Stable: the oscillation energy did not grow.
    const double Eeq = chain->equilibrium_energy();
    EXPECT_LE(chain->total_energy(r.q, r.v) - Eeq,
              (1 + 1e-6) * (chain->total_energy(chain->initial_q(), chain->initial_v()) - Eeq));
  }
}

TEST_P(IntegratorSuite, LibraryFailureCarriesTheLibraryFlag) {
  const IntegratorCapabilities cap = capabilities_of(GetParam());
  if (!cap.controls_error) GTEST_SKIP() << GetParam() << " is an in-house fixed-step method";
  // Error control cannot be met with a minimum step far above the stiff
  // chain's period (2π/200 s): SUNDIALS gives up and names its flag.
  auto chain = make_chain(1e4);
  IntegratorOptions opt;
  opt.adaptive = true;
  opt.rtol = 1e-10;
  opt.atol = 1e-12;
  opt.dt = 0.5;
  opt.min_step = 0.5;
  auto r = run(GetParam(), *chain, 20.0, opt);
  ASSERT_NE(r.result.outcome, Outcome::ok);
  if (cap.replays_steps) {  // an in-house adaptive method: its own outcome, no library flag
    EXPECT_EQ(r.result.outcome, Outcome::step_too_small) << r.result.message;
    EXPECT_EQ(r.result.library_flag, 0);
    EXPECT_NE(r.result.message.find("below the minimum"), std::string::npos) << r.result.message;
    return;
  }
  EXPECT_LT(r.result.library_flag, 0) << r.result.message;
  EXPECT_TRUE(r.result.library_flag_name.starts_with("ARK_") || r.result.library_flag_name.starts_with("IDA_"))
      << r.result.library_flag_name;
  EXPECT_NE(r.result.message.find(r.result.library_flag_name), std::string::npos) << r.result.message;
}

TEST_P(IntegratorSuite, RunawayIsAStructuredCauseAndTheStepIsNotAccepted) {
  auto chain = make_chain();  // starts at 0.5 m/s
  IntegratorOptions opt;
  opt.dt = 0.01;
  opt.runaway_speed = 0.1;
  auto r = run(GetParam(), *chain, 1.0, opt);
  EXPECT_EQ(r.result.outcome, Outcome::diverged) << r.result.message;
  EXPECT_EQ(r.result.cause, FailureCause::runaway_speed) << r.result.message;
  EXPECT_EQ(r.result.library_flag, 0);
  // The step that failed the check is not accepted: no time, count or callback.
  EXPECT_EQ(r.t, 0.0);
  EXPECT_EQ(r.stats.steps, 0);
  EXPECT_EQ(r.callbacks, 0);
}

TEST(BackwardEulerNewton, NonConvergenceIsAStructuredCause) {
  test::VariableMassOscillator osc(1.0, 2.0, 1.0, 0.8, 0.0);  // nonlinear: one iteration does not converge
  IntegratorOptions opt;
  opt.dt = 0.01;
  opt.newton_max_iters = 1;
  opt.newton_tol = 1e-15;
  auto r = run("be-newton", osc, 0.1, opt);
  EXPECT_EQ(r.result.outcome, Outcome::diverged) << r.result.message;
  EXPECT_EQ(r.result.cause, FailureCause::newton) << r.result.message;
  // Retaken in halves first (docs/design.md §6.1), the failure names how far.
  EXPECT_NE(r.result.message.find("retaken in halves 10 times"), std::string::npos) << r.result.message;
  EXPECT_EQ(r.stats.rejected_steps, 11);  // the step and its first halves, down to h/1024
  opt.newton_max_iters = 20;
  opt.newton_tol = 1e-8;
  EXPECT_EQ(run("be-newton", osc, 0.1, opt).result.outcome, Outcome::ok);
}

// A model without admissible states too: a step whose Newton iteration fails
// is retaken as two halves (docs/design.md §6.1), and the halves land where
// the run at the halved step lands.
TEST(BackwardEulerNewton, AFailedStepIsRetakenInHalves) {
  // Two Newton iterations do not converge a step of 0.1 s of this nonlinear
  // oscillator but do one of 0.05 s: every step is retaken as two halves.
  IntegratorOptions opt;
  opt.dt = 0.1;
  opt.newton_max_iters = 2;
  test::VariableMassOscillator osc(1.0, 2.0, 1.0, 0.8, 0.0);
  const RunResult retaken = run("be-newton", osc, 0.4, opt);
  ASSERT_EQ(retaken.result.outcome, Outcome::ok) << retaken.result.message;
  EXPECT_EQ(retaken.stats.rejected_steps, 4);
  EXPECT_EQ(retaken.stats.steps, 8);
  opt.dt = 0.05;
  const RunResult halved = run("be-newton", osc, 0.4, opt);
  ASSERT_EQ(halved.result.outcome, Outcome::ok) << halved.result.message;
  EXPECT_EQ(halved.stats.rejected_steps, 0);
  EXPECT_NEAR(retaken.q[0], halved.q[0], 1e-12);
  EXPECT_NEAR(retaken.v[0], halved.v[0], 1e-12);
  EXPECT_GT(std::abs(retaken.q[0] - osc.initial_q()[0]), 0.01) << "the oscillator should have moved";
}

TEST_P(IntegratorSuite, PinnedDofStaysFixedAndStatsAreCounted) {
  auto chain = make_chain();
  IntegratorOptions opt;
  opt.dt = 0.01;
  auto r = run(GetParam(), *chain, 1.0, opt, 10);
  ASSERT_EQ(r.result.outcome, Outcome::ok) << r.result.message;
  EXPECT_EQ(r.q[0], chain->initial_q()[0]);
  EXPECT_EQ(r.v[0], 0.0);
  EXPECT_GT(r.stats.steps, 0);
  EXPECT_EQ(r.callbacks, r.stats.steps);
  EXPECT_GE(r.stats.rhs_evals, r.stats.steps);
  EXPECT_GT(r.stats.wall_s, 0.0);
  if (!capabilities_of(GetParam()).explicit_method) {
    EXPECT_GT(r.stats.linear_setups, 0);
    EXPECT_GE(r.stats.linear_solves, r.stats.linear_setups);
    EXPECT_GT(r.stats.jac_evals, 0);
  }
}

TEST_P(IntegratorSuite, StepLimitEndsInMaxStepsOutcome) {
  auto chain = make_chain();
  IntegratorOptions opt;
  opt.dt = 0.01;
  opt.max_steps = 5;
  auto r = run(GetParam(), *chain, 1.0, opt);
  EXPECT_EQ(r.result.outcome, Outcome::max_steps) << r.result.message;
  EXPECT_LE(r.stats.steps, 5);
}

TEST_P(IntegratorSuite, NanInTheStateIsReportedNotCrashed) {
  auto chain = make_chain();
  Vec q0 = chain->initial_q();
  q0[3] = std::nan("");
  chain->set_initial(q0, chain->initial_v());
  IntegratorOptions opt;
  opt.dt = 0.01;
  auto integ = make_integrator(GetParam());
  StepResult r;
  try {
    integ->initialize(*chain, 0.0, chain->initial_q(), chain->initial_v(), opt);
    r = integ->advance_to(0.1);
  } catch (const std::exception& e) {
    FAIL() << "threw: " << e.what();
  }
  EXPECT_TRUE(r.outcome == Outcome::nan || r.outcome == Outcome::diverged) << to_string(r.outcome);
}

// A chain that cannot represent states where mass 2 has moved more than 5 cm
// (as the yarn model cannot represent sliding coordinates that meet).
class FencedChain : public test::SpringChain {
 public:
  FencedChain() : SpringChain(4, 1.0, 1.0, 1.0, -1.0) {
    Vec q0 = initial_q();
    q0[2] += 0.3;
    set_initial(q0, initial_v());
    fence_ = q0[2];
  }
  std::string invalid_state(const Vec& q) const override {
    return std::abs(q[2] - fence_) > 0.05 ? "mass 2 left its fence" : "";
  }

 private:
  double fence_ = 0.0;
};

TEST_P(IntegratorSuite, StateTheModelCannotRepresentIsANamedOutcome) {
  FencedChain chain;
  IntegratorOptions opt;
  opt.dt = 0.01;
  auto r = run(GetParam(), chain, 2.0, opt);
  EXPECT_EQ(r.result.outcome, Outcome::invalid_state) << to_string(r.result.outcome) << ": " << r.result.message;
  EXPECT_EQ(r.result.message, "mass 2 left its fence");
  EXPECT_GT(r.stats.steps, 0);
}

TEST_P(IntegratorSuite, StateDependentMassConservesEnergyOrIsNotOffered) {
  const IntegratorCapabilities cap = capabilities_of(GetParam());
  test::VariableMassOscillator osc(1.0, 2.0, 1.0, 0.8, 0.0);
  IntegratorOptions opt;
  opt.dt = cap.energy == EnergyBehaviour::follows_tolerance ? 1e-3 : 2e-3;
  opt.adaptive = cap.energy == EnergyBehaviour::follows_tolerance;
  opt.rtol = 1e-9;
  opt.atol = 1e-11;
  auto r = run(GetParam(), osc, 10.0, opt);
  if (!cap.state_dependent_mass) {
    EXPECT_EQ(r.result.outcome, Outcome::not_offered);
    EXPECT_NE(r.result.message.find("not offered"), std::string::npos) << r.result.message;
    return;
  }
  ASSERT_EQ(r.result.outcome, Outcome::ok) << r.result.message;
  const double E0 = osc.total_energy(osc.initial_q(), osc.initial_v());
  const double E1 = osc.total_energy(r.q, r.v);
  EXPECT_EQ(r.q[1], 0.0);
  if (cap.energy == EnergyBehaviour::follows_tolerance) EXPECT_NEAR(E1, E0, 1e-5 * E0);
  else if (cap.energy == EnergyBehaviour::bounded) EXPECT_NEAR(E1, E0, 0.02 * E0);
  else EXPECT_LT(E1, E0);
}

INSTANTIATE_TEST_SUITE_P(AllIntegrators, IntegratorSuite, ::testing::ValuesIn(integrator_names()),
                         [](const auto& param_info) {
                           std::string s = param_info.param;
                           for (char& c : s)
                             if (c == '-') c = '_';
                           return s;
                         });

TEST(IntegratorRegistry, EveryNameRunsInSomeModeAndUnknownNameThrows) {
  for (auto& n : integrator_names()) {
    const IntegratorCapabilities cap = capabilities_of(n);
    EXPECT_TRUE(cap.controls_error || cap.fixed_step_order > 0) << n;
    EXPECT_EQ(make_integrator(n)->name(), n);
  }
  EXPECT_THROW(make_integrator("rk-nonsense"), std::invalid_argument);
}

TEST(TermModelSplit, ExplicitAndImplicitTermsPartitionTheForce) {
  auto chain = make_chain();
  Evaluation all, ex, im;
  const Vec q = chain->initial_q(), v = chain->initial_v();
  chain->evaluate(0.0, q, v, kForce | kDfdq, all);
  chain->evaluate(0.0, q, v, kForce | kDfdq | kExplicitTerms, ex);
  chain->evaluate(0.0, q, v, kForce | kDfdq | kImplicitTerms, im);
  // The explicit part is the constant force m·g on each free mass only.
  EXPECT_NEAR(ex.force[3], -1.0, 1e-14);
  EXPECT_EQ(ex.force[0], 0.0);
  EXPECT_EQ(Eigen::MatrixXd(ex.dfdq).norm(), 0.0);
  EXPECT_LT((ex.force + im.force - all.force).norm(), 1e-14);
  EXPECT_LT(Eigen::MatrixXd(im.dfdq - all.dfdq).norm(), 1e-14);
  EXPECT_GT(im.force.norm(), 0.1);
}

TEST(IntegratorTestModels, TermsPassFiniteDifferenceCheck) {
  auto spring = test::make_spring_3d({{0, 1, 2, 3, 4, 5}}, {0.7}, 3.0, 0.4);
  std::vector<test::LocalState> st = {{{0, 0, 0, 1, 0.2, -0.3}, {0.1, 0, 0, 0, 0.3, 0}},
                                      {{0.5, -1, 2, 0.1, 0.4, 0.9}, {1, 2, 3, -1, 0, 1}}};
  auto r = test::check_element(*spring, 0, st);
  EXPECT_TRUE(r.ok) << r.detail;
  auto mass = test::make_variable_mass_term(1.3, 2.0);
  auto r2 = test::check_element(*mass, 0, {{{0.4}, {0.7}}, {{-1.1}, {0.3}}});
  EXPECT_TRUE(r2.ok) << r2.detail;
}

}  // namespace
}  // namespace wl
