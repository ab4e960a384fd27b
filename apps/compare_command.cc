// dynslam compare FRONTEND.g2o --gt GT --out DIR [--formulations wc,oc_a,…] [options]
//
// Builds every formulation from one front-end file (identical data, SPEC §3), solves each the
// same way, scores each the same way (SPEC §5) and prints the paper's Tables I–III side by side.
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <set>
#include <sstream>

#include "build_flags.h"
#include "cli.h"
#include "compat_flags.h"
#include "commands.h"
#include "dynslam/formulation.h"
#include "dynslam/graph_io.h"
#include "dynslam/ground_truth.h"
#include "dynslam/metrics.h"
#include "dynslam/solve_output.h"
#include "dynslam/solver.h"
#include "solver_flags.h"

namespace dynslam::cli {
namespace {

namespace fs = std::filesystem;

struct Row {
  Formulation formulation;
  int64_t variables = 0;
  int64_t edges = 0;
  SolveReport report;
  Metrics metrics;
};

std::string Fixed(double value, int digits) {
  char buffer[32];
  std::snprintf(buffer, sizeof(buffer), "%.*f", digits, value);
  return buffer;
}

// Tables I–III as Markdown, and the same numbers as CSV (table,formulation,object,quantity,value).
void Tables(const std::vector<Row>& rows, std::string* markdown, std::string* csv) {
  std::ostringstream md, out;
  out << "table,formulation,object,quantity,value\n";
  md << "### Table I: camera relative pose error, problem size, solve time\n\n"
     << "| formulation | camera E_r (deg) | camera E_t (m) | pairs | variables | edges | iterations | solve time (s) |\n"
     << "|---|---|---|---|---|---|---|---|\n";
  for (const Row& r : rows) {
    const char* f = FormulationName(r.formulation);
    md << "| " << f << " | " << Fixed(r.metrics.camera.mean_rot_deg, 4) << " | "
       << Fixed(r.metrics.camera.mean_trans_m, 4) << " | " << r.metrics.camera.count << " | "
       << r.variables << " | " << r.edges << " | " << r.report.iterations << " | "
       << Fixed(r.report.time_total_s, 3) << " |\n";
    out << "I," << f << ",,camera_rot_deg," << r.metrics.camera.mean_rot_deg << "\n"
        << "I," << f << ",,camera_trans_m," << r.metrics.camera.mean_trans_m << "\n"
        << "I," << f << ",,variables," << r.variables << "\n"
        << "I," << f << ",,solve_time_s," << r.report.time_total_s << "\n";
  }
  auto object_table = [&](const char* title, const char* id,
                          const ObjectErrors Metrics::*family) {
    std::set<int64_t> objects;
    for (const Row& r : rows) {
      for (const auto& [object, mean] : (r.metrics.*family).per_object) objects.insert(object);
    }
    md << "\n### " << title << "\n\n| object |";
    for (const Row& r : rows) md << " " << FormulationName(r.formulation) << " E_r (deg) | E_t (m) |";
    md << "\n|---|";
    for (size_t i = 0; i < rows.size(); ++i) md << "---|---|";
    md << "\n";
    for (const int64_t object : objects) {
      md << "| " << object << " |";
      for (const Row& r : rows) {
        const auto& per_object = (r.metrics.*family).per_object;
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
      md << " " << Fixed((r.metrics.*family).mean_rot_deg, 4) << " | "
         << Fixed((r.metrics.*family).mean_trans_m, 4) << " |";
      out << id << "," << FormulationName(r.formulation) << ",mean,rot_deg,"
          << (r.metrics.*family).mean_rot_deg << "\n"
          << id << "," << FormulationName(r.formulation) << ",mean,trans_m,"
          << (r.metrics.*family).mean_trans_m << "\n";
    }
    md << "\n";
  };
  object_table("Table II: object motion error", "II", &Metrics::object_motion);
  object_table("Table III: object pose error", "III", &Metrics::object_pose);
  *markdown = md.str();
  *csv = out.str();
}

}  // namespace

int RunCompare(int argc, char** argv) {
  std::string front_end_path, gt_path, out_dir, formulation_list = "wc,oc_a,oc_b,oc_c";
  ArgParser parser(
      "dynslam compare FRONTEND.g2o --gt GT --out DIR [options]",
      "Builds every formulation from one front-end file (identical data), solves each with the\n"
      "same options, scores each against ground truth, and prints the paper's Tables I-III.\n"
      "Writes DIR/tables.md, DIR/tables.csv and, per formulation, DIR/<f>/graph.g2o with the\n"
      "full solve output (SPEC §4).");
  parser.AddPositional("FRONTEND.g2o", &front_end_path, "front-end graph file");
  parser.AddString("gt", &gt_path, "ground-truth file (SPEC §2), required", "GT");
  parser.AddString("out", &out_dir, "output directory, required", "DIR");
  parser.AddString("formulations", &formulation_list, "comma-separated subset of wc,oc_a,oc_b,oc_c",
                   "LIST");
  BuildFlags build_flags(&parser);
  SolverFlags solver_flags(&parser);
  CompatFlags compat(&parser);
  if (std::optional<int> exit_code = parser.Parse(argc, argv, 2)) return *exit_code;
  if (std::optional<std::string> problem = compat.Finish()) {
    std::cerr << "error: " << *problem << "\n";
    return kExitBadInput;
  }
  if (gt_path.empty() || out_dir.empty()) {
    std::cerr << "error: --gt GT and --out DIR are required\n";
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
  BuildOptions build_options;
  build_flags.Finish(&build_options);
  compat.Apply(&build_options);
  SolverOptions solver_options;
  if (std::optional<std::string> problem = solver_flags.Finish(&solver_options)) {
    std::cerr << "error: " << *problem << "\n";
    return kExitBadInput;
  }

  ReadOptions read_options;
  compat.Apply(&read_options);
  Expected<Graph> front_end = ReadGraph(front_end_path, read_options);
  if (!front_end.ok()) {
    std::cerr << "error: " << front_end.error().ToString() << "\n";
    return kExitBadInput;
  }
  Expected<GroundTruth> gt = ReadGroundTruth(gt_path);
  if (!gt.ok()) {
    std::cerr << "error: " << gt.error().ToString() << "\n";
    return kExitBadInput;
  }
  std::vector<Row> rows;
  for (const Formulation formulation : formulations) {
    const char* name = FormulationName(formulation);
    BuildReport build_report;
    Expected<Graph> graph = BuildFormulation(*front_end, formulation, build_options, &*gt,
                                             &build_report, fs::path(front_end_path).filename().string());
    if (!graph.ok()) {
      std::cerr << "error: " << graph.error().ToString() << "\n";
      return kExitBadInput;
    }
    const fs::path dir = fs::path(out_dir) / name;
    std::error_code ec;
    fs::create_directories(dir, ec);
    if (Status s = WriteGraph(*graph, (dir / "graph.g2o").string()); !s.ok()) {
      std::cerr << "error: " << s.error().ToString() << "\n";
      return kExitFailed;
    }
    std::fprintf(stderr, "[compare] %s: solving %zu variables, %zu edges\n", name,
                 graph->vertices.size(), graph->NumEdges());
    SolverOptions options = solver_options;
    compat.Apply(formulation == Formulation::kWorldCentric, &options);
    Row row;
    row.formulation = formulation;
    row.variables = static_cast<int64_t>(graph->vertices.size());
    row.edges = static_cast<int64_t>(graph->NumEdges());
    Expected<SolveReport> report = Solve(options, &*graph);
    if (!report.ok()) {
      std::cerr << "error: " << name << ": " << report.error().ToString() << "\n";
      return kExitFailed;
    }
    row.report = *report;
    row.metrics = ComputeMetrics(*graph, *gt);
    SolveOutputs outputs;
    outputs.input = (dir / "graph.g2o").string();
    outputs.solved = &*graph;
    outputs.report = &row.report;
    outputs.options = &options;
    outputs.metrics = MetricsJson(row.metrics);
    outputs.warnings = build_report.warnings;
    for (const auto& [key, pose] : EstimatedObjectPoses(*graph, *gt)) {
      outputs.object_poses.push_back({key.first, key.second, pose});
    }
    if (Status s = WriteSolveOutputs(dir.string(), outputs); !s.ok()) {
      std::cerr << "error: " << s.error().ToString() << "\n";
      return kExitFailed;
    }
    std::ofstream(dir / "build.txt") << build_report.ToText();
    if (!report->usable) {
      std::cerr << "error: " << name << ": the solve failed: " << report->termination_detail << "\n";
      return kExitFailed;
    }
    rows.push_back(std::move(row));
  }
  std::string markdown, csv;
  Tables(rows, &markdown, &csv);
  if (compat.any()) markdown = "(--compat " + compat.Describe() + ": the released code's choices, SPEC §7)\n\n" + markdown;
  std::ofstream(fs::path(out_dir) / "tables.md") << markdown;
  std::ofstream(fs::path(out_dir) / "tables.csv") << csv;
  std::fputs(markdown.c_str(), stdout);
  return kExitOk;
}

}  // namespace dynslam::cli
