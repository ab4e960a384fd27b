// Where a solve's steps go (issue 20, docs/CONVERGENCE.md): solves a graph with the default
// solver options (or those given) and records, per accepted step, the model fidelity ρ
// (actual / predicted decrease), how far each kind of variable still is from the final values,
// and, every `--cost-every` steps, the cost per edge kind. Then names the variables that move
// last: those farthest from the final values once the cost is within 1e-6 of the final cost.
//
//   convergence_probe GRAPH [solver options] [--cost-every N] [--top N]
//
// (solver options as `dynslam solve` spells them, docs/OPTIONS.md; --help lists them)
//
// Prints CSV blocks to stdout: "steps" (one row per linear solve or extrapolation), "gap" (per
// accepted step and role: RMS rotation [rad] and translation/position [m] distance to the final
// values), "cost" (per sampled accepted step and edge kind), "late" (the top variables still
// moving).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <optional>
#include <string>
#include <tuple>
#include <vector>

#include "arg_parser.h"
#include "dynslam/graph_io.h"
#include "dynslam/se3.h"
#include "dynslam/solver.h"
#ifdef DYNSLAM_INLINE_OPENMP_REGIONS
#include "inline_openmp_regions.h"
#endif

namespace dynslam {
namespace {

struct Snapshot {
  StepRecord record;
  std::vector<std::array<double, kPoseSize>> values;  // in the graph's vertex order
  CostByKind cost{};
  bool has_cost = false;
};

// Rotation (rad) and translation or position (m) distance of one vertex's value to another's.
std::pair<double, double> Distance(VertexType type, const std::array<double, kPoseSize>& a,
                                   const std::array<double, kPoseSize>& b) {
  if (type == VertexType::kPoint) {
    return {0.0, (Eigen::Vector3d(a[0], a[1], a[2]) - Eigen::Vector3d(b[0], b[1], b[2])).norm()};
  }
  const Pose e = Compose(Inverse(Pose{a}), Pose{b});
  return {RotationAngle(e), e.translation().norm()};
}

struct Args {
  std::string graph;
  SolverOptions options;
  int cost_every = 10;
  int top = 15;
};

void PrintSteps(const std::vector<StepRecord>& rows) {
  std::printf("# steps\nstep,accepted,lambda,cost,trial_cost,rho,time_s,step_norm\n");
  for (const StepRecord& r : rows) {
    std::printf("%d,%d,%.3e,%.10f,%.10f,%.4f,%.3f,%.3e\n", r.step, r.accepted ? 1 : 0, r.lambda,
                r.cost, r.trial_cost, r.relative_decrease, r.time_s, r.step_norm);
  }
}

void PrintGaps(const Graph& graph, const std::vector<Snapshot>& snapshots) {
  std::printf("# gap\nstep,role,rms_rotation_rad,rms_translation_m\n");
  const std::vector<std::array<double, kPoseSize>>& last = snapshots.back().values;
  for (const Snapshot& s : snapshots) {
    std::map<Role, std::array<double, 3>> sums;  // rotation², translation², count
    size_t i = 0;
    for (const auto& [id, v] : graph.vertices) {
      const auto [r, t] = Distance(v.type, s.values[i], last[i]);
      auto& sum = sums[v.label.role];
      sum[0] += r * r;
      sum[1] += t * t;
      sum[2] += 1;
      ++i;
    }
    for (const auto& [role, sum] : sums) {
      std::printf("%d,%s,%.3e,%.3e\n", s.record.step, RoleName(role), std::sqrt(sum[0] / sum[2]),
                  std::sqrt(sum[1] / sum[2]));
    }
  }
}

// The tangent-space difference b ⊟ a of every vertex, stacked (6 per pose as [ω; ρ], 3 per point).
Eigen::VectorXd Difference(const Graph& graph, const Snapshot& a, const Snapshot& b) {
  std::vector<double> d;
  size_t i = 0;
  for (const auto& [id, v] : graph.vertices) {
    if (v.type == VertexType::kPoint) {
      for (int k = 0; k < 3; ++k) d.push_back(b.values[i][k] - a.values[i][k]);
    } else {
      const Vector6d xi = Log(Compose(Inverse(Pose{a.values[i]}), Pose{b.values[i]}));
      d.insert(d.end(), xi.data(), xi.data() + 6);
    }
    ++i;
  }
  return Eigen::Map<Eigen::VectorXd>(d.data(), static_cast<Eigen::Index>(d.size()));
}

// Is the creep one direction, shrinking geometrically? Per accepted step k: the step δ_k's norm,
// its cosine with δ_{k−1}, the ratio r = |δ_k| / |δ_{k−1}|, the gap g_k to the final state, and
// what is left of it after moving on along δ_k by the geometric tail r/(1−r) (Aitken), and by the
// best multiple of δ_k (the part of the gap not along the last step).
void PrintDirections(const Graph& graph, const std::vector<Snapshot>& snapshots) {
  std::printf("# directions\nstep,step_norm,cos_prev,ratio,gap,gap_after_tail,gap_off_step\n");
  Eigen::VectorXd previous;
  for (size_t k = 1; k < snapshots.size(); ++k) {
    const Eigen::VectorXd step = Difference(graph, snapshots[k - 1], snapshots[k]);
    const Eigen::VectorXd gap = Difference(graph, snapshots[k], snapshots.back());
    double cos_prev = std::nan(""), ratio = std::nan(""), after_tail = std::nan("");
    if (previous.size() == step.size() && previous.norm() > 0 && step.norm() > 0) {
      cos_prev = step.dot(previous) / (step.norm() * previous.norm());
      ratio = step.norm() / previous.norm();
      if (ratio < 1) after_tail = (gap - step * (ratio / (1 - ratio))).norm();
    }
    const double along = step.squaredNorm() > 0 ? gap.dot(step) / step.squaredNorm() : 0;
    std::printf("%d,%.3e,%.4f,%.4f,%.3e,%.3e,%.3e\n", snapshots[k].record.step, step.norm(),
                cos_prev, ratio, gap.norm(), after_tail, (gap - along * step).norm());
    previous = step;
  }
}

void PrintCosts(const std::vector<Snapshot>& snapshots) {
  std::printf("# cost\nstep");
  for (const EdgeKind kind : kAllEdgeKinds) std::printf(",%s", EdgeKindName(kind));
  std::printf("\n");
  for (const Snapshot& s : snapshots) {
    if (!s.has_cost) continue;
    std::printf("%d", s.record.step);
    for (const double c : s.cost) std::printf(",%.6f", c);
    std::printf("\n");
  }
}

// The variables farthest (in rotation, then translation) from their final values at the first
// accepted step whose cost is within 1e-6 of the final cost.
void PrintLate(const Graph& graph, const std::vector<Snapshot>& snapshots, int top) {
  const double final_cost = snapshots.back().record.trial_cost;
  const Snapshot* late = &snapshots.back();
  for (const Snapshot& s : snapshots) {
    if (s.record.trial_cost <= final_cost * (1 + 1e-6)) {
      late = &s;
      break;
    }
  }
  struct Row {
    double rotation, translation;
    VertexId id;
  };
  std::vector<Row> rows;
  size_t i = 0;
  for (const auto& [id, v] : graph.vertices) {
    const auto [r, t] = Distance(v.type, late->values[i], snapshots.back().values[i]);
    rows.push_back({r, t, id});
    ++i;
  }
  std::sort(rows.begin(), rows.end(), [](const Row& a, const Row& b) {
    return std::tie(a.rotation, a.translation) > std::tie(b.rotation, b.translation);
  });
  std::printf("# late (step %d, cost %.10f, final %.10f)\nid,role,object,frame,rotation_rad,"
              "translation_m\n", late->record.step, late->record.trial_cost, final_cost);
  for (int k = 0; k < top && k < static_cast<int>(rows.size()); ++k) {
    const Vertex& v = *graph.Find(rows[k].id);
    std::printf("%lld,%s,%lld,%lld,%.3e,%.3e\n", static_cast<long long>(rows[k].id),
                RoleName(v.label.role), static_cast<long long>(v.label.object),
                static_cast<long long>(v.label.frame), rows[k].rotation, rows[k].translation);
  }
}

int Run(const Args& args) {
  Expected<Graph> graph = ReadGraph(args.graph);
  if (!graph.ok()) {
    std::fprintf(stderr, "%s\n", graph.error().ToString().c_str());
    return 2;
  }
  std::vector<Snapshot> snapshots;
  auto snapshot = [&](const StepRecord& record, const Graph& state) {
    Snapshot s;
    s.record = record;
    for (const auto& [id, v] : state.vertices) s.values.push_back(v.value);
    if (snapshots.size() % args.cost_every == 0) {
      Expected<CostByKind> cost = EvaluateCost(state, args.options);
      s.has_cost = cost.ok();
      if (cost.ok()) s.cost = *cost;
    }
    snapshots.push_back(std::move(s));
  };
  SolverOptions options = args.options;
  options.on_accepted_state = snapshot;
  Graph solved = *graph;
  Expected<SolveReport> report = Solve(options, &solved);
  if (!report.ok()) {
    std::fprintf(stderr, "%s\n", report.error().ToString().c_str());
    return 1;
  }
  if (snapshots.empty()) {
    std::fprintf(stderr, "no accepted step\n");
    return 1;
  }
  if (!snapshots.back().has_cost) {
    Expected<CostByKind> cost = EvaluateCost(solved, args.options);
    snapshots.back().has_cost = cost.ok();
    if (cost.ok()) snapshots.back().cost = *cost;
  }
  std::printf("# %s: final cost %.10f, %d steps, %d accepted, %s\n", args.graph.c_str(),
              report->final_cost, report->steps, report->iterations, report->termination.c_str());
  PrintSteps(report->convergence);
  PrintGaps(*graph, snapshots);
  PrintDirections(*graph, snapshots);
  PrintCosts(snapshots);
  PrintLate(*graph, snapshots, args.top);
  return 0;
}

}  // namespace
}  // namespace dynslam

