#include "dynslam/solve_output.h"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "dynslam/file_io.h"
#include "dynslam/formulation.h"
#include "dynslam/graph_io.h"
#include "src/json_io.h"
#include "src/number_text.h"

namespace dynslam {
namespace {

std::string CamerasCsv(const Graph& graph) {
  std::vector<std::pair<int64_t, Pose>> rows;
  for (const auto& [id, vertex] : graph.vertices) {
    if (vertex.label.role == Role::kCamera && graph.labelled) {
      rows.emplace_back(vertex.label.frame, vertex.pose());
    }
  }
  std::sort(rows.begin(), rows.end(),
            [](const auto& a, const auto& b) { return a.first < b.first; });
  std::string text = "frame,tx,ty,tz,qx,qy,qz,qw\n";
  for (const auto& [frame, pose] : rows) {
    std::string line = std::to_string(frame);
    AppendPoseFields(&line, pose, ',');
    text += line + "\n";
  }
  return text;
}

std::string ObjectFrameCsv(std::vector<ObjectPoseRow> rows) {
  std::sort(rows.begin(), rows.end(), [](const ObjectPoseRow& a, const ObjectPoseRow& b) {
    return std::tie(a.object, a.frame) < std::tie(b.object, b.frame);
  });
  std::string text = "object,frame,tx,ty,tz,qx,qy,qz,qw\n";
  for (const ObjectPoseRow& row : rows) {
    std::string line = std::to_string(row.object) + "," + std::to_string(row.frame);
    AppendPoseFields(&line, row.pose, ',');
    text += line + "\n";
  }
  return text;
}

// Poses by (object, frame) as CSV rows.
std::vector<ObjectPoseRow> Rows(const std::map<std::pair<int64_t, int64_t>, Pose>& poses) {
  std::vector<ObjectPoseRow> rows;
  for (const auto& [key, pose] : poses) rows.push_back({key.first, key.second, pose});
  return rows;
}

std::string ConvergenceCsv(const SolveReport& report) {
  std::string text = "step,iteration,lambda,cost,trial_cost,accepted,time_s\n";
  for (const StepRecord& row : report.convergence) {
    text += std::to_string(row.step) + "," + std::to_string(row.iteration) + "," +
            NumberText(row.lambda) + "," + NumberText(row.cost) + "," +
            NumberText(row.trial_cost) + "," + (row.accepted ? "1" : "0") + "," +
            NumberText(row.time_s) + "\n";
  }
  return text;
}

// errors.csv: every per-frame error of the metrics (SPEC §4, §5).
std::string ErrorsCsv(const Metrics& metrics) {
  std::string text = "quantity,object,frame,rot_deg,trans_m\n";
  for (const FrameError& e : metrics.per_frame) {
    text += std::string(e.quantity) + "," + std::to_string(e.object) + "," +
            std::to_string(e.frame) + "," + NumberText(e.rot_deg) + "," + NumberText(e.trans_m) +
            "\n";
  }
  return text;
}

std::string CovariancesCsv(const CovarianceReport& covariance) {
  std::string out = "id,role,dim,upper_triangle\n";
  for (const MarginalCovariance& m : covariance.marginals) {
    const int dim = static_cast<int>(m.covariance.rows());
    out += std::to_string(m.id) + "," + RoleName(m.role) + "," + std::to_string(dim);
    for (int r = 0; r < dim; ++r) {
      for (int c = r; c < dim; ++c) {
        out += ',';
        AppendNumber(&out, m.covariance(r, c));
      }
    }
    out += '\n';
  }
  return out;
}

JsonValue CovarianceJson(const SolveOutputs& outputs) {
  const CovarianceReport& c = *outputs.covariance;
  JsonValue weak = JsonValue::array();
  for (const WeakDirection& w : c.weak_directions) {
    weak.push_back({{"id", w.id},
                    {"direction", DirectionName(*outputs.solved, w)}});
  }
  return {{"kinds", outputs.covariance_kinds},
          {"variables", c.marginals.size()},
          {"columns", c.columns},
          {"time_s", c.time_s},
          {"held_constant", c.held_constant},
          {"weak_directions", std::move(weak)},
          {"file", c.weak_directions.empty() ? "covariances.csv" : ""}};
}

JsonValue NeesJson(const NeesMean& nees) {
  return {{"count", nees.count}, {"dim", nees.dim}, {"mean", nees.mean},
          {"band_95", {nees.band_low, nees.band_high}}};
}

std::vector<ObjectPoseRow> EstimatedObjectPoseRows(const SolveOutputs& outputs) {
  const GroundTruth none;  // object-centric poses need none; world-centric ones get none then
  return Rows(EstimatedObjectPoses(*outputs.solved,
                                   outputs.ground_truth ? *outputs.ground_truth : none));
}

JsonValue CostJson(const CostByKind& cost) {
  JsonValue json = JsonValue::object();
  for (const EdgeKind kind : kAllEdgeKinds) json[EdgeKindName(kind)] = cost[static_cast<int>(kind)];
  return json;
}

// `options` as the solve used them (SolveReport::options_used: no auto left), every option of
// SolverOptionTable under its name.
JsonValue SolverJson(const SolverOptions& options) {
  JsonValue json = {{"library", "Ceres Solver 2.1 (dynslam)"}};
  for (const Option<SolverOptions>& option : SolverOptionTable()) {
    const std::string text = option.get(options);
    switch (option.type) {
      case OptionType::kPreset: continue;  // its effect is in the options it sets
      case OptionType::kSwitch: json[option.name] = text == "on"; break;
      case OptionType::kInteger: json[option.name] = std::stoll(text); break;
      case OptionType::kReal: {
        double value = 0;
        ParseReal(text, -HUGE_VAL, HUGE_VAL, &value);  // exact: the text is the shortest form
        json[option.name] = value;
        break;
      }
      case OptionType::kChoice:
      case OptionType::kText: json[option.name] = text; break;
    }
  }
  return json;
}

}  // namespace


std::string SummaryJson(const SolveOutputs& outputs) {
  const SolveReport& report = *outputs.report;
  std::string source;
  const std::string formulation = FormulationLabelOf(*outputs.solved, &source);

  JsonValue variables = JsonValue::object();
  int64_t total_variables = 0;
  for (size_t r = 0; r < kAllRoles.size(); ++r) {
    variables[RoleName(kAllRoles[r])] = report.variables_by_role[r];
    if (!InfoOf(kAllRoles[r])->constant) total_variables += report.variables_by_role[r];
  }
  variables["unused"] = report.unused_variables;
  variables["total"] = total_variables;

  JsonValue edges = JsonValue::object();
  int64_t total_edges = 0;
  for (const EdgeKind kind : kAllEdgeKinds) {
    edges[EdgeKindName(kind)] = report.edges_by_kind[static_cast<int>(kind)];
    total_edges += report.edges_by_kind[static_cast<int>(kind)];
  }
  edges["total"] = total_edges;

  JsonValue warnings = outputs.warnings;
  for (const std::string& warning : report.warnings) warnings.push_back(warning);

  JsonValue summary{
      {"input", outputs.input},
      {"formulation", formulation},
      {"formulation_source", source},
      {"variables", std::move(variables)},
      {"edges", std::move(edges)},
      {"initial_cost", report.initial_cost},
      {"final_cost", report.final_cost},
      {"cost_by_kind",
       {{"initial", CostJson(report.initial_cost_by_kind)},
        {"final", CostJson(report.final_cost_by_kind)}}},
      {"iterations", report.iterations},
      {"steps", report.steps},
      {"extrapolations", report.extrapolations},
      {"gauge_moves", report.gauge_moves},
      {"termination", report.termination},
      {"termination_detail", report.termination_detail},
      {"usable", report.usable},
      {"time_s",
       {{"total", report.time_total_s},
        {"preprocessing", report.time_preprocessor_s},
        {"minimizer", report.time_minimizer_s},
        {"residual_jacobian_evaluation", report.time_evaluation_s},
        {"linear_solve", report.time_linear_solver_s}}},
      {"schur_ordering", report.eliminated_first},
      {"held_constant", report.held_constant},
      {"solver", report.solver_json.empty() ? SolverJson(report.options_used)
                                            : JsonValue::parse(report.solver_json)},
      {"warnings", std::move(warnings)}};
  if (outputs.metrics) summary["metrics"] = MetricsToJson(*outputs.metrics);
  if (outputs.covariance) summary["covariance"] = CovarianceJson(outputs);
  if (const std::optional<Consistency>& c = outputs.consistency) {
    summary["consistency"] = {{"camera", NeesJson(c->camera)},
                              {"object_motion", NeesJson(c->object_motion)},
                              {"object_pose", NeesJson(c->object_pose)}};
  }
  return DumpJson(summary);
}

Status WriteExportedTrajectories(const std::string& dir, const SolveOutputs& outputs) {
  if (outputs.export_options.formats.empty()) return Status::Ok();
  const std::vector<Trajectory> trajectories =
      ExportedTrajectories(*outputs.solved, outputs.ground_truth);
  for (const TrajectoryFormat format : outputs.export_options.formats) {
    if (Status s = WriteTrajectories(dir, trajectories, format, outputs.export_options.rate_hz); !s.ok()) {
      return s;
    }
  }
  return Status::Ok();
}

// summary.json marks a complete set (SPEC §4): it is removed before anything else is written and
// written last, so a directory whose write failed or was killed holds no summary.json.
Status WriteSolveOutputs(const std::string& dir, const SolveOutputs& outputs) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) return Error{dir, 0, "cannot create the output directory: " + ec.message()};
  const std::filesystem::path base(dir);
  if (Status s = RemoveIfPresent((base / "summary.json").string()); !s.ok()) return s;
  const Graph& graph = *outputs.solved;
  if (Status s = WriteGraph(graph, (base / "solution.g2o").string()); !s.ok()) return s;
  const std::pair<const char*, std::string> files[] = {
      {"cameras.csv", CamerasCsv(graph)},
      {"motions.csv", ObjectFrameCsv(Rows(EstimatedMotions(graph)))},
      {"object_poses.csv", ObjectFrameCsv(EstimatedObjectPoseRows(outputs))},
      {"convergence.csv", ConvergenceCsv(*outputs.report)},
      {"summary.json", SummaryJson(outputs) + "\n"},
  };
  if (Status s = WriteExportedTrajectories(dir, outputs); !s.ok()) return s;
  const std::string errors = (base / "errors.csv").string();
  if (outputs.metrics) {
    if (Status s = WriteFileAtomically(errors, ErrorsCsv(*outputs.metrics)); !s.ok()) return s;
  } else if (Status s = RemoveIfPresent(errors); !s.ok()) {  // not an earlier solve's
    return s;
  }
  const std::string covariances = (base / "covariances.csv").string();
  if (outputs.covariance && outputs.covariance->weak_directions.empty()) {
    if (Status s = WriteFileAtomically(covariances, CovariancesCsv(*outputs.covariance)); !s.ok()) {
      return s;
    }
  } else if (Status s = RemoveIfPresent(covariances); !s.ok()) {  // not an earlier solve's
    return s;
  }
  for (const auto& [name, text] : files) {
    if (Status s = WriteFileAtomically((base / name).string(), text); !s.ok()) return s;
  }
  return Status::Ok();
}

