// The tolerance search of --accuracy (driver/accuracy_search.h) on synthetic
// error–tolerance relations: a power law is followed to its target, a floor is
// recognised, the budget and the tolerance floor bound the search.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>

#include "driver/accuracy_search.h"

namespace wl {
namespace {

struct Searched {
  std::vector<ToleranceTrial> trials;
  SearchStep last;
};

// The search driven by the true errors `error(rtol)` from the first tolerance
// until it stops. Two trials' errors are taken as independent: their distance
// is √(e_i² + e_j²).
Searched search(const std::function<double(double)>& error, double target, const SearchLimits& limits = {}) {
  Searched s;
  double rtol = limits.first_rtol;
  for (int guard = 0; guard < 50; ++guard) {
    if (!s.trials.empty()) s.trials.back().error_m = std::hypot(error(s.trials.back().rtol), error(rtol));
    s.trials.push_back({rtol, true, std::nan("")});
    s.last = next_tolerance(s.trials, target, limits);
    if (s.last.verdict != SearchVerdict::next_trial) return s;
    EXPECT_LE(s.last.next_rtol, rtol / limits.companion_ratio * (1 + 1e-12)) << "each trial measures the one before";
    rtol = s.last.next_rtol;
  }
  ADD_FAILURE() << "the search did not stop";
  return s;
}

TEST(AccuracySearch, FitRecoversAPowerLaw) {
  const std::vector<ToleranceTrial> t = {{1e-3, true, 3.0 * std::pow(1e-3, 0.4)},
                                         {1e-4, true, 3.0 * std::pow(1e-4, 0.4)},
                                         {2e-6, true, 3.0 * std::pow(2e-6, 0.4)},
                                         {1e-7, true, std::nan("")}};
  const PowerLaw fit = fit_power_law(t);
  EXPECT_EQ(fit.points, 3);
  EXPECT_NEAR(fit.slope, 0.4, 1e-12);
  EXPECT_NEAR(fit.log_c, std::log(3.0), 1e-10);
  EXPECT_TRUE(std::isnan(fit_power_law({{1e-4, true, 1e-3}}).slope)) << "one tolerance measures no slope";
}

// The first trial meets the target: the second, ten times tighter, measures
// it, is bounded by the same distance and is the run.
TEST(AccuracySearch, TargetMetAtTheFirstTrial) {
  const Searched s = search([](double r) { return 10.0 * r; }, 2e-2);
  EXPECT_EQ(s.last.verdict, SearchVerdict::reached);
  ASSERT_EQ(s.trials.size(), 2u);
  EXPECT_DOUBLE_EQ(s.trials[1].rtol, 1e-4);
  EXPECT_DOUBLE_EQ(s.last.bound_m, std::hypot(1e-2, 1e-3));
}

// A bound needs a looser trial at least companion_ratio times looser.
TEST(AccuracySearch, NoBoundFromATrialCloseBy) {
  const std::vector<ToleranceTrial> t = {{1e-3, true, 1e-9}, {3e-4, true, std::nan("")}};
  EXPECT_TRUE(std::isnan(last_trial_bound(t)));
  EXPECT_EQ(next_tolerance(t, 1e-4).verdict, SearchVerdict::next_trial);
  EXPECT_DOUBLE_EQ(last_trial_bound({{1e-3, true, 1e-9}, {1e-4, false, std::nan("")}, {1e-5, true, std::nan("")}}),
                   1e-9)
      << "a failed trial between two is skipped";
}

// A relation much flatter than proportional (slope 0.35, as error control
// delivers on the damped hanging cloth) and a proportional one: the target is
// reached in a few trials whose cost, with a run's cost growing as rtol^-¼, is
// at most three times the last one's.
TEST(AccuracySearch, PowerLawsReachTheirTargetAffordably) {
  for (double slope : {0.35, 1.0}) {
    const auto error = [slope](double r) { return 3.8e-4 * std::pow(r / 1e-3, slope); };
    const Searched s = search(error, 1e-4);
    EXPECT_EQ(s.last.verdict, SearchVerdict::reached) << "slope " << slope << ": " << s.last.reason;
    EXPECT_LE(s.trials.size(), 4u) << "slope " << slope;
    EXPECT_LE(s.last.bound_m, 1e-4);
    double cost = 0.0;
    for (const ToleranceTrial& t : s.trials) cost += std::pow(t.rtol, -0.25);
    EXPECT_LE(cost, 3.0 * std::pow(s.trials.back().rtol, -0.25)) << "slope " << slope;
  }
}

// One tightening that lowers the error less than proportionally is no floor
// (the old rule stopped there): the fitted slope predicts the next tolerance.
TEST(AccuracySearch, ALessThanProportionalFallIsNoFloor) {
  const std::vector<ToleranceTrial> t = {{1e-3, true, 3.8e-4}, {1e-4, true, 2.1e-4}, {1e-5, true, std::nan("")}};
  const SearchStep step = next_tolerance(t, 1e-4);
  EXPECT_EQ(step.verdict, SearchVerdict::next_trial) << step.reason;
  EXPECT_NEAR(step.slope, std::log(3.8 / 2.1) / std::log(10.0), 1e-12);
  const double aimed = 1e-4 * std::pow(0.7e-4 / 2.1e-4, 1.0 / step.slope);  // 0.7 × target from the last measured
  EXPECT_LT(aimed, 1e-5);
  EXPECT_NEAR(step.next_rtol, std::min(aimed, 1e-6), 1e-9 * aimed);
}

TEST(AccuracySearch, AFloorIsRecognisedFromSeveralTrials) {
  // The error approaches 2e-4 m however tight the tolerance; the target is below it.
  const Searched s = search([](double r) { return 2e-4 + 1e-1 * r; }, 1e-4);
  EXPECT_EQ(s.last.verdict, SearchVerdict::floor) << s.last.reason;
  EXPECT_EQ(s.trials.size(), 4u) << "three measured trials show a floor";
  EXPECT_NE(s.last.reason.find("a floor above the target"), std::string::npos) << s.last.reason;
}

TEST(AccuracySearch, TheTrialBudgetBoundsTheSearch) {
  SearchLimits limits;
  limits.max_trials = 3;
  const Searched s = search([](double r) { return r; }, 1e-9, limits);
  EXPECT_EQ(s.last.verdict, SearchVerdict::budget);
  ASSERT_EQ(s.trials.size(), 3u);
  EXPECT_NE(s.last.reason.find("budget of 3 trials"), std::string::npos) << s.last.reason;
  EXPECT_DOUBLE_EQ(s.trials[2].rtol, 1e-6) << "a step on the assumed slope tightens by at most 100";
}

// A target the measured relation puts below the tolerance floor ends the
// search without running there (before, --accuracy 1e-15 tightened for ever).
TEST(AccuracySearch, ATargetBelowTheToleranceFloorStopsTheSearch) {
  const Searched s = search([](double r) { return r; }, 1e-20);
  EXPECT_EQ(s.last.verdict, SearchVerdict::tolerance_floor) << s.last.reason;
  EXPECT_EQ(s.trials.size(), 3u) << "two measured trials give the relation";
  EXPECT_NE(s.last.reason.find("below the tolerance floor rtol 1e-12"), std::string::npos) << s.last.reason;
}

TEST(AccuracySearch, TheToleranceFloorBoundsTheSearch) {
  SearchLimits limits;
  limits.min_rtol = 1e-5;
  const Searched s = search([](double r) { return r; }, 2e-5, limits);
  EXPECT_EQ(s.last.verdict, SearchVerdict::tolerance_floor) << s.last.reason;
  EXPECT_DOUBLE_EQ(s.trials.back().rtol, 1e-5);
  for (const ToleranceTrial& t : s.trials) EXPECT_GE(t.rtol, 1e-5);
}

TEST(AccuracySearch, AFailedTrialIsFollowedByATighterOne) {
  const SearchStep step = next_tolerance({{1e-4, false, std::nan("")}}, 1e-4);
  EXPECT_EQ(step.verdict, SearchVerdict::next_trial);
  EXPECT_DOUBLE_EQ(step.next_rtol, 1e-5);
}

}  // namespace
}  // namespace wl
