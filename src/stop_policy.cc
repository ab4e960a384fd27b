#include "src/stop_policy.h"

#include <algorithm>
#include <cstdio>
#include <limits>

namespace dynslam {
namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

// The checks, each nothing or the decision to stop.

std::optional<StopDecision> Interrupted(const SolverOptions& options, int steps) {
  if (!options.should_stop || !options.should_stop()) return std::nullopt;
  return StopDecision{"interrupted", "stopped on request after " + std::to_string(steps) + " steps"};
}

std::optional<StopDecision> TimeLimit(const SolverOptions& options, StopPolicy::Clock::time_point start,
                                      int steps) {
  if (!(options.max_time > 0)) return std::nullopt;
  if (std::chrono::duration<double>(StopPolicy::Clock::now() - start).count() < options.max_time) {
    return std::nullopt;
  }
  return StopDecision{"time_limit", "time limit reached after " + std::to_string(steps) + " steps"};
}

std::optional<StopDecision> ReleasedRule(const SolverOptions& options,
                                         const std::vector<StepRecord>& rows, int accepted) {
  if (!options.dsc_released_lm || rows.empty() || !rows.back().accepted) return std::nullopt;
  if (rows.back().cost - rows.back().trial_cost <= kReleasedTolerance) {
    return StopDecision{"convergence", "released rule: an accepted step lowered the cost by <= 1e-5"};
  }
  if (accepted >= options.max_iterations) {
    return StopDecision{"no_convergence",
                        "released rule: " + std::to_string(accepted) + " iterations"};
  }
  return std::nullopt;
}

// GTSAM's absoluteErrorTol: an accepted linear solve that lowered the cost by at most it.
std::optional<StopDecision> AbsoluteDecrease(const SolverOptions& options,
                                             const std::vector<StepRecord>& rows) {
  if (!(options.absolute_decrease > 0) || rows.empty()) return std::nullopt;
  const StepRecord& last = rows.back();
  if (!last.accepted || !IsLinearSolve(last)) return std::nullopt;
  if (last.cost - last.trial_cost > options.absolute_decrease) return std::nullopt;
  char detail[96];
  std::snprintf(detail, sizeof detail, "an accepted step lowered the cost by <= absolute_decrease %g",
                options.absolute_decrease);
  return StopDecision{"convergence", detail};
}

// The remaining-χ² rule's bound on the χ² still to gain, or nothing when the rule is off: the
// one place that reads SolverOptions::remaining_chi2.
std::optional<double> RemainingChi2Bound(const SolverOptions& options) {
  if (!(options.remaining_chi2 > 0)) return std::nullopt;
  return options.remaining_chi2;
}

std::optional<StopDecision> RemainingChi2(const SolverOptions& options,
                                          const std::vector<StepRecord>& rows) {
  if (options.dsc_released_lm) return std::nullopt;  // its own rule
  const std::optional<double> bound = RemainingChi2Bound(options);
  double remaining = StopPolicy::EstimatedRemainingChi2(rows);
  // A tail with the secant estimate is not a geometric series (its steps alternate between the
  // two models): the estimate must hold after the step before too (docs/SOLVER.md).
  if (options.secant_memory > 0 && !rows.empty()) {
    remaining = std::max(remaining, StopPolicy::EstimatedRemainingChi2(rows, rows.size() - 1));
  }
  if (!bound || !(remaining <= *bound)) return std::nullopt;
  char detail[160];
  std::snprintf(detail, sizeof detail,
                "the chi2 still to gain is estimated at %.3g <= remaining_chi2 %g", remaining,
                *bound);
  return StopDecision{"convergence", detail, /*after_probe=*/true};
}

}  // namespace

std::optional<StopDecision> StopPolicy::Check(const std::vector<StepRecord>& rows,
                                              int accepted) const {
  const int steps = static_cast<int>(rows.size());
  for (std::optional<StopDecision> stop :
       {Interrupted(options_, steps), TimeLimit(options_, start_, steps),
        ReleasedRule(options_, rows, accepted), AbsoluteDecrease(options_, rows),
        RemainingChi2(options_, rows)}) {
    if (stop) return stop;
  }
  return std::nullopt;
}

bool StopPolicy::WithinRemainingChi2(double chi2) const {
  const std::optional<double> bound = RemainingChi2Bound(options_);
  return bound && chi2 <= *bound;
}

std::optional<StopDecision> StopPolicy::AfterProbe(const StopDecision& probe,
                                                   double gained_chi2) const {
  if (!WithinRemainingChi2(gained_chi2)) return std::nullopt;
  char gained[96];
  std::snprintf(gained, sizeof gained, "; extrapolating gained %.3g", gained_chi2);
  return StopDecision{probe.termination, probe.detail + gained};
}

StopDecision StopPolicy::StepLimit() const {
  return {"no_convergence", std::to_string(options_.max_iterations) + " linear solves, the limit"};
}

// The χ² still to gain after the last step (docs/SOLVER.md "When a solve stops"), told only
// when the last two steps were accepted decreases, the later one smaller: twice the rest of
// the geometric series of their ratio r, d·r/(1 − r), and never less than twice the last
// step's actual or predicted decrease d, nor than twice what the 1-D quadratic that explains
// the step's quality ρ ∈ (1, 2) leaves along the step, d·(ρ − 1)²/((2 − ρ)·ρ) (a model whose
// curvature is 1/(2 − ρ) times too high: its steps undershoot). +inf otherwise.
double StopPolicy::EstimatedRemainingChi2(const std::vector<StepRecord>& rows) {
  return EstimatedRemainingChi2(rows, rows.size());
}

double StopPolicy::EstimatedRemainingChi2(const std::vector<StepRecord>& rows, size_t count) {
  if (count < 2 || count > rows.size()) return kInfinity;
  const StepRecord& last = rows[count - 1];
  const StepRecord& before = rows[count - 2];
  if (!last.accepted || !before.accepted || !(last.relative_decrease > 0)) return kInfinity;
  // An extrapolation or gauge move breaks the series: the step after it also corrects its
  // overshoot, so the ratio is read only from the second and third steps after one.
  for (size_t i = count >= 3 ? count - 3 : 0; i < count; ++i) {
    if (!IsLinearSolve(rows[i])) return kInfinity;
  }
  const double decrease = last.cost - last.trial_cost;
  const double ratio = decrease / (before.cost - before.trial_cost);
  if (!(decrease > 0) || !(ratio > 0 && ratio < 1)) return kInfinity;
  const double rho = last.relative_decrease;
  if (rho >= 2) return kInfinity;
  const double along_the_step = rho > 1 ? decrease * (rho - 1) * (rho - 1) / ((2 - rho) * rho) : 0;
  const double series = std::max(decrease, decrease / rho) * std::max(1.0, ratio / (1 - ratio));
  return 2 * std::max(series, along_the_step);
}

}  // namespace dynslam
