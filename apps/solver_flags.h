// The solver options shared by `solve` and the commands that solve (SPEC §4 `solver`).
#ifndef DYNSLAM_APPS_SOLVER_FLAGS_H_
#define DYNSLAM_APPS_SOLVER_FLAGS_H_

#include <optional>
#include <string>

#include "cli.h"
#include "dynslam/solver.h"

namespace dynslam::cli {

// Declares --minimizer, --linear-solver, --sparse-backend, --threads, --max-iterations, --max-time, the
// three tolerances, --remaining-chi2, --tolerances, --fix-first and --robust on `parser`;
// Finish() turns them into options.
class SolverFlags {
 public:
  explicit SolverFlags(ArgParser* parser);
  // After a successful Parse: the options, or a usage error message.
  std::optional<std::string> Finish(SolverOptions* options) const;

 private:
  SolverOptions defaults_;
  std::string minimizer_;
  std::string linear_solver_;
  std::string sparse_backend_;
  int64_t threads_;
  int64_t max_iterations_;
  double max_time_;
  double function_tolerance_;
  double gradient_tolerance_;
  double parameter_tolerance_;
  double remaining_chi2_;
  std::string tolerances_ = "default";
  std::string extrapolation_ = defaults_.extrapolate ? "on" : "off";
  std::string gauge_moves_ = defaults_.snap_segment_gauges ? "on" : "off";
  double initial_lambda_;
  int64_t nonmonotonic_steps_;
  bool fix_first_;
  bool eliminate_object_points_;
  std::string object_point_variables_ = defaults_.world_anchored_object_points ? "world" : "object";
  std::string kinematic_residual_frame_ =
      defaults_.world_frame_kinematic_residual ? "world" : "object";
  std::string robust_;
  const ArgParser* parser_;
};

// Prints one line per linear solve to stderr once a solve has run for more than a second.
void PrintProgressAfterOneSecond(SolverOptions* options);

}  // namespace dynslam::cli

#endif  // DYNSLAM_APPS_SOLVER_FLAGS_H_
