// dynslam solve GRAPH --out DIR [--gt GT] [solver options]   (SPEC §4)
#include <cstdio>
#include <filesystem>
#include <optional>
#include <string>

#include "arg_parser.h"
#include "command_inputs.h"
#include "commands.h"
#include "dynslam/covariance.h"
#include "dynslam/formulation.h"
#include "dynslam/graph_io.h"
#include "dynslam/gtsam_backend.h"
#include "dynslam/ground_truth.h"
#include "dynslam/metrics.h"
#include "dynslam/solve_output.h"
#include "dynslam/solver.h"
#include "python_scripts.h"
#include "solver_flags.h"
#include "stop_signals.h"

namespace dynslam::cli {
namespace {

// The error printed when the covariances could not be computed (the other outputs are written
// all the same).
std::string SingularMessage(const CovarianceReport& covariance, const Graph& graph) {
  const WeakDirection& first = covariance.weak_directions.front();
  return "the information matrix is singular along " +
         std::to_string(covariance.weak_directions.size()) +
         " directions (weakly determined variables; first: vertex " + std::to_string(first.id) +
         " " + DirectionName(graph, first) + "): no covariances.csv; summary.json lists them";
}

// The GTSAM backend's covariances of `kinds`, attached to *outputs like AttachCovariances.
Status AttachGtsamCovariances(const GtsamProfile& profile, const SolverOptions& options,
                              const Graph& graph, const std::vector<CovarianceKind>& kinds,
                              const std::string& kinds_text, CovarianceReport* covariance,
                              SolveOutputs* outputs) {
  Expected<CovarianceReport> computed =
      GtsamCovariances(graph, profile, options, VerticesOfKinds(graph, kinds));
  if (!computed.ok()) return computed.error();
  AttachComputedCovariances(graph, std::move(computed).value(), kinds_text, covariance, outputs);
  return Status::Ok();
}

}  // namespace

int RunSolve(int argc, char** argv) {
  std::string graph_path;
  std::string out_dir;
  std::string gt_path;
  bool skip_unknown = false;
  bool ceres_report = false;
  bool html_report = false;
  bool repair_information = false;
  bool check_options = false;
  std::string covariance_kinds;
  std::string backend = "ceres";
  ArgParser parser("dynslam solve GRAPH --out DIR [--gt GT] [options]",
                   "Solves a graph file (SPEC §1) with Ceres (or GTSAM: --backend) and writes\n"
                   "solution.g2o, cameras.csv, motions.csv, object_poses.csv, convergence.csv\n"
                   "and summary.json (SPEC §4).\n"
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
  parser.AddString("backend", &backend,
                   "ceres, or gtsam[:PROFILE]: GTSAM 4.2's optimisers on the same file "
                   "(released, the default, tight, tight_exact, dogleg, gn; "
                   "docs/GTSAM_BACKEND.md); gtsam needs a build with it (scripts/build_gtsam)",
                   "NAME");
  parser.Group("output");
  parser.AddString("out", &out_dir, "output directory (required)", "DIR");
  parser.AddFlag("ceres-report", &ceres_report,
                 "also print Ceres's full report (problem sizes, linear solver, time per phase)");
  parser.AddFlag("report", &html_report,
                 "also write DIR/report.html: the solve's scene in 3D (against --gt), its errors "
                 "and convergence in one self-contained page (scripts/html_report.py; Debian's "
                 "python3-plotly)");
  parser.AddString("covariance", &covariance_kinds,
                   "also write covariances.csv: the marginal covariance of every variable of "
                   "these kinds at the solution (cameras, motions, object_poses, points, all; "
                   "docs/COVARIANCE.md)",
                   "KIND,...");
  parser.AddFlag("check-options", &check_options,
                 "check the other options and exit (0, or 2 naming the problem) without reading "
                 "GRAPH or writing anything (what a sweep does before it starts)");
  SolverFlags solver_flags(&parser, SolverOptionTable());
  CompatFlags compat_flags(&parser, CompatOptionTable());
  ExportFlags export_flags(&parser, ExportOptionTable());
  if (std::optional<int> exit_code = parser.Parse(argc, argv, 2)) return *exit_code;
  Compat compat;
  if (ReportedProblem(compat_flags.Finish(&compat))) return kExitBadInput;
  ExportOptions exported;
  if (ReportedProblem(export_flags.Finish(&exported))) return kExitBadInput;
  SolverOptions options;
  if (ReportedProblem(solver_flags.Finish(&options))) return kExitBadInput;
  std::vector<CovarianceKind> kinds;
  if (!CovarianceKindsOfFlag(parser.Given("covariance"), covariance_kinds, &kinds)) {
    return kExitBadInput;
  }
  std::optional<GtsamProfile> gtsam;
  if (!BackendOfFlag(backend, &gtsam)) return kExitBadInput;
  if (check_options) return kExitOk;
  if (out_dir.empty()) return ErrorExit("--out DIR is required", kExitBadInput);
  PrintStepLines(&options, 1.0);
  StopOnSignals(&options);

  ReadOptions read_options;
  read_options.skip_unknown_tags = skip_unknown;
  read_options.repair_information = repair_information;
  ApplyCompat(compat, &read_options);
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

  ApplyCompat(compat, FormulationLabelOf(*graph) == "wc", &options);
  if (const std::string items = CompatText(compat); items != "none") {
    outputs.warnings.push_back("--compat " + items + " (SPEC §7, §3.6)");
  }
  Expected<SolveReport> report =
      gtsam ? SolveWithGtsam(*gtsam, options, &*graph) : Solve(options, &*graph);
  if (!report.ok()) {
    Error error = report.error();
    if (error.file.empty() && error.line > 0) error.file = graph_path;
    return ErrorExit(error, kExitBadInput);
  }
  outputs.solved = &*graph;
  outputs.report = &*report;
  outputs.export_options = exported;
  if (ground_truth) {
    outputs.ground_truth = &*ground_truth;
    outputs.metrics = ComputeMetrics(*graph, *ground_truth);
  }
  std::optional<std::string> covariance_problem;
  CovarianceReport covariance;
  if (!kinds.empty() && report->usable) {
    const Status s = gtsam ? AttachGtsamCovariances(*gtsam, options, *graph, kinds,
                                                    covariance_kinds, &covariance, &outputs)
                           : AttachCovariances(*graph, *report, kinds, covariance_kinds,
                                               &covariance, &outputs);
    if (!s.ok()) {
      covariance_problem = s.error().ToString();
    } else if (!covariance.weak_directions.empty()) {
      covariance_problem = SingularMessage(covariance, *graph);
    }
  }
  if (Status status = WriteSolveOutputs(out_dir, outputs); !status.ok()) {
    return ErrorExit(status.error(), kExitFailed);
  }
  std::fputs(SolveSummaryText(outputs, out_dir).c_str(), stdout);
  if (ceres_report) std::fputs(report->ceres_report.c_str(), stdout);
  if (html_report && report->usable) {
    const std::string title = std::filesystem::path(graph_path).filename().string();
    RunPythonScript("html_report.py", ReportArguments(out_dir, title, gt_path), "report.html");
  }
  if (!report->usable) {
    return ErrorExit("the solve failed: " + report->termination_detail, kExitFailed);
  }
  if (covariance_problem) return ErrorExit("--covariance: " + *covariance_problem, kExitFailed);
  return ExitCodeAfterStopSignal(kExitOk);
}

}  // namespace dynslam::cli
