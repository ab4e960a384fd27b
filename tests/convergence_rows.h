// The convergence rows of a solve against SPEC §4 (a test helper): numbering, costs that chain
// from one accepted row to the next, extrapolations and gauge moves marked by lambda 0, and the
// counts of SolveReport. Expects a monotonic solve (no non-monotonic steps).
#ifndef DYNSLAM_TESTS_CONVERGENCE_ROWS_H_
#define DYNSLAM_TESTS_CONVERGENCE_ROWS_H_

#include <algorithm>
#include <cmath>
#include <string>

#include <gtest/gtest.h>

#include "dynslam/solver.h"

namespace dynslam::testing {

inline void ExpectRowsFollowSpecSection4(const SolveReport& report) {
  // report.initial_cost and final_cost are summed per edge kind, Ceres's costs in one sum: they
  // agree to rounding. From one row to the next the cost is passed on as it is.
  auto near = [](double cost) { return 1e-12 * std::max(std::abs(cost), 1.0); };
  int accepted = 0, extrapolations = 0, gauge_moves = 0;
  double cost = report.initial_cost;
  for (size_t i = 0; i < report.convergence.size(); ++i) {
    const StepRecord& row = report.convergence[i];
    SCOPED_TRACE("row " + std::to_string(i + 1));
    EXPECT_EQ(row.step, static_cast<int>(i) + 1);
    EXPECT_EQ(row.iteration, accepted + 1);
    if (i == 0) {
      EXPECT_NEAR(row.cost, cost, near(cost));
    } else {
      EXPECT_DOUBLE_EQ(row.cost, cost);
    }
    if (row.extrapolation || row.gauge_move) {
      EXPECT_FALSE(row.extrapolation && row.gauge_move);
      EXPECT_EQ(row.lambda, 0);
      EXPECT_TRUE(row.accepted);
      extrapolations += row.extrapolation;
      gauge_moves += row.gauge_move;
    } else {
      EXPECT_GT(row.lambda, 0);
    }
    if (row.accepted) {
      EXPECT_LT(row.trial_cost, row.cost);
      cost = row.trial_cost;
      ++accepted;
    }
  }
  EXPECT_EQ(accepted, report.iterations);
  EXPECT_EQ(extrapolations, report.extrapolations);
  EXPECT_EQ(gauge_moves, report.gauge_moves);
  EXPECT_EQ(static_cast<int>(report.convergence.size()),
            report.steps + report.extrapolations + report.gauge_moves);
  EXPECT_NEAR(report.final_cost, cost, near(cost)) << "the solution is the last accepted state";
}

}  // namespace dynslam::testing

#endif  // DYNSLAM_TESTS_CONVERGENCE_ROWS_H_
