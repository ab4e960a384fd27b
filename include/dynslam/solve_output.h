// The outputs of a solve (SPEC §4): solution.g2o, cameras.csv, motions.csv, object_poses.csv,
// convergence.csv and summary.json in one directory.
#ifndef DYNSLAM_SOLVE_OUTPUT_H_
#define DYNSLAM_SOLVE_OUTPUT_H_

#include <cstdint>
#include <optional>
#include <string>
#include <tuple>
#include <vector>

#include "dynslam/consistency.h"
#include "dynslam/covariance.h"
#include "dynslam/graph.h"
#include "dynslam/metrics.h"
#include "dynslam/pose.h"
#include "dynslam/solver.h"
#include "dynslam/status.h"
#include "dynslam/trajectory_export.h"

namespace dynslam {

struct ObjectPoseRow {
  int64_t object = 0;
  int64_t frame = 0;
  Pose pose;
};

struct SolveOutputs {
  std::string input;                    // the graph file, as given
  const Graph* solved = nullptr;        // at the optimised values
  const SolveReport* report = nullptr;
  std::optional<Metrics> metrics;       // SPEC §5, when ground truth was given
  std::vector<std::string> warnings;    // reading/building warnings to keep in the summary
  // object_poses.csv holds the L variables of an object-centric graph, or, with ground truth, the
  // poses a world-centric one composes from its motions (EstimatedObjectPoses, SPEC §4, §5); the
  // exported trajectories add the true ones.
  const GroundTruth* ground_truth = nullptr;
  // Trajectory files for evo (trajectory_export.h).
  ExportOptions export_options;
  // Marginal covariances (covariance.h), when asked for: covariances.csv and summary.json's
  // "covariance"; `covariance_kinds` is the request as given ("cameras,motions").
  const CovarianceReport* covariance = nullptr;
  std::string covariance_kinds;
  // With covariances and ground truth: summary.json's "consistency" (NEES, consistency.h).
  std::optional<Consistency> consistency;
};

// What `dynslam solve` prints once the outputs are in `out_dir`: the input and its formulation,
// the variables by role and edges by kind, the costs, steps and termination, the times, the
// warnings, the covariances' count and, with metrics, MetricsText.
std::string SolveSummaryText(const SolveOutputs& outputs, const std::string& out_dir);

// One line of SPEC §5's mean errors and their counts.
std::string MetricsText(const Metrics& metrics);

// summary.json's text (SPEC §4), without the trailing newline.
std::string SummaryJson(const SolveOutputs& outputs);

// Writes all files of SPEC §4 into `dir` (created when missing), the requested trajectory files
// and covariances.csv (`id,role,dim,` then the upper triangle row by row, SPEC §1.3's tangent
// order) when there are covariances; summary.json last.
Status WriteSolveOutputs(const std::string& dir, const SolveOutputs& outputs);

// Only the trajectory files of `outputs.export_options` (none without formats), from `outputs.solved`
// and `outputs.ground_truth`; part of WriteSolveOutputs.
Status WriteExportedTrajectories(const std::string& dir, const SolveOutputs& outputs);

// The covariances of `kinds` of `solved` (as `report` solved it) into *covariance, attached to
// *outputs with `kinds_text`, and their NEES when outputs has ground truth and no direction is
// weak. The library's error, when there is one (then nothing is attached).
Status AttachCovariances(const Graph& solved, const SolveReport& report,
                         const std::vector<CovarianceKind>& kinds, const std::string& kinds_text,
                         CovarianceReport* covariance, SolveOutputs* outputs);

// The same for covariances computed elsewhere (the GTSAM backend's, gtsam_backend.h).
void AttachComputedCovariances(const Graph& solved, CovarianceReport computed,
                               const std::string& kinds_text, CovarianceReport* covariance,
                               SolveOutputs* outputs);

// summary.json's "solver" entry for `options` as a solve used them (no auto left: ResolveAuto),
// as JSON text. Two solves whose texts are equal ran with the same options.
std::string SolverOptionsJson(const SolverOptions& options);

// What summary.json holds of a finished solve, read back (`dynslam compare --resume`).
struct SolveSummary {
  // termination, its detail, usable, initial and final cost, iterations, steps, extrapolations,
  // gauge moves and the times; not the counts by role and kind, the convergence rows, the
  // warnings or Ceres's report.
  SolveReport report;
  std::string solver_options_json;  // as SolverOptionsJson writes it
};

// Errors name the file: unreadable, not JSON, or a field missing or of the wrong type.
Expected<SolveSummary> ReadSolveSummary(const std::string& path);

}  // namespace dynslam

#endif  // DYNSLAM_SOLVE_OUTPUT_H_
