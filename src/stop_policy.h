// When a solve stops (docs/SOLVER.md "When a solve stops"): one named check per criterion
// (stop_policy.cc), asked after every step in the order StopPolicy::Check lists them. Ceres's own
// tolerances and step limit stop Ceres itself; the step limit across restarts is StepLimit. The
// solver's loop
// (RunSegments, solver.cc) asks the policy and carries out what it says: stop, or, before a
// remaining-χ² stop, probe with an extrapolation first and stop only if that gains at most the
// rule's χ² (WithinRemainingChi2).
#ifndef DYNSLAM_SRC_STOP_POLICY_H_
#define DYNSLAM_SRC_STOP_POLICY_H_

#include <chrono>
#include <optional>
#include <string>
#include <vector>

#include "dynslam/solver.h"

namespace dynslam {

// The released code's GTSAM LM (SPEC §6 `released`, §7 item 7): the decrease (relative and
// absolute) of an accepted step at which it stops, and the λ at which it gives up.
inline constexpr double kReleasedTolerance = 1e-5;
inline constexpr double kReleasedMaxLambda = 1e5;

// A convergence row that is a linear solve, not an extrapolation or a gauge move (SPEC §4).
inline bool IsLinearSolve(const StepRecord& row) { return !row.extrapolation && !row.gauge_move; }

struct StopDecision {
  std::string termination;  // "interrupted", "time_limit", "convergence", "no_convergence"
  std::string detail;
  // The remaining-χ² rule: stop only after an extrapolation along the last two steps has
  // gained at most its χ² (when the solve can still extrapolate).
  bool after_probe = false;
};

class StopPolicy {
 public:
  using Clock = std::chrono::steady_clock;
  // `start`: where options.max_time counts from.
  StopPolicy(const SolverOptions& options, Clock::time_point start)
      : options_(options), start_(start) {}

  // After the step that produced the last of `rows` (before the first step when it is empty);
  // `accepted` counts the accepted rows.
  std::optional<StopDecision> Check(const std::vector<StepRecord>& rows, int accepted) const;

  // The remaining-χ² rule's test, for the estimate after a step and for what a probing
  // extrapolation gained: on, and `chi2` at most its bound.
  bool WithinRemainingChi2(double chi2) const;
  // The decision once a probe gained `gained_chi2`, or nothing: the solve goes on.
  std::optional<StopDecision> AfterProbe(const StopDecision& probe, double gained_chi2) const;
  StopDecision StepLimit() const;

  // The χ² still to gain after the last of `rows` (or after the first `count` of them), +inf
  // when the rows cannot tell.
  static double EstimatedRemainingChi2(const std::vector<StepRecord>& rows);
  static double EstimatedRemainingChi2(const std::vector<StepRecord>& rows, size_t count);

 private:
  const SolverOptions& options_;
  const Clock::time_point start_;
};

}  // namespace dynslam

#endif  // DYNSLAM_SRC_STOP_POLICY_H_
