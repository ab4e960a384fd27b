#include "dynslam/compare.h"

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <utility>

#include "dynslam/file_io.h"
#include "dynslam/graph_io.h"
#include "dynslam/solve_output.h"
#include "src/number_text.h"

namespace dynslam {
namespace {

namespace fs = std::filesystem;

// The row of `formulation` as built: its sizes, before any solve.
CompareRow BuiltRow(Formulation formulation, const Graph& built) {
  CompareRow row;
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

// "37", or "37 (interrupted)" for a solve a signal or --max-time stopped.
std::string Iterations(const SolveReport& report) {
  const bool stopped_early =
      report.termination == "interrupted" || report.termination == "time_limit";
  return std::to_string(report.iterations) + (stopped_early ? " (" + report.termination + ")" : "");
}

// Without ground truth: what every formulation's solve did, the accuracy columns marked.
void TablesWithoutGroundTruth(const std::vector<CompareRow>& rows, std::string* markdown,
                              std::string* csv) {
  std::ostringstream md, out;
  out << "table,formulation,object,quantity,value\n";
  md << "### Table I without ground truth: problem size and solve\n\n"
     << "No ground truth (--gt): each segment's first object pose started at the centroid of its "
        "points with identity rotation (SPEC §3.3); the camera, object motion and object pose "
        "errors (Tables I-III) need ground truth.\n\n"
     << "| formulation | variables | edges | steps | iterations | final cost | solve time (s) | camera E_r (deg) | camera E_t (m) |\n"
     << "|---|---|---|---|---|---|---|---|---|\n";
  for (const CompareRow& r : rows) {
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
void NeesTable(const std::vector<CompareRow>& rows, std::ostringstream* md, std::ostringstream* csv) {
  if (std::none_of(rows.begin(), rows.end(), [](const CompareRow& r) { return r.consistency; })) return;
  *md << "### NEES: how honest each covariance is (expected 6; docs/COVARIANCE.md)\n\n"
      << "| formulation | camera | band | object motion | band | object pose | band |\n"
      << "|---|---|---|---|---|---|---|\n";
  for (const CompareRow& r : rows) {
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
void Tables(const std::vector<CompareRow>& rows, std::string* markdown, std::string* csv) {
  std::ostringstream md, out;
  out << "table,formulation,object,quantity,value\n";
  md << "### Table I: camera relative pose error, problem size, solve time\n\n"
     << "| formulation | camera E_r (deg) | camera E_t (m) | pairs | variables | edges | iterations | solve time (s) |\n"
     << "|---|---|---|---|---|---|---|---|\n";
  for (const CompareRow& r : rows) {
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
    for (const CompareRow& r : rows) {
      for (const auto& [object, mean] : (*r.metrics.*family).per_object) objects.insert(object);
    }
    md << "\n### " << title << "\n\n| object |";
    for (const CompareRow& r : rows) md << " " << FormulationName(r.formulation) << " E_r (deg) | E_t (m) |";
    md << "\n|---|";
    for (size_t i = 0; i < rows.size(); ++i) md << "---|---|";
    md << "\n";
    for (const int64_t object : objects) {
      md << "| " << object << " |";
      for (const CompareRow& r : rows) {
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
    for (const CompareRow& r : rows) {
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
std::optional<CompareRow> FinishedSolveIn(const fs::path& dir, Formulation formulation,
                                          const Graph& built, const SolverOptions& options,
                                          const GroundTruth* gt, const CompareOptions& run,
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
  CompareRow row = BuiltRow(formulation, built);
  row.report = report;
  row.reused = true;
  if (gt) row.metrics = ComputeMetrics(*solved, *gt);
  SolveOutputs exported;
  exported.solved = &*solved;
  exported.ground_truth = gt;
  exported.export_options = run.export_options;
  if (!WriteExportedTrajectories(dir.string(), exported).ok()) return std::nullopt;
  if (solved_out != nullptr) *solved_out = std::move(*solved);
  return row;
}

// The outputs of SPEC §4 and build.txt of one formulation's solve in `dir`, covariances
// computed first when asked for (into row->consistency).
Status WriteOutputs(const fs::path& dir, const Graph& solved, const BuildReport& build_report,
                    const GroundTruth* gt, const CompareOptions& run, CompareRow* row) {
  SolveOutputs outputs;
  outputs.input = (dir / "graph.g2o").string();
  outputs.solved = &solved;
  outputs.report = &row->report;
  outputs.warnings = build_report.warnings;
  outputs.ground_truth = gt;
  outputs.metrics = row->metrics;
  outputs.export_options = run.export_options;
  if (!gt) {
    outputs.warnings.push_back(row->formulation == Formulation::kWorldCentric
                                   ? "no ground truth: no metrics"
                                   : "no ground truth: no metrics; each segment's first object "
                                     "pose started by the centroid rule (SPEC §3.3)");
  }
  CovarianceReport covariance;
  if (!run.covariance.empty() && row->report.usable) {
    if (Status s = AttachCovariances(solved, row->report, run.covariance, run.covariance_kinds,
                                     &covariance, &outputs);
        !s.ok()) {
      return s;
    }
  }
  row->consistency = outputs.consistency;
  if (run.out_dir.empty()) return Status::Ok();
  if (Status s = WriteSolveOutputs(dir.string(), outputs); !s.ok()) return s;
  return WriteFileAtomically((dir / "build.txt").string(), build_report.ToText());
}

// Builds, solves and scores one formulation (its outputs in out_dir/<f>/ when there is one).
// `world_centric_start`: wc's solution to start from (start wc), or null.
Expected<CompareRow> SolveFormulation(const Graph& front_end, Formulation formulation,
                                      const GroundTruth* gt, const CompareOptions& run,
                                      const Graph* world_centric_start, Graph* solved_out) {
  const char* name = FormulationName(formulation);
  BuildReport build_report;
  Expected<Graph> graph = BuildFormulation(front_end, formulation, run.build, gt, &build_report,
                                           run.front_end_name);
  if (!graph.ok()) return graph.error();
  if (world_centric_start != nullptr && IsObjectCentric(formulation)) {
    if (Status s = StartFromWorldCentric(front_end, *world_centric_start, run.build, gt, &*graph,
                                         "wc's solution");
        !s.ok()) {
      return s.error();
    }
    build_report.lines.push_back("initial values from wc's solution (--start wc, SPEC §3.5)");
  }
  const fs::path dir = fs::path(run.out_dir) / name;
  SolverOptions options = run.solver;
  ApplyCompat(run.compat, formulation == Formulation::kWorldCentric, &options);
  if (run.resume && !run.out_dir.empty()) {
    if (std::optional<CompareRow> row =
            FinishedSolveIn(dir, formulation, *graph, options, gt, run, solved_out)) {
      return std::move(*row);
    }
  }
  if (!run.out_dir.empty()) {
    std::error_code ec;
    fs::create_directories(dir, ec);
    if (Status s = WriteGraph(*graph, (dir / "graph.g2o").string()); !s.ok()) return s.error();
  }
  CompareRow row = BuiltRow(formulation, *graph);
  if (run.on_solve_start) run.on_solve_start(formulation, *graph);
  Expected<SolveReport> report = run.solve ? run.solve(options, &*graph) : Solve(options, &*graph);
  if (!report.ok()) {
    Error error = report.error();
    error.message = std::string(name) + ": " + error.message;
    return error;
  }
  row.report = std::move(report).value();
  if (gt) row.metrics = ComputeMetrics(*graph, *gt);
  if (Status s = WriteOutputs(dir, *graph, build_report, gt, run, &row); !s.ok()) {
    return s.error();
  }
  if (!row.report.usable) {
    return Error{"", 0, std::string(name) + ": the solve failed: " + row.report.termination_detail};
  }
  if (solved_out != nullptr) *solved_out = std::move(*graph);
  return row;
}

// Notes above the tables: what a reader must know to read them.
std::string Notes(const CompareRun& run, const CompareOptions& options) {
  std::string notes;
  if (CompatText(options.compat) != "none") {
    notes += "(--compat " + CompatText(options.compat) +
             ": the released code's or DynoSAM's choices, SPEC §7, §3.6)\n\n";
  }
  std::string reused;
  for (const CompareRow& row : run.rows) {
    if (row.reused) reused += std::string(reused.empty() ? "" : ", ") + FormulationName(row.formulation);
  }
  if (!reused.empty()) {
    notes += "(--resume: " + reused + " read back from the finished solves in " +
             options.out_dir + "; their steps and times are those solves')\n\n";
  }
  if (options.start_from_world_centric && !run.rows.empty()) {
    notes += "(--start wc: oc_a, oc_b and oc_c started from wc's solution (wc's termination: " +
             run.rows.front().report.termination +
             "), so their steps and times come after wc's; hy from the front end)\n\n";
  }
  return notes;
}

}  // namespace

Expected<CompareRun> CompareFormulations(const Graph& front_end, const GroundTruth* ground_truth,
                                         const CompareOptions& options) {
  const bool start_wc = options.start_from_world_centric;
  if (start_wc && (options.formulations.empty() ||
                   options.formulations.front() != Formulation::kWorldCentric)) {
    return Error{"", 0, "start from wc: wc must come first in the formulations"};
  }
  if (options.resume && !options.covariance.empty()) {
    return Error{"", 0, "a solve read back (resume) has no covariances; ask for one of them"};
  }
  CompareOptions run = options;
  ApplyCompat(run.compat, &run.build);
  CompareRun result;
  Graph world_centric;  // wc's solution, with start wc
  for (const Formulation formulation : run.formulations) {
    const bool wc = formulation == Formulation::kWorldCentric;
    Graph solved;
    Graph* keep = options.keep_solutions ? &solved : (start_wc && wc ? &world_centric : nullptr);
    Expected<CompareRow> row = SolveFormulation(front_end, formulation, ground_truth, run,
                                                start_wc && !wc ? &world_centric : nullptr, keep);
    if (!row.ok()) return row.error();
    if (options.keep_solutions) {
      if (start_wc && wc) world_centric = solved;
      row->solution = std::move(solved);
    }
    result.rows.push_back(std::move(row).value());
    if (options.on_row) options.on_row(result.rows.back());
    if (run.solver.should_stop && run.solver.should_stop()) {
      result.stopped = formulation != run.formulations.back();
      break;
    }
  }
  return result;
}

CompareTables TablesOf(const CompareRun& run, const CompareOptions& options) {
  CompareTables tables;
  const bool scored = !run.rows.empty() && run.rows.front().metrics.has_value();
  if (scored) {
    Tables(run.rows, &tables.markdown, &tables.csv);
  } else {
    TablesWithoutGroundTruth(run.rows, &tables.markdown, &tables.csv);
  }
  tables.markdown = Notes(run, options) + tables.markdown;
  return tables;
}

}  // namespace dynslam
