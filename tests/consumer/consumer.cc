// Adds dynslam's residuals and SE(3) manifold to its own ceres::Problem, solves a small pose
// graph, and checks the answer against dynslam::Solve on the same file. Exit 0 on success.
#include <cstdio>

#include <ceres/ceres.h>

#include "cost_functions/pose_between_error.h"
#include "cost_functions/pose_prior_error.h"
#include "dynslam/graph_io.h"
#include "dynslam/se3_manifold.h"
#include "dynslam/solver.h"

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: consumer POSE_GRAPH.g2o\n");
    return 2;
  }
  dynslam::Expected<dynslam::Graph> graph = dynslam::ReadGraph(argv[1]);
  if (!graph.ok()) {
    std::fprintf(stderr, "%s\n", graph.error().ToString().c_str());
    return 2;
  }
  dynslam::Graph own = *graph;
  ceres::Problem problem;
  dynslam::SE3Manifold* manifold = new dynslam::SE3Manifold();  // the problem owns it
  for (auto& [id, vertex] : own.vertices) problem.AddParameterBlock(vertex.value.data(), 7, manifold);
  for (const dynslam::PriorEdge& e : own.Edges<dynslam::PriorEdge>()) {
    problem.AddResidualBlock(dynslam::PosePriorError::Create(e.measurement, e.information),
                             nullptr, own.Find(e.pose)->value.data());
  }
  for (const dynslam::BetweenEdge& e : own.Edges<dynslam::BetweenEdge>()) {
    problem.AddResidualBlock(dynslam::PoseBetweenError::Create(e.measurement, e.information),
                             nullptr, own.Find(e.from)->value.data(), own.Find(e.to)->value.data());
  }
  ceres::Solver::Options options;
  options.linear_solver_type = ceres::SPARSE_NORMAL_CHOLESKY;
  options.function_tolerance = 1e-12;
  options.gradient_tolerance = 1e-12;
  options.parameter_tolerance = 1e-12;
  options.max_num_iterations = 200;
  ceres::Solver::Summary summary;
  ceres::Solve(options, &problem, &summary);

  dynslam::Expected<dynslam::SolveReport> report = dynslam::Solve({}, &*graph);
  if (!report.ok()) {
    std::fprintf(stderr, "%s\n", report.error().ToString().c_str());
    return 1;
  }
  std::printf("own problem: %.12g -> %.12g; dynslam::Solve: %.12g -> %.12g\n",
              summary.initial_cost, summary.final_cost, report->initial_cost, report->final_cost);
  const double gap = std::abs(summary.final_cost - report->final_cost);
  return summary.IsSolutionUsable() && gap <= 1e-6 * report->final_cost + 1e-12 ? 0 : 1;
}
