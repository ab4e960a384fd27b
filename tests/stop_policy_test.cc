// The stopping policy (src/stop_policy.h): each named check, their order, and the probe before a
// remaining-χ² stop.
#include "src/stop_policy.h"

#include <cmath>
#include <vector>

#include <gtest/gtest.h>

namespace dynslam {
namespace {

// An accepted linear solve from `cost` to `trial` with step quality `rho`.
StepRecord Accepted(double cost, double trial, double rho = 1) {
  StepRecord row;
  row.cost = cost;
  row.trial_cost = trial;
  row.accepted = true;
  row.relative_decrease = rho;
  return row;
}

TEST(StopPolicyTest, AnInterruptComesBeforeEveryOtherCheck) {
  SolverOptions options;
  options.should_stop = [] { return true; };
  options.max_time = 1e-9;  // already over
  const StopPolicy policy(options, StopPolicy::Clock::now() - std::chrono::seconds(1));
  const std::optional<StopDecision> stop = policy.Check({}, 0);
  ASSERT_TRUE(stop);
  EXPECT_EQ(stop->termination, "interrupted");
  options.should_stop = nullptr;
  EXPECT_EQ(policy.Check({}, 0)->termination, "time_limit");
  options.max_time = 0;
  EXPECT_FALSE(policy.Check({}, 0));
}

// Decreases 8, 4: ratio 1/2, so the series leaves 4 more in cost, χ² 8 — at most 10 stops (after
// a probe), at most 1 does not; 0 is the rule off.
TEST(StopPolicyTest, TheRemainingChi2RuleReadsTheGeometricSeries) {
  const std::vector<StepRecord> rows = {Accepted(100, 92), Accepted(92, 88)};
  EXPECT_DOUBLE_EQ(StopPolicy::EstimatedRemainingChi2(rows), 8);
  SolverOptions options;
  options.remaining_chi2 = 10;
  const StopPolicy loose(options, StopPolicy::Clock::now());
  const std::optional<StopDecision> stop = loose.Check(rows, 2);
  ASSERT_TRUE(stop);
  EXPECT_EQ(stop->termination, "convergence");
  EXPECT_TRUE(stop->after_probe);
  options.remaining_chi2 = 1;
  EXPECT_FALSE(StopPolicy(options, StopPolicy::Clock::now()).Check(rows, 2));
  options.remaining_chi2 = 0;
  EXPECT_FALSE(StopPolicy(options, StopPolicy::Clock::now()).WithinRemainingChi2(0));
}

// With the secant estimate the tail is no geometric series: a sudden fall in the decrease (8,
// then 0.1: estimate 0.2) stops only once the estimate after the step before is within the bound
// too (there decreases 4, then 8: no series, +inf).
TEST(StopPolicyTest, WithTheSecantEstimateTheRuleMustHoldForTheLastTwoSteps) {
  std::vector<StepRecord> rows = {Accepted(100, 96), Accepted(96, 88), Accepted(88, 87.9)};
  EXPECT_NEAR(StopPolicy::EstimatedRemainingChi2(rows), 0.2, 1e-12);
  SolverOptions options;
  options.remaining_chi2 = 1;
  EXPECT_TRUE(StopPolicy(options, StopPolicy::Clock::now()).Check(rows, 3));
  options.secant_memory = 2;
  const StopPolicy secant(options, StopPolicy::Clock::now());
  EXPECT_FALSE(secant.Check(rows, 3));
  rows.push_back(Accepted(87.9, 87.89));
  EXPECT_TRUE(secant.Check(rows, 4));
}

TEST(StopPolicyTest, AProbeThatGainsMoreThanTheRuleAllowsGoesOn) {
  SolverOptions options;
  options.remaining_chi2 = 0.01;
  const StopPolicy policy(options, StopPolicy::Clock::now());
  const StopDecision probe{"convergence", "estimate", true};
  const std::optional<StopDecision> stop = policy.AfterProbe(probe, 0.005);
  ASSERT_TRUE(stop);
  EXPECT_EQ(stop->detail, "estimate; extrapolating gained 0.005");
  EXPECT_FALSE(policy.AfterProbe(probe, 0.02));
}

TEST(StopPolicyTest, AnExtrapolationBreaksTheSeries) {
  StepRecord extrapolation = Accepted(100, 95);
  extrapolation.extrapolation = true;
  EXPECT_TRUE(std::isinf(StopPolicy::EstimatedRemainingChi2(
      {extrapolation, Accepted(95, 92), Accepted(92, 90)})));
  EXPECT_TRUE(std::isinf(StopPolicy::EstimatedRemainingChi2({Accepted(100, 92)})));
  EXPECT_TRUE(std::isinf(StopPolicy::EstimatedRemainingChi2({Accepted(100, 92), Accepted(92, 84)})));
}

TEST(StopPolicyTest, TheReleasedRuleStopsAtASmallDecreaseOrItsIterations) {
  SolverOptions options;
  options.dsc_released_lm = true;
  options.max_iterations = 3;
  const StopPolicy policy(options, StopPolicy::Clock::now());
  EXPECT_EQ(policy.Check({Accepted(10, 10 - 1e-6)}, 1)->termination, "convergence");
  EXPECT_EQ(policy.Check({Accepted(10, 9)}, 3)->termination, "no_convergence");
  EXPECT_FALSE(policy.Check({Accepted(10, 9)}, 2));
}

TEST(StopPolicyTest, AbsoluteDecreaseStopsAtASmallAcceptedStep) {
  SolverOptions options;
  options.absolute_decrease = 1e-5;
  options.remaining_chi2 = 0;
  const StopPolicy policy(options, StopPolicy::Clock::now());
  EXPECT_EQ(policy.Check({Accepted(10, 10 - 1e-6)}, 1)->termination, "convergence");
  EXPECT_FALSE(policy.Check({Accepted(10, 9)}, 1));
  StepRecord rejected = Accepted(10, 10);
  rejected.accepted = false;
  EXPECT_FALSE(policy.Check({rejected}, 0));
  options.absolute_decrease = 0;
  EXPECT_FALSE(policy.Check({Accepted(10, 10 - 1e-6)}, 1));
}

}  // namespace
}  // namespace dynslam
