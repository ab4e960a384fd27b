// dynslam compare FRONTEND.g2o --out DIR [--gt GT] [--formulations wc,oc_a,…] [options]
//
// Builds every formulation from one front-end file (identical data, SPEC §3), solves each the
// same way, scores each the same way (SPEC §5) and prints the paper's Tables I–III side by side,
// then draws the convergence (Fig. 4) and trajectory plots with scripts/plot_*.py. Without ground
// truth it tabulates the solves alone.
#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <set>
#include <sstream>
#include <vector>

#include "solver_flags.h"
#include "cli.h"
#include "command_inputs.h"
#include "compat_flags.h"
#include "export_flags.h"
#include "commands.h"
#include "dynslam/file_io.h"
#include "dynslam/formulation.h"
#include "dynslam/graph_io.h"
#include "dynslam/ground_truth.h"
#include "dynslam/metrics.h"
#include "dynslam/solve_output.h"
#include "dynslam/solver.h"
#include "solver_flags.h"
#include "src/number_text.h"
#include "stop_signals.h"

// The repository's scripts/ folder, set by apps/CMakeLists.txt; the environment variable of the
// same name overrides it at run time (a moved or installed tree).
#ifndef DYNSLAM_SCRIPTS_DIR
#define DYNSLAM_SCRIPTS_DIR ""
#endif

