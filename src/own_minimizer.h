// dynslam's own Levenberg–Marquardt loop over a ceres::Problem's cost functions
// (SolverOptions::minimizer = dynslam_lm; docs/SOLVER.md "dynslam's own loop").
//
// Ceres evaluates nothing here but the cost functions and manifolds it holds: the loop evaluates
// every residual block with its Jacobian once per step (at the trial point, so an accepted step
// needs no second evaluation), maps the Jacobian into each block's tangent space, accumulates
// JᵀJ and Jᵀr straight into a sparse matrix whose pattern is built once, damps it (λ·diag(JᵀJ)
// with jacobi_scaling, λ·I without, as Ceres's LM does), factorises it with CHOLMOD (its symbolic
// analysis done once per solve) and decides the step by the model's ratio with Ceres's λ rules.
// The stop is StopPolicy's, plus Ceres's function and gradient tolerances and the step limit.
#ifndef DYNSLAM_SRC_OWN_MINIMIZER_H_
#define DYNSLAM_SRC_OWN_MINIMIZER_H_

#include <string>
#include <vector>

#include <ceres/problem.h>

#include "dynslam/solver.h"
#include "src/stop_policy.h"

namespace dynslam {

struct OwnMinimizerResult {
  std::string termination;  // SPEC §4's terms
  std::string detail;
  bool usable = true;
  int linear_solves = 0;
  double evaluation_s = 0;    // residuals and Jacobians, JᵀJ included
  double linear_solve_s = 0;  // damping, factorisation and solve
};

// Minimises `problem` (its parameter blocks hold the start and receive the result: the last
// accepted state). Rows are appended to *rows, one per linear solve (SPEC §4), with times since
// `start`. Robust losses are supported as Ceres applies them (Triggs's correction).
OwnMinimizerResult MinimizeWithOwnLoop(ceres::Problem* problem, const SolverOptions& options,
                                       const StopPolicy& policy,
                                       StopPolicy::Clock::time_point start,
                                       std::vector<StepRecord>* rows);

}  // namespace dynslam

#endif  // DYNSLAM_SRC_OWN_MINIMIZER_H_