int main(int argc, char** argv) {
#ifdef DYNSLAM_INLINE_OPENMP_REGIONS
  dynslam::InlineOneThreadOpenMpRegions();  // CHOLMOD's regions as `dynslam solve` runs them
#endif
  using dynslam::cli::ArgParser;
  dynslam::Args args;
  ArgParser parser("convergence_probe GRAPH [solver options] [--cost-every N] [--top N]",
                   "Where a solve's steps go (docs/CONVERGENCE.md): CSV blocks on stdout.");
  parser.AddPositional("GRAPH", &args.graph, "graph file (SPEC §1)");
  auto integer = [](int* target, int64_t min) {
    return [target, min](const std::string& text) {
      int64_t value = 0;
      std::optional<std::string> problem = dynslam::ParseInteger(text, min, 1 << 30, &value);
      if (!problem) *target = static_cast<int>(value);
      return problem;
    };
  };
  parser.AddValue("cost-every", "N", "the cost per edge kind every N accepted steps",
                  std::to_string(args.cost_every), integer(&args.cost_every, 1));
  parser.AddValue("top", "N", "how many of the variables that move last to name",
                  std::to_string(args.top), integer(&args.top, 0));
  dynslam::cli::TableFlags<dynslam::SolverOptions> solver_flags(&parser,
                                                               dynslam::SolverOptionTable());
  if (std::optional<int> exit_code = parser.Parse(argc, argv, 1)) return *exit_code;
  if (dynslam::cli::ReportedProblem(solver_flags.Finish(&args.options))) {
    return dynslam::cli::kExitBadInput;
  }
  return dynslam::Run(args);
}