std::string SolverOptionsJson(const SolverOptions& options) {
  return DumpJson(SolverJson(options));
}

Expected<SolveSummary> ReadSolveSummary(const std::string& path) {
  Expected<JsonValue> read = ReadJsonFile(path);
  if (!read.ok()) return read.error();
  const JsonValue& json = *read;
  try {
    SolveSummary summary;
    SolveReport& report = summary.report;
    report.termination = json.at("termination").get<std::string>();
    report.termination_detail = json.at("termination_detail").get<std::string>();
    report.usable = json.at("usable").get<bool>();
    report.initial_cost = NumberAt(json, {"initial_cost"});
    report.final_cost = NumberAt(json, {"final_cost"});
    report.iterations = json.at("iterations").get<int>();
    report.steps = json.at("steps").get<int>();
    report.extrapolations = json.at("extrapolations").get<int>();
    report.gauge_moves = json.at("gauge_moves").get<int>();
    report.time_total_s = NumberAt(json, {"time_s", "total"});
    report.time_preprocessor_s = NumberAt(json, {"time_s", "preprocessing"});
    report.time_minimizer_s = NumberAt(json, {"time_s", "minimizer"});
    report.time_evaluation_s = NumberAt(json, {"time_s", "residual_jacobian_evaluation"});
    report.time_linear_solver_s = NumberAt(json, {"time_s", "linear_solve"});
    summary.solver_options_json = DumpJson(json.at("solver"));
    return summary;
  } catch (const nlohmann::json::exception& e) {
    return Error{path, 0, std::string("not a summary.json of dynslam solve: ") + e.what()};
  }
}

Status AttachCovariances(const Graph& solved, const SolveReport& report,
                         const std::vector<CovarianceKind>& kinds, const std::string& kinds_text,
                         CovarianceReport* covariance, SolveOutputs* outputs) {
  Expected<CovarianceReport> computed =
      ComputeCovariances(solved, report, VerticesOfKinds(solved, kinds));
  if (!computed.ok()) return computed.error();
  AttachComputedCovariances(solved, std::move(computed).value(), kinds_text, covariance, outputs);
  return Status::Ok();
}

void AttachComputedCovariances(const Graph& solved, CovarianceReport computed,
                               const std::string& kinds_text, CovarianceReport* covariance,
                               SolveOutputs* outputs) {
  *covariance = std::move(computed);
  outputs->covariance = covariance;
  outputs->covariance_kinds = kinds_text;
  if (outputs->ground_truth != nullptr && covariance->weak_directions.empty()) {
    outputs->consistency = ComputeConsistency(solved, *covariance, *outputs->ground_truth);
  }
}

}  // namespace dynslam