namespace dynslam::cli {
namespace {

namespace fs = std::filesystem;

struct Row {
  Formulation formulation;
  int64_t variables = 0;
  int64_t edges = 0;
  SolveReport report;
  std::optional<Metrics> metrics;  // with ground truth
  bool reused = false;             // --resume: read back from an earlier run's outputs
  std::optional<Consistency> consistency;  // --covariance with ground truth
};

// The row of `formulation` as built: its sizes, before any solve.
Row BuiltRow(Formulation formulation, const Graph& built) {
  Row row;
  row.formulation = formulation;
  row.variables = static_cast<int64_t>(built.NumVariables());
  row.edges = static_cast<int64_t>(built.NumEdges());
  return row;
}

std::string Fixed(double value, int digits) {
  char buffer[32];
  std::snprintf(buffer, sizeof(buffer), "%.*f", digits, value);
  return buffer;
}

double SecondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// "[compare] 2/5 oc_a: convergence, 40 steps, final cost 12345.6789, 3.2 s; 10 s so far, about
// 15 s left" to stderr after each formulation (the estimate: the mean so far per formulation).
void PrintProgress(const std::vector<Row>& rows, size_t total, double elapsed_s) {
  const Row& r = rows.back();
  const double left = elapsed_s / rows.size() * (total - rows.size());
  std::fprintf(stderr, "[compare] %zu/%zu %s: %s, %d steps, final cost %.10g, %.1f s%s; %.0f s so far",
               rows.size(), total, FormulationName(r.formulation), r.report.termination.c_str(),
               r.report.steps, r.report.final_cost, r.report.time_total_s,
               r.reused ? " (read back)" : "", elapsed_s);
  if (rows.size() < total) std::fprintf(stderr, ", about %.0f s left", left);
  std::fprintf(stderr, "\n");
}

// "37", or "37 (interrupted)" for a solve a signal or --max-time stopped.
std::string Iterations(const SolveReport& report) {
  const bool stopped_early =
      report.termination == "interrupted" || report.termination == "time_limit";
  return std::to_string(report.iterations) + (stopped_early ? " (" + report.termination + ")" : "");
}

// Without ground truth: what every formulation's solve did, the accuracy columns marked.
void TablesWithoutGroundTruth(const std::vector<Row>& rows, std::string* markdown,
                              std::string* csv) {
  std::ostringstream md, out;
  out << "table,formulation,object,quantity,value\n";
  md << "### Table I without ground truth: problem size and solve\n\n"
     << "No ground truth (--gt): each segment's first object pose started at the centroid of its "
        "points with identity rotation (SPEC §3.3); the camera, object motion and object pose "
        "errors (Tables I-III) need ground truth.\n\n"
     << "| formulation | variables | edges | steps | iterations | final cost | solve time (s) | camera E_r (deg) | camera E_t (m) |\n"
     << "|---|---|---|---|---|---|---|---|---|\n";
  for (const Row& r : rows) {
    const char* f = FormulationName(r.formulation);
    char cost[32];
    std::snprintf(cost, sizeof(cost), "%.10g", r.report.final_cost);
    md << "| " << f << " | " << r.variables << " | " << r.edges << " | " << r.report.steps << " | "
       << Iterations(r.report) << " | " << cost << " | " << Fixed(r.report.time_total_s, 3)
       << " | needs --gt | needs --gt |\n";
    out << "I," << f << ",,variables," << r.variables << "\n"
        << "I," << f << ",,edges," << r.edges << "\n"
        << "I," << f << ",,steps," << r.report.steps << "\n"
        << "I," << f << ",,iterations," << r.report.iterations << "\n"
        << "I," << f << ",,final_cost," << cost << "\n"
        << "I," << f << ",,termination," << r.report.termination << "\n"
        << "I," << f << ",,solve_time_s," << r.report.time_total_s << "\n";
  }
  *markdown = md.str();
  *csv = out.str();
}

// With --covariance: each formulation's mean NEES against its 95 % band (consistency.h), rows of
// table "NEES" in the CSV. Nothing without covariances.
void NeesTable(const std::vector<Row>& rows, std::ostringstream* md, std::ostringstream* csv) {
  if (std::none_of(rows.begin(), rows.end(), [](const Row& r) { return r.consistency; })) return;
  *md << "### NEES: how honest each covariance is (expected 6; docs/COVARIANCE.md)\n\n"
      << "| formulation | camera | band | object motion | band | object pose | band |\n"
      << "|---|---|---|---|---|---|---|\n";
  for (const Row& r : rows) {
    const char* f = FormulationName(r.formulation);
    *md << "| " << f;
    for (const NeesMean Consistency::*family :
         {&Consistency::camera, &Consistency::object_motion, &Consistency::object_pose}) {
      if (!r.consistency || (*r.consistency.*family).count == 0) {
        *md << " | – | –";
        continue;
      }
      const NeesMean& n = *r.consistency.*family;
      *md << " | " << Fixed(n.mean, 2) << " | " << Fixed(n.band_low, 2) << "–"
          << Fixed(n.band_high, 2);
    }
    *md << " |\n";
    if (r.consistency) {
      *csv << "NEES," << f << ",,camera," << r.consistency->camera.mean << "\n"
           << "NEES," << f << ",,object_motion," << r.consistency->object_motion.mean << "\n"
           << "NEES," << f << ",,object_pose," << r.consistency->object_pose.mean << "\n";
    }
  }
  *md << "\n";
}

// Tables I–III as Markdown, and the same numbers as CSV (table,formulation,object,quantity,value).
// Every row has metrics.
void Tables(const std::vector<Row>& rows, std::string* markdown, std::string* csv) {
  std::ostringstream md, out;
  out << "table,formulation,object,quantity,value\n";
  md << "### Table I: camera relative pose error, problem size, solve time\n\n"
     << "| formulation | camera E_r (deg) | camera E_t (m) | pairs | variables | edges | iterations | solve time (s) |\n"
     << "|---|---|---|---|---|---|---|---|\n";
  for (const Row& r : rows) {
    const char* f = FormulationName(r.formulation);
    const ErrorMean& camera = r.metrics->camera;
    md << "| " << f << " | " << Fixed(camera.mean_rot_deg, 4) << " | "
       << Fixed(camera.mean_trans_m, 4) << " | " << camera.count << " | " << r.variables << " | "
       << r.edges << " | " << Iterations(r.report) << " | " << Fixed(r.report.time_total_s, 3)
       << " |\n";
    out << "I," << f << ",,camera_rot_deg," << camera.mean_rot_deg << "\n"
        << "I," << f << ",,camera_trans_m," << camera.mean_trans_m << "\n"
        << "I," << f << ",,variables," << r.variables << "\n"
        << "I," << f << ",,edges," << r.edges << "\n"
        << "I," << f << ",,steps," << r.report.steps << "\n"
        << "I," << f << ",,iterations," << r.report.iterations << "\n"
        << "I," << f << ",,final_cost," << NumberText(r.report.final_cost) << "\n"
        << "I," << f << ",,termination," << r.report.termination << "\n"
        << "I," << f << ",,solve_time_s," << r.report.time_total_s << "\n";
  }
  auto object_table = [&](const char* title, const char* id,
                          const ObjectErrors Metrics::*family) {
    std::set<int64_t> objects;
    for (const Row& r : rows) {
      for (const auto& [object, mean] : (*r.metrics.*family).per_object) objects.insert(object);
    }
    md << "\n### " << title << "\n\n| object |";
    for (const Row& r : rows) md << " " << FormulationName(r.formulation) << " E_r (deg) | E_t (m) |";
    md << "\n|---|";
    for (size_t i = 0; i < rows.size(); ++i) md << "---|---|";
    md << "\n";
    for (const int64_t object : objects) {
      md << "| " << object << " |";
      for (const Row& r : rows) {
        const auto& per_object = (*r.metrics.*family).per_object;
        auto it = per_object.find(object);
        if (it == per_object.end()) {
          md << " – | – |";
          continue;
        }
        md << " " << Fixed(it->second.mean_rot_deg, 4) << " | " << Fixed(it->second.mean_trans_m, 4) << " |";
        out << id << "," << FormulationName(r.formulation) << "," << object << ",rot_deg,"
            << it->second.mean_rot_deg << "\n"
            << id << "," << FormulationName(r.formulation) << "," << object << ",trans_m,"
            << it->second.mean_trans_m << "\n";
      }
      md << "\n";
    }
    md << "| mean |";
    for (const Row& r : rows) {
      md << " " << Fixed((*r.metrics.*family).mean_rot_deg, 4) << " | "
         << Fixed((*r.metrics.*family).mean_trans_m, 4) << " |";
      out << id << "," << FormulationName(r.formulation) << ",mean,rot_deg,"
          << (*r.metrics.*family).mean_rot_deg << "\n"
          << id << "," << FormulationName(r.formulation) << ",mean,trans_m,"
          << (*r.metrics.*family).mean_trans_m << "\n";
    }
    md << "\n";
  };
  object_table("Table II: object motion error", "II", &Metrics::object_motion);
  object_table("Table III: object pose error", "III", &Metrics::object_pose);
  NeesTable(rows, &md, &out);
  *markdown = md.str();
  *csv = out.str();
}

// Runs args[0] (an absolute path, no shell: paths may hold spaces or quotes) with stdin from
// /dev/null and stdout and stderr captured in *output. Returns its exit code, or -1 when it could
// not be started or did not exit normally. posix_spawn, not fork: the child does not copy the
// page tables of a process that may hold a whole sequence's solve (glibc spawns with vfork
// semantics and reports a failed exec as an error here).
int RunCaptured(const std::vector<std::string>& args, std::string* output) {
  std::vector<char*> argv;
  for (const std::string& arg : args) argv.push_back(const_cast<char*>(arg.c_str()));
  argv.push_back(nullptr);
  int pipe_fds[2];
  if (pipe2(pipe_fds, O_CLOEXEC) != 0) return -1;
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, pipe_fds[1], STDOUT_FILENO);
  posix_spawn_file_actions_adddup2(&actions, pipe_fds[1], STDERR_FILENO);
  posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
  std::fflush(stdout);
  std::fflush(stderr);
  pid_t pid = -1;
  const int spawned = posix_spawn(&pid, argv[0], &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (spawned != 0) {
    close(pipe_fds[0]);
    close(pipe_fds[1]);
    return -1;
  }
  close(pipe_fds[1]);
  char buffer[4096];
  for (;;) {
    const ssize_t n = read(pipe_fds[0], buffer, sizeof(buffer));
    if (n > 0) {
      output->append(buffer, static_cast<size_t>(n));
    } else if (n == 0 || errno != EINTR) {
      break;
    }
  }
  close(pipe_fds[0]);
  int status = 0;
  while (waitpid(pid, &status, 0) < 0) {
    if (errno != EINTR) return -1;
  }
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

// The last non-blank line of a script's output: the error message of a failed script.
std::string LastLine(const std::string& text) {
  const size_t end = text.find_last_not_of(" \t\r\n");
  if (end == std::string::npos) return "no message";
  const size_t newline = text.find_last_of('\n', end);
  const size_t start = newline == std::string::npos ? 0 : newline + 1;
  return text.substr(start, end + 1 - start);
}

// DIR/convergence.png (every formulation's convergence.csv on one figure) and DIR/trajectory.png
// (every formulation's cameras and object poses with the ground truth). Plots are a convenience:
// a missing python3 or matplotlib, or a failing script, is one warning line, not a failure.
void DrawPlots(const std::string& out_dir, const std::vector<Row>& rows, const std::string& gt_path,
               const std::string& title) {
  const std::string python = "/usr/bin/python3";
  if (access(python.c_str(), X_OK) != 0) {
    std::cerr << "warning: no " << python << ", so no convergence.png or trajectory.png\n";
    return;
  }
  std::string output;
  if (RunCaptured({python, "-c", "import matplotlib"}, &output) != 0) {
    std::cerr << "warning: " << python << " cannot import matplotlib (Debian: python3-matplotlib), "
              << "so no convergence.png or trajectory.png\n";
    return;
  }
  const char* from_environment = std::getenv("DYNSLAM_SCRIPTS_DIR");
  const fs::path scripts = from_environment && *from_environment ? from_environment
                                                                 : DYNSLAM_SCRIPTS_DIR;
  std::error_code ec;
  const fs::path out = fs::absolute(out_dir, ec);  // absolute: no path can look like an option
  std::vector<std::string> labels;
  for (const Row& row : rows) labels.push_back(FormulationName(row.formulation));

  auto draw = [&](const char* script, const char* image, const char* file_in_folder,
                  std::vector<std::string> extra) {
    const fs::path script_path = scripts / script;
    if (!fs::is_regular_file(script_path, ec)) {
      std::cerr << "warning: no " << script_path.string() << " (DYNSLAM_SCRIPTS_DIR), so no "
                << image << "\n";
      return;
    }
    std::vector<std::string> args = {python, script_path.string()};
    for (const std::string& label : labels) {
      const fs::path folder = out / label;
      args.push_back((*file_in_folder ? folder / file_in_folder : folder).string());
    }
    args.push_back("--labels");
    args.insert(args.end(), labels.begin(), labels.end());
    args.insert(args.end(), extra.begin(), extra.end());
    args.push_back("--out");
    args.push_back((out / image).string());
    output.clear();
    const int code = RunCaptured(args, &output);
    if (code != 0) {
      std::cerr << "warning: " << script << " failed (exit " << code << "), so no " << image
                << ": " << LastLine(output) << "\n";
      return;
    }
    std::fprintf(stderr, "[compare] wrote %s\n", (out / image).string().c_str());
  };
  draw("plot_convergence.py", "convergence.png", "convergence.csv",
       {"--title", title + ": convergence (Fig. 4)"});
  std::vector<std::string> trajectory_args = {"--title", title + ": trajectories (top view, x-z)"};
  if (!gt_path.empty()) {  // drawn dashed
    trajectory_args.insert(trajectory_args.end(), {"--gt", fs::absolute(gt_path, ec).string()});
  }
  draw("plot_trajectory.py", "trajectory.png", "", trajectory_args);
}

// What every formulation of one compare run is built, solved and written with.
struct RunSettings {
  BuildOptions build_options;
  SolverOptions solver_options;
  const CompatFlags* compat = nullptr;
  const ExportFlags* export_flags = nullptr;
  const GroundTruth* gt = nullptr;
  fs::path out_dir;
  std::string front_end_name;
  bool resume = false;
  std::string covariance_kinds;  // --covariance, as given
  std::vector<CovarianceKind> covariance;
};

// True when the file at `path` holds exactly `text`, read a megabyte at a time (a paper-scale
// graph is hundreds of megabytes: no second copy of it in memory).
bool FileHolds(const fs::path& path, const std::string& text) {
  std::ifstream in(path, std::ios::binary);
  std::vector<char> chunk(1 << 20);
  size_t offset = 0;
  while (in) {
    in.read(chunk.data(), static_cast<std::streamsize>(chunk.size()));
    const size_t n = static_cast<size_t>(in.gcount());
    if (n > text.size() - offset || std::memcmp(chunk.data(), text.data() + offset, n) != 0) {
      return false;
    }
    offset += n;
  }
  return in.eof() && !in.bad() && offset == text.size();
}

// --resume: the solve already in `dir`, read back when it is the one this run would do and it
// finished — graph.g2o byte-equal to `built`, summary.json (written last, SPEC §4) ending by
// convergence or the step limit with the same solver options. The row comes from summary.json,
// the metrics from solution.g2o. Anything else (missing, interrupted, other graph or options,
// unreadable): nothing, and the formulation is solved again. --export's files are written
// again from the solution read back.
std::optional<Row> FinishedSolveIn(const fs::path& dir, Formulation formulation, const Graph& built,
                                   const SolverOptions& options, const RunSettings& run,
                                   Graph* solved_out) {
  Expected<SolveSummary> summary = ReadSolveSummary((dir / "summary.json").string());
  if (!summary.ok()) return std::nullopt;
  const SolveReport& report = summary->report;
  if (report.termination != "convergence" && report.termination != "no_convergence") {
    return std::nullopt;
  }
  if (summary->solver_options_json != SolverOptionsJson(ResolveAuto(options, built))) {
    return std::nullopt;
  }
  if (!FileHolds(dir / "graph.g2o", GraphText(built))) return std::nullopt;
  Expected<Graph> solved = ReadGraph((dir / "solution.g2o").string());
  if (!solved.ok()) return std::nullopt;
  Row row = BuiltRow(formulation, built);
  row.report = report;
  row.reused = true;
  if (run.gt) row.metrics = ComputeMetrics(*solved, *run.gt);
  SolveOutputs exported;
  exported.solved = &*solved;
  exported.ground_truth = run.gt;
  run.export_flags->Apply(&exported);
  if (!WriteExportedTrajectories(dir.string(), exported).ok()) return std::nullopt;
  if (solved_out != nullptr) *solved_out = std::move(*solved);
  std::fprintf(stderr, "[compare] %s: the finished solve in %s reused (--resume)\n",
               FormulationName(formulation), dir.string().c_str());
  return row;
}

// Builds one formulation into DIR/<f>/graph.g2o, solves it, scores it when there is ground truth
// and writes the solve's outputs (SPEC §4) and build.txt beside it. On failure: the error is
// printed, *exit_code set and nothing returned.
std::optional<Row> SolveFormulation(const Graph& front_end, Formulation formulation,
                                    const RunSettings& run, const Graph* world_centric_start,
                                    Graph* solved_out, int* exit_code) {
  const char* name = FormulationName(formulation);
  const GroundTruth* gt = run.gt;
  auto fail = [exit_code](const Error& error, int code = kExitFailed) {
    std::cerr << "error: " << error.ToString() << "\n";
    *exit_code = code;
    return std::nullopt;
  };
  BuildReport build_report;
  Expected<Graph> graph = BuildFormulation(front_end, formulation, run.build_options, gt,
                                           &build_report, run.front_end_name);
  if (!graph.ok()) return fail(graph.error(), kExitBadInput);
  if (world_centric_start != nullptr && IsObjectCentric(formulation)) {
    if (Status s = StartFromWorldCentric(front_end, *world_centric_start, run.build_options, gt,
                                         &*graph, "wc's solution");
        !s.ok()) {
      return fail(s.error());
    }
    build_report.lines.push_back("initial values from wc's solution (--start wc, SPEC §3.5)");
  }
  const fs::path dir = run.out_dir / name;
  SolverOptions options = run.solver_options;
  run.compat->Apply(formulation == Formulation::kWorldCentric, &options);
  if (run.resume) {
    if (std::optional<Row> row = FinishedSolveIn(dir, formulation, *graph, options, run, solved_out)) {
      return row;
    }
  }
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (Status s = WriteGraph(*graph, (dir / "graph.g2o").string()); !s.ok()) {
    return fail(s.error());
  }
  std::fprintf(stderr, "[compare] %s: solving %zu variables, %zu edges\n", name,
               graph->NumVariables(), graph->NumEdges());
  Row row = BuiltRow(formulation, *graph);
  Expected<SolveReport> report = Solve(options, &*graph);
  if (!report.ok()) {
    Error error = report.error();
    error.message = std::string(name) + ": " + error.message;
    return fail(error);
  }
  row.report = std::move(report).value();
  SolveOutputs outputs;
  outputs.input = (dir / "graph.g2o").string();
  outputs.solved = &*graph;
  outputs.report = &row.report;
  outputs.warnings = build_report.warnings;
  outputs.ground_truth = gt;
  run.export_flags->Apply(&outputs);
  if (gt) {
    row.metrics = ComputeMetrics(*graph, *gt);
    outputs.metrics = row.metrics;
  } else {
    outputs.warnings.push_back(formulation == Formulation::kWorldCentric
                                   ? "no ground truth: no metrics"
                                   : "no ground truth: no metrics; each segment's first object "
                                     "pose started by the centroid rule (SPEC §3.3)");
  }
  CovarianceReport covariance;
  if (!run.covariance.empty() && row.report.usable) {
    if (Status s = AttachCovariances(*graph, row.report, run.covariance, run.covariance_kinds,
                                     &covariance, &outputs);
        !s.ok()) {
      return fail(s.error());
    }
    row.consistency = outputs.consistency;
  }
  if (Status s = WriteSolveOutputs(dir.string(), outputs); !s.ok()) {
    return fail(s.error());
  }
  if (Status s = WriteFileAtomically((dir / "build.txt").string(), build_report.ToText());
      !s.ok()) {
    return fail(s.error());
  }
  if (!row.report.usable) {
    return fail(Error{"", 0, std::string(name) + ": the solve failed: " +
                                 row.report.termination_detail});
  }
  if (solved_out != nullptr) *solved_out = std::move(*graph);
  return row;
}

}  // namespace

int RunCompare(int argc, char** argv) {
  std::string front_end_path, gt_path, out_dir, formulation_list = FormulationNames(",");
  bool no_plots = false;
  ArgParser parser(
      "dynslam compare FRONTEND.g2o --out DIR [--gt GT] [options]",
      "Builds every formulation from one front-end file (identical data), solves each with the\n"
      "same options, scores each against ground truth, and prints the paper's Tables I-III.\n"
      "Writes DIR/tables.md, DIR/tables.csv and, per formulation, DIR/<f>/graph.g2o with the\n"
      "full solve output (SPEC §4); then, when /usr/bin/python3 has matplotlib, DIR/convergence.png\n"
      "and DIR/trajectory.png (scripts/plot_convergence.py, scripts/plot_trajectory.py).\n"
      "--max-time limits each formulation's solve. SIGINT (Ctrl-C) or SIGTERM stops the current\n"
      "solve after its step, writes its outputs and the tables of what finished (no plots), and\n"
      "exits 130 or 143; a second signal quits at once.");
  parser.AddPositional("FRONTEND.g2o", &front_end_path, "front-end graph file");
  parser.AddString("gt", &gt_path,
                   "ground-truth file (SPEC §2): the errors of Tables I-III and each segment's "
                   "first object pose; without it, only the solves are tabulated and object poses "
                   "start by the centroid rule (SPEC §3.3)",
                   "GT");
  parser.AddString("out", &out_dir, "output directory, required", "DIR");
  parser.AddString("formulations", &formulation_list,
                   "comma-separated subset of " + FormulationNames(","), "LIST");
  parser.AddFlag("no-plots", &no_plots, "do not draw DIR/convergence.png and DIR/trajectory.png");
  std::string start = "frontend";
  parser.AddChoice("start", &start, {"frontend", "wc"},
                   "where oc_a, oc_b and oc_c start: the front end's estimates, or wc's solution "
                   "(SPEC §3.5; wc must come first in --formulations; their steps and times then "
                   "add to wc's)");
  bool resume = false;
  std::string covariance_kinds;
  parser.AddString("covariance", &covariance_kinds,
                   "also each formulation's marginal covariances of these kinds "
                   "(<f>/covariances.csv, as `solve --covariance`) and, with --gt, a NEES table "
                   "of how honest they are (docs/COVARIANCE.md); not with --resume",
                   "KIND,...");
  parser.AddFlag("resume", &resume,
                 "reuse each formulation's finished solve already in DIR (the same built graph "
                 "and solver options, ended by convergence or the step limit) instead of solving "
                 "it again: a long compare that was stopped goes on from the next formulation");
  BuildFlags build_flags(&parser, BuildOptionTable());
  SolverFlags solver_flags(&parser, SolverOptionTable());
  CompatFlags compat(&parser);
  ExportFlags export_flags(&parser);
  if (std::optional<int> exit_code = parser.Parse(argc, argv, 2)) return *exit_code;
  if (ReportedProblem(export_flags.Finish())) return kExitBadInput;
  if (ReportedProblem(compat.Finish())) return kExitBadInput;
  if (out_dir.empty()) {
    std::cerr << "error: --out DIR is required\n";
    return kExitBadInput;
  }
  std::vector<Formulation> formulations;
  std::stringstream list(formulation_list);
  for (std::string item; std::getline(list, item, ',');) {
    Formulation f;
    if (!ParseFormulation(item, &f)) {
      std::cerr << "error: --formulations: unknown formulation '" << item << "'\n";
      return kExitBadInput;
    }
    formulations.push_back(f);
  }
  std::vector<CovarianceKind> covariance;
  if (!CovarianceKindsOfFlag(parser.Given("covariance"), covariance_kinds, &covariance)) {
    return kExitBadInput;
  }
  if (!covariance.empty() && resume) {
    std::cerr << "error: --covariance and --resume: a solve read back has no covariances; give "
                 "one of them\n";
    return kExitBadInput;
  }
  const bool start_wc = start == "wc";
  if (start_wc && (formulations.empty() || formulations[0] != Formulation::kWorldCentric)) {
    std::cerr << "error: --start wc: wc must come first in --formulations\n";
    return kExitBadInput;
  }
  BuildOptions build_options;
  if (ReportedProblem(build_flags.Finish(&build_options))) return kExitBadInput;
  compat.Apply(&build_options);
  SolverOptions solver_options;
  if (ReportedProblem(solver_flags.Finish(&solver_options))) return kExitBadInput;
  PrintProgressAfterOneSecond(&solver_options);
  StopOnSignals(&solver_options);

  ReadOptions read_options;
  compat.Apply(&read_options);
  Expected<Graph> front_end = ReadGraph(front_end_path, read_options);
  if (!front_end.ok()) {
    std::cerr << "error: " << front_end.error().ToString() << "\n";
    return kExitBadInput;
  }
  std::optional<GroundTruth> gt;
  if (!ReadGroundTruthIfGiven(gt_path, &gt)) return kExitBadInput;
  // The tables mark a finished compare: a run that fails or is killed leaves none behind.
  for (const char* name : {"tables.md", "tables.csv"}) {
    if (Status s = RemoveIfPresent((fs::path(out_dir) / name).string()); !s.ok()) {
      std::cerr << "error: " << s.error().ToString() << "\n";
      return kExitFailed;
    }
  }
  RunSettings run;
  run.build_options = build_options;
  run.solver_options = solver_options;
  run.compat = &compat;
  run.export_flags = &export_flags;
  run.gt = gt ? &*gt : nullptr;
  run.out_dir = out_dir;
  run.front_end_name = fs::path(front_end_path).filename().string();
  run.resume = resume;
  run.covariance_kinds = covariance_kinds;
  run.covariance = covariance;
  std::vector<Row> rows;
  const auto started = std::chrono::steady_clock::now();
  Graph world_centric;  // wc's solution, with --start wc
  for (const Formulation formulation : formulations) {
    int exit_code = kExitOk;
    const bool wc = formulation == Formulation::kWorldCentric;
    std::optional<Row> row = SolveFormulation(
        *front_end, formulation, run, start_wc && !wc ? &world_centric : nullptr,
        start_wc && wc ? &world_centric : nullptr, &exit_code);
    if (!row) return exit_code;
    rows.push_back(std::move(*row));
    PrintProgress(rows, formulations.size(), SecondsSince(started));
    if (StopSignal() != 0) {
      std::fprintf(stderr, "[compare] stopped by a signal after %s: tables for what finished\n",
                   FormulationName(formulation));
      break;
    }
  }
  std::string markdown, csv;
  if (gt) {
    Tables(rows, &markdown, &csv);
  } else {
    TablesWithoutGroundTruth(rows, &markdown, &csv);
  }
  if (start_wc && !rows.empty()) {
    markdown = "(--start wc: oc_a, oc_b and oc_c started from wc's solution (wc's termination: " +
               rows.front().report.termination +
               "), so their steps and times come after wc's; hy from the front end)\n\n" +
               markdown;
  }
  std::string reused;
  for (const Row& row : rows) {
    if (row.reused) reused += std::string(reused.empty() ? "" : ", ") + FormulationName(row.formulation);
  }
  if (!reused.empty()) {
    markdown = "(--resume: " + reused + " read back from the finished solves in " + out_dir +
               "; their steps and times are those solves')\n\n" + markdown;
  }
  if (compat.any()) {
    markdown = "(--compat " + compat.Describe() +
               ": the released code's or DynoSAM's choices, SPEC §7, §3.6)\n\n" + markdown;
  }
  for (const auto& [name, text] : {std::pair{"tables.csv", &csv}, std::pair{"tables.md", &markdown}}) {
    if (Status s = WriteFileAtomically((fs::path(out_dir) / name).string(), *text); !s.ok()) {
      std::cerr << "error: " << s.error().ToString() << "\n";
      return kExitFailed;
    }
  }
  std::fputs(markdown.c_str(), stdout);
  if (!no_plots && StopSignal() == 0) {
    DrawPlots(out_dir, rows, gt_path, fs::path(front_end_path).filename().string());
  }
  return ExitCodeAfterStopSignal(kExitOk);
}

}  // namespace dynslam::cli
