// Solve a graph file with dynslam's defaults and print the cost per edge kind.
//   examples/solve_graph GRAPH.g2o
#include <cstdio>

#include "dynslam/graph_io.h"
#include "dynslam/solver.h"

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: solve_graph GRAPH.g2o\n");
    return 2;
  }
  dynslam::Expected<dynslam::Graph> graph = dynslam::ReadGraph(argv[1]);
  if (!graph.ok()) {  // file:line: problem
    std::fprintf(stderr, "%s\n", graph.error().ToString().c_str());
    return 2;
  }
  dynslam::SolverOptions options;  // auto solver choice per graph (solver.h), tolerances 1e-12
  dynslam::Expected<dynslam::SolveReport> report = dynslam::Solve(options, &*graph);
  if (!report.ok()) {  // e.g. no prior (gauge freedom): set options.fix_first
    std::fprintf(stderr, "%s\n", report.error().ToString().c_str());
    return 2;
  }
  for (const dynslam::EdgeKind kind : dynslam::kAllEdgeKinds) {
    const int k = static_cast<int>(kind);
    if (report->edges_by_kind[k] == 0) continue;
    std::printf("%-14s %7lld edges  %14.6f -> %14.6f\n", dynslam::EdgeKindName(kind),
                static_cast<long long>(report->edges_by_kind[k]), report->initial_cost_by_kind[k],
                report->final_cost_by_kind[k]);
  }
  std::printf("total %.10g -> %.10g in %d iterations (%s)\n", report->initial_cost,
              report->final_cost, report->iterations, report->termination.c_str());
  // graph now holds the solution: dynslam::WriteGraph(*graph, "solution.g2o");
  return report->usable ? 0 : 1;
}
