// dynslam compare FRONTEND.g2o --out DIR [--gt GT] [--formulations wc,oc_a,…] [options]
//
// Builds every formulation from one front-end file (identical data, SPEC §3), solves each the
// same way, scores each the same way (SPEC §5) and prints the paper's Tables I–III side by side,
// then draws the convergence (Fig. 4), trajectory and error plots (scripts/plot_compare.py) and
// writes report.html (scripts/html_report.py). Without ground truth it tabulates the solves alone.
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <memory>
#include <sstream>
#include <vector>

#include "arg_parser.h"
#include "command_inputs.h"
#include "commands.h"
#include "dynslam/compare.h"
#include "dynslam/file_io.h"
#include "dynslam/graph_io.h"
#include "python_scripts.h"
#include "solver_flags.h"
#include "stop_signals.h"

namespace dynslam::cli {
namespace {

namespace fs = std::filesystem;

double SecondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// "[compare] 2/5 oc_a: convergence, 40 steps, final cost 12345.6789, 3.2 s; 10 s so far, about
// 15 s left" to stderr after each formulation (the estimate: the mean so far per formulation).
void PrintProgress(const CompareRow& r, size_t done, size_t total, double elapsed_s) {
  const double left = elapsed_s / done * (total - done);
  std::fprintf(stderr, "[compare] %zu/%zu %s: %s, %d steps, final cost %.10g, %.1f s%s; %.0f s so far",
               done, total, FormulationName(r.formulation), r.report.termination.c_str(),
               r.report.steps, r.report.final_cost, r.report.time_total_s,
               r.reused ? " (read back)" : "", elapsed_s);
  if (done < total) std::fprintf(stderr, ", about %.0f s left", left);
  std::fprintf(stderr, "\n");
}

// DIR/convergence.png, DIR/trajectory.png and, with ground truth, DIR/errors.png (scripts/
// plot_compare.py), then DIR/report.html (scripts/html_report.py).
void DrawPlotsAndReport(const std::string& out_dir, const std::vector<CompareRow>& rows,
                        const std::string& gt_path, const std::string& title, bool plots,
                        bool report) {
  std::vector<std::string> args = ReportArguments(out_dir, title, gt_path);
  args.push_back("--labels");
  for (const CompareRow& row : rows) args.push_back(FormulationName(row.formulation));
  if (plots) RunPythonScript("plot_compare.py", args, "plots");
  if (report) RunPythonScript("html_report.py", args, "report.html");
}

// Parses --formulations LIST; false after printing the problem.
bool ParseFormulationList(const std::string& list_text, std::vector<Formulation>* formulations) {
  std::stringstream list(list_text);
  for (std::string item; std::getline(list, item, ',');) {
    Formulation f;
    if (!ParseFormulation(item, &f)) {
      std::cerr << "error: --formulations: unknown formulation '" << item << "'\n";
      return false;
    }
    formulations->push_back(f);
  }
  return true;
}

// Reports progress on stderr as the library's compare goes: one line per formulation (on a
// terminal, a line that shows the running solve's steps as they go); with `verbose`, a line per
// step too.
void PrintProgressAsItGoes(CompareOptions* options, bool verbose) {
  const bool terminal = isatty(STDERR_FILENO) == 1;
  const auto started = std::chrono::steady_clock::now();
  const size_t total = options->formulations.size();
  auto done = std::make_shared<size_t>(0);
  auto running = std::make_shared<std::string>();  // "[compare] 2/5 oc_a: "
  if (verbose) {
    PrintStepLines(&options->solver, 0.0);
  } else if (terminal) {
    options->solver.on_step = [running](const StepRecord& row) {
      std::fprintf(stderr, "\r\033[K%sstep %d, cost %.10g, %.1f s", running->c_str(), row.step,
                   row.accepted ? row.trial_cost : row.cost, row.time_s);
    };
  }
  options->on_solve_start = [verbose, terminal, done, total, running](Formulation formulation,
                                                                      const Graph& built) {
    *running = "[compare] " + std::to_string(*done + 1) + "/" + std::to_string(total) + " " +
               FormulationName(formulation) + ": ";
    if (!verbose && !terminal) return;
    std::fprintf(stderr, "%s%ssolving %zu variables, %zu edges%s", terminal ? "\r\033[K" : "",
                 running->c_str(), built.NumVariables(), built.NumEdges(), verbose ? "\n" : "");
  };
  options->on_row = [started, total, done, terminal, out_dir = options->out_dir](
                        const CompareRow& row) {
    if (terminal) std::fputs("\r\033[K", stderr);
    if (row.reused) {
      const char* name = FormulationName(row.formulation);
      std::fprintf(stderr, "[compare] %s: the finished solve in %s reused (--resume)\n", name,
                   (fs::path(out_dir) / name).string().c_str());
    }
    PrintProgress(row, ++*done, total, SecondsSince(started));
  };
}

}  // namespace

int RunCompare(int argc, char** argv) {
  std::string front_end_path, gt_path, out_dir, formulation_list = FormulationNames(",");
  bool no_plots = false, no_report = false, verbose = false;
  ArgParser parser(
      "dynslam compare FRONTEND.g2o --out DIR [--gt GT] [options]",
      "Builds every formulation from one front-end file (identical data), solves each with the\n"
      "same options, scores each against ground truth, and prints the paper's Tables I-III.\n"
      "Writes DIR/tables.md, DIR/tables.csv and, per formulation, DIR/<f>/graph.g2o with the\n"
      "full solve output (SPEC §4); then, when /usr/bin/python3 has matplotlib, DIR/convergence.png,\n"
      "DIR/trajectory.png and, with --gt, DIR/errors.png (scripts/plot_compare.py), and, when it\n"
      "has Debian's python3-plotly, DIR/report.html: the scene in 3D, errors, convergence and\n"
      "tables in one self-contained page (scripts/html_report.py).\n"
      "--max-time limits each formulation's solve. SIGINT (Ctrl-C) or SIGTERM stops the current\n"
      "solve after its step, writes its outputs and the tables of what finished (no plots), and\n"
      "exits 130 or 143; a second signal quits at once.");
  parser.AddExample("dynslam compare scene.g2o --gt scene.gt.txt --out cmp");
  parser.AddExample("dynslam compare scene.g2o --gt scene.gt.txt --out cmp --formulations wc,oc_b --resume");
  parser.AddPositional("FRONTEND.g2o", &front_end_path, "front-end graph file");
  parser.Group("input");
  parser.AddString("gt", &gt_path,
                   "ground-truth file (SPEC §2): the errors of Tables I-III and each segment's "
                   "first object pose; without it, only the solves are tabulated and object poses "
                   "start by the centroid rule (SPEC §3.3)",
                   "GT");
  parser.AddString("formulations", &formulation_list,
                   "comma-separated subset of " + FormulationNames(","), "LIST");
  parser.AddFlag("no-plots", &no_plots, "do not draw DIR/convergence.png, DIR/trajectory.png and DIR/errors.png");
  parser.AddFlag("no-report", &no_report, "do not write DIR/report.html");
  parser.AddFlag("verbose", &verbose,
                 "a line per linear solve of each formulation (else one line per formulation)");
  std::string start = "frontend";
  parser.AddChoice("start", &start, {"frontend", "wc"},
                   "where oc_a, oc_b and oc_c start: the front end's estimates, or wc's solution "
                   "(SPEC §3.5; wc must come first in --formulations; their steps and times then "
                   "add to wc's)");
  bool resume = false;
  std::string covariance_kinds;
  parser.Group("output");
  parser.AddString("out", &out_dir, "output directory, required", "DIR");
  parser.AddString("covariance", &covariance_kinds,
                   "also each formulation's marginal covariances of these kinds "
                   "(<f>/covariances.csv, as `solve --covariance`) and, with --gt, a NEES table "
                   "of how honest they are (docs/COVARIANCE.md); not with --resume",
                   "KIND,...");
  parser.AddFlag("resume", &resume,
                 "reuse each formulation's finished solve already in DIR (the same built graph "
                 "and solver options, ended by convergence or the step limit) instead of solving "
                 "it again: a long compare that was stopped goes on from the next formulation");
  std::string backend = "ceres";
  parser.AddString("backend", &backend,
                   "ceres, or gtsam[:PROFILE]: every formulation solved by GTSAM 4.2's optimisers "
                   "(as solve --backend; with --compat dsc the released code's optimisation end "
                   "to end, docs/GTSAM_BACKEND.md)",
                   "NAME");
  BuildFlags build_flags(&parser, BuildOptionTable());
  SolverFlags solver_flags(&parser, SolverOptionTable());
  CompatFlags compat_flags(&parser, CompatOptionTable());
  ExportFlags export_flags(&parser, ExportOptionTable());
  if (std::optional<int> exit_code = parser.Parse(argc, argv, 2)) return *exit_code;
  CompareOptions options;
  std::optional<GtsamProfile> gtsam;
  if (!BackendOfFlag(backend, &gtsam)) return kExitBadInput;
  if (gtsam) {
    options.solve = [profile = *gtsam](const SolverOptions& solver, Graph* graph) {
      return SolveWithGtsam(profile, solver, graph);
    };
  }
  if (ReportedProblem(export_flags.Finish(&options.export_options))) return kExitBadInput;
  if (ReportedProblem(compat_flags.Finish(&options.compat))) return kExitBadInput;
  if (out_dir.empty()) return ErrorExit("--out DIR is required", kExitBadInput);
  options.formulations.clear();
  if (!ParseFormulationList(formulation_list, &options.formulations)) return kExitBadInput;
  options.covariance_kinds = covariance_kinds;
  options.resume = resume;
  if (!CovarianceKindsOfFlag(parser.Given("covariance"), covariance_kinds, &options.covariance)) {
    return kExitBadInput;
  }
  if (!options.covariance.empty() && options.resume) {
    return ErrorExit("--covariance and --resume: a solve read back has no covariances; give one "
                     "of them",
                     kExitBadInput);
  }
  options.start_from_world_centric = start == "wc";
  if (options.start_from_world_centric &&
      (options.formulations.empty() || options.formulations[0] != Formulation::kWorldCentric)) {
    return ErrorExit("--start wc: wc must come first in --formulations", kExitBadInput);
  }
  if (ReportedProblem(build_flags.Finish(&options.build))) return kExitBadInput;
  if (ReportedProblem(solver_flags.Finish(&options.solver))) return kExitBadInput;
  StopOnSignals(&options.solver);
  options.out_dir = out_dir;
  options.front_end_name = fs::path(front_end_path).filename().string();
  PrintProgressAsItGoes(&options, verbose);

  ReadOptions read_options;
  ApplyCompat(options.compat, &read_options);
  Expected<Graph> front_end = ReadGraph(front_end_path, read_options);
  if (!front_end.ok()) return ErrorExit(front_end.error(), kExitBadInput);
  std::optional<GroundTruth> gt;
  if (!ReadGroundTruthIfGiven(gt_path, &gt)) return kExitBadInput;
  // The tables mark a finished compare: a run that fails or is killed leaves none behind.
  for (const char* name : {"tables.md", "tables.csv"}) {
    if (Status s = RemoveIfPresent((fs::path(out_dir) / name).string()); !s.ok()) {
      return ErrorExit(s.error(), kExitFailed);
    }
  }
  Expected<CompareRun> run = CompareFormulations(*front_end, gt ? &*gt : nullptr, options);
  if (!run.ok()) return ErrorExit(run.error(), kExitFailed);
  if (run->stopped) {
    std::fprintf(stderr, "[compare] stopped by a signal after %s: tables for what finished\n",
                 FormulationName(run->rows.back().formulation));
  }
  const CompareTables tables = TablesOf(*run, options);
  for (const auto& [name, text] :
       {std::pair{"tables.csv", &tables.csv}, std::pair{"tables.md", &tables.markdown}}) {
    if (Status s = WriteFileAtomically((fs::path(out_dir) / name).string(), *text); !s.ok()) {
      return ErrorExit(s.error(), kExitFailed);
    }
  }
  std::fputs(tables.markdown.c_str(), stdout);
  if ((!no_plots || !no_report) && StopSignal() == 0) {
    DrawPlotsAndReport(out_dir, run->rows, gt_path, fs::path(front_end_path).filename().string(),
                       !no_plots, !no_report);
  }
  return ExitCodeAfterStopSignal(kExitOk);
}

}  // namespace dynslam::cli
