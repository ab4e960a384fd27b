// dynslam solve GRAPH --out DIR [--gt GT] [solver options]   (SPEC §4)
#include <cstdio>
#include <iostream>
#include <optional>
#include <string>

#include "cli.h"
#include "command_inputs.h"
#include "compat_flags.h"
#include "export_flags.h"
#include "commands.h"
#include "dynslam/covariance.h"
#include "dynslam/formulation.h"
#include "dynslam/graph_io.h"
#include "dynslam/ground_truth.h"
#include "dynslam/metrics.h"
#include "dynslam/solve_output.h"
#include "dynslam/solver.h"
#include "solver_flags.h"
#include "stop_signals.h"

namespace dynslam::cli {
namespace {

void PrintSummary(const SolveOutputs& outputs, const std::string& out_dir) {
  const SolveReport& r = *outputs.report;
  std::string source;
  std::printf("%s (%s)\n", outputs.input.c_str(),
              FormulationLabelOf(*outputs.solved, &source).c_str());
  std::printf("variables:");
  for (size_t i = 0; i < kAllRoles.size(); ++i) {
    if (r.variables_by_role[i] > 0) {
      std::printf(" %s %lld", RoleName(kAllRoles[i]), static_cast<long long>(r.variables_by_role[i]));
    }
  }
  if (r.unused_variables > 0) std::printf(" (unused, held constant: %lld)", static_cast<long long>(r.unused_variables));
  std::printf("\nedges:");
  for (const EdgeKind kind : kAllEdgeKinds) {
    const int64_t n = r.edges_by_kind[static_cast<int>(kind)];
    if (n > 0) std::printf(" %s %lld", EdgeKindName(kind), static_cast<long long>(n));
  }
  std::printf("\ncost: %.12g -> %.12g\n", r.initial_cost, r.final_cost);
  std::printf("iterations: %d accepted of %d steps, %d extrapolations and %d gauge moves; %s (%s)\n",
              r.iterations, r.steps, r.extrapolations, r.gauge_moves, r.termination.c_str(),
              r.termination_detail.c_str());
  std::printf("time: %.3f s total = %.3f s set-up + %.3f s minimiser (%.3f s evaluation, %.3f s linear solves)\n",
              r.time_total_s, r.time_preprocessor_s, r.time_minimizer_s, r.time_evaluation_s,
              r.time_linear_solver_s);
  for (const std::string& warning : outputs.warnings) std::printf("warning: %s\n", warning.c_str());
  for (const std::string& warning : r.warnings) std::printf("warning: %s\n", warning.c_str());
  if (const CovarianceReport* c = outputs.covariance; c != nullptr && c->weak_directions.empty()) {
    std::printf("covariances: %zu variables in %.3f s (covariances.csv)\n", c->marginals.size(),
                c->time_s);
  }
  std::printf("outputs: %s\n", out_dir.c_str());
}

// The error printed when the covariances could not be computed (the other outputs are written
// all the same).
std::string SingularMessage(const CovarianceReport& covariance, const Graph& graph) {
  const WeakDirection& first = covariance.weak_directions.front();
  return "the information matrix is singular along " +
         std::to_string(covariance.weak_directions.size()) +
         " directions (weakly determined variables; first: vertex " + std::to_string(first.id) +
         " " + DirectionName(graph, first) + "): no covariances.csv; summary.json lists them";
}

}  // namespace

int RunSolve(int argc, char** argv) {
  std::string graph_path;
  std::string out_dir;
  std::string gt_path;
  bool skip_unknown = false;
  bool ceres_report = false;
  bool repair_information = false;
  bool check_options = false;
  std::string covariance_kinds;
  ArgParser parser("dynslam solve GRAPH --out DIR [--gt GT] [options]",
                   "Solves a graph file (SPEC §1) with Ceres and writes solution.g2o, cameras.csv,\n"
                   "motions.csv, object_poses.csv, convergence.csv and summary.json (SPEC §4).\n"
                   "SIGINT (Ctrl-C) or SIGTERM stops the solve after its current step and writes\n"
                   "them for the last accepted state (termination \"interrupted\", exit 130 or\n"
                   "143); a second signal quits at once. Each file is written whole or not at\n"
                   "all; summary.json, written last, marks a complete set.");
  parser.AddExample("dynslam solve scene.oc_b.g2o --out result --gt scene.gt.txt");
  parser.AddExample("dynslam solve graph.g2o --out result --tolerances tight --covariance cameras");
  parser.AddPositional("GRAPH", &graph_path, "graph file (g2o dialect of SPEC §1)");
  parser.Group("input");
  parser.AddString("gt", &gt_path, "ground-truth file (SPEC §2) for the metrics of SPEC §5", "GT");
  parser.AddFlag("skip-unknown-tags", &skip_unknown,
                 "skip lines with tags SPEC §1 does not know (counted and reported)");
  parser.AddFlag("repair-information", &repair_information,
                 "replace an information matrix that is not positive definite by the nearest one "
                 "with eigenvalues >= 1e-9 x the largest (each repaired line is reported)");
  parser.Group("output");
  parser.AddString("out", &out_dir, "output directory (required)", "DIR");
  parser.AddFlag("ceres-report", &ceres_report,
                 "also print Ceres's full report (problem sizes, linear solver, time per phase)");
  parser.AddString("covariance", &covariance_kinds,
                   "also write covariances.csv: the marginal covariance of every variable of "
                   "these kinds at the solution (cameras, motions, object_poses, points, all; "
                   "docs/COVARIANCE.md)",
                   "KIND,...");
  parser.AddFlag("check-options", &check_options,
                 "check the other options and exit (0, or 2 naming the problem) without reading "
                 "GRAPH or writing anything (what a sweep does before it starts)");
  SolverFlags solver_flags(&parser, SolverOptionTable());
  CompatFlags compat(&parser);
  ExportFlags export_flags(&parser);
  if (std::optional<int> exit_code = parser.Parse(argc, argv, 2)) return *exit_code;
  if (ReportedProblem(compat.Finish())) return kExitBadInput;
  if (ReportedProblem(export_flags.Finish())) return kExitBadInput;
  SolverOptions options;
  if (ReportedProblem(solver_flags.Finish(&options))) return kExitBadInput;
  std::vector<CovarianceKind> kinds;
  if (!CovarianceKindsOfFlag(parser.Given("covariance"), covariance_kinds, &kinds)) {
    return kExitBadInput;
  }
  if (check_options) return kExitOk;
  if (out_dir.empty()) return ErrorExit("--out DIR is required", kExitBadInput);
  PrintProgressAfterOneSecond(&options);
  StopOnSignals(&options);

  ReadOptions read_options;
  read_options.skip_unknown_tags = skip_unknown;
  read_options.repair_information = repair_information;
  compat.Apply(&read_options);
  ReadReport read_report;
  Expected<Graph> graph = ReadGraph(graph_path, read_options, &read_report);
  if (!graph.ok()) return ErrorExit(graph.error(), kExitBadInput);
  std::optional<GroundTruth> ground_truth;
  if (!ReadGroundTruthIfGiven(gt_path, &ground_truth)) return kExitBadInput;
  SolveOutputs outputs;
  outputs.input = graph_path;
  if (const std::vector<int64_t>& lines = read_report.repaired_information_lines; !lines.empty()) {
    outputs.warnings.push_back("--repair-information: repaired the information matrices of " +
                               std::to_string(lines.size()) + " edges (first: " + graph_path +
                               ":" + std::to_string(lines.front()) + ")");
  }
  for (const auto& [tag, count] : read_report.skipped_tags) {
    outputs.warnings.push_back("skipped " + std::to_string(count) + " lines with unknown tag " + tag);
  }

  std::string source;
  compat.Apply(FormulationLabelOf(*graph, &source) == "wc", &options);
  if (compat.any()) {
    outputs.warnings.push_back("--compat " + compat.Describe() + " (SPEC §7, §3.6)");
  }
  Expected<SolveReport> report = Solve(options, &*graph);
  if (!report.ok()) {
    Error error = report.error();
    if (error.file.empty() && error.line > 0) error.file = graph_path;
    return ErrorExit(error, kExitBadInput);
  }
  outputs.solved = &*graph;
  outputs.report = &*report;
  export_flags.Apply(&outputs);
  if (ground_truth) {
    outputs.ground_truth = &*ground_truth;
    outputs.metrics = ComputeMetrics(*graph, *ground_truth);
  }
  std::optional<std::string> covariance_problem;
  CovarianceReport covariance;
  if (!kinds.empty() && report->usable) {
    const Status s =
        AttachCovariances(*graph, *report, kinds, covariance_kinds, &covariance, &outputs);
    if (!s.ok()) {
      covariance_problem = s.error().ToString();
    } else if (!covariance.weak_directions.empty()) {
      covariance_problem = SingularMessage(covariance, *graph);
    }
  }
  if (Status status = WriteSolveOutputs(out_dir, outputs); !status.ok()) {
    return ErrorExit(status.error(), kExitFailed);
  }
  PrintSummary(outputs, out_dir);
  if (ceres_report) std::printf("%s", report->ceres_report.c_str());
  if (outputs.metrics) {
    const Metrics& m = *outputs.metrics;
    std::printf("metrics (SPEC §5): camera %.4f deg %.4f m over %lld pairs; object motion %.4f deg "
                "%.4f m over %lld motions; object pose %.4f deg %.4f m over %lld pairs\n",
                m.camera.mean_rot_deg, m.camera.mean_trans_m,
                static_cast<long long>(m.camera.count), m.object_motion.mean_rot_deg,
                m.object_motion.mean_trans_m, static_cast<long long>(m.object_motion.count),
                m.object_pose.mean_rot_deg, m.object_pose.mean_trans_m,
                static_cast<long long>(m.object_pose.count));
  }
  if (!report->usable) {
    return ErrorExit("the solve failed: " + report->termination_detail, kExitFailed);
  }
  if (covariance_problem) return ErrorExit("--covariance: " + *covariance_problem, kExitFailed);
  return ExitCodeAfterStopSignal(kExitOk);
}

}  // namespace dynslam::cli
