// Assemble a ceres::Problem from a Graph and solve it (SPEC §1.5, §1.7, §4).
//
// Every edge becomes one autodiff cost function of cost_functions/ over the SE(3) manifold
// (se3_manifold.h); robust kernels are chosen per edge kind (SPEC §1.5). Points that no
// residual joins to another point are eliminated first by the Schur solvers. The solver works
// on its own copy of the values and writes the optimum back into the Graph.
#ifndef DYNSLAM_SOLVER_H_
#define DYNSLAM_SOLVER_H_

#include <array>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include <Eigen/SparseCore>

#include "dynslam/graph.h"
#include "dynslam/solver_options.h"
#include "dynslam/status.h"

namespace dynslam {

// One row of convergence.csv (SPEC §4).
struct StepRecord {
  int step = 0;       // from 1: linear solves, extrapolations and gauge moves
  int iteration = 0;  // 1 + accepted steps before this one
  double lambda = 0;  // LM damping; for dogleg 1/radius
  double cost = 0;    // before the step
  double trial_cost = 0;  // at the trial point; +inf when the step was not valid
  bool accepted = false;
  double time_s = 0;  // since the minimiser started (problem set-up excluded)
  // Not in convergence.csv (SPEC §4); for analysis. Ceres's step quality ρ: actual / predicted
  // decrease (with non-monotonic steps, the larger of that and the decrease relative to the
  // reference cost). 0 for invalid steps; for an extrapolation, the factor it moved by.
  double relative_decrease = 0;
  // Not in convergence.csv; the 2-norm of the step in the variables' tangent spaces (rad and m);
  // 0 for an extrapolation.
  double step_norm = 0;
  // A move along the previous step (SolverOptions::extrapolation), not a linear solve: lambda 0.
  bool extrapolation = false;
  // A move of the object segments' gauges (SolverOptions::gauge_moves), not a linear
  // solve: lambda 0.
  bool gauge_move = false;
};

using CostByKind = std::array<double, kNumEdgeKinds>;

struct SolveReport {
  std::array<int64_t, kAllRoles.size()> variables_by_role{};  // order of kAllRoles
  int64_t unused_variables = 0;  // in no edge: held constant (SPEC §1.6)
  std::array<int64_t, kNumEdgeKinds> edges_by_kind{};
  double initial_cost = 0;
  double final_cost = 0;
  CostByKind initial_cost_by_kind{};
  CostByKind final_cost_by_kind{};
  int iterations = 0;  // accepted steps
  int steps = 0;       // linear solves Ceres reported
  int extrapolations = 0;  // SolverOptions::extrapolation rows
  int gauge_moves = 0;     // SolverOptions::gauge_moves rows; convergence has steps +
                           // extrapolations + these rows
  // "convergence", "no_convergence" (max_iterations), "interrupted" (should_stop),
  // "time_limit" (max_time) or "failure"; all but "failure" leave a usable solution.
  std::string termination;
  std::string termination_detail;  // Ceres's message
  std::string ceres_report;        // Ceres's Summary::FullReport() (problem sizes, phase times)
  bool usable = false;             // Ceres says the solution is usable
  double time_total_s = 0;              // ceres::Solve, preprocessing included
  double time_minimizer_s = 0;
  double time_evaluation_s = 0;         // residuals and Jacobians
  double time_linear_solver_s = 0;
  double time_preprocessor_s = 0;
  std::string eliminated_first;         // what the Schur ordering put in the first group
  SolverOptions options_used;           // the options with every auto resolved (ResolveAuto)
  // summary.json's "solver" entry as JSON text when another backend solved (gtsam_backend.h);
  // empty: the entry is options_used.
  std::string solver_json;
  std::vector<VertexId> held_constant;  // unused vertices and, with fix_first, the first pose
  std::vector<StepRecord> convergence;
  std::vector<std::string> warnings;
};

// `options` with every auto field resolved for `graph`: minimizer, linear solver and sparse
// backend (MinimizerType::kAuto), initial_lambda (0), nonmonotonic_steps (−1).
SolverOptions ResolveAuto(const SolverOptions& options, const Graph& graph);

// The SPEC §1.5 cost of the graph at its current values, in total (sum) and per edge kind.
// Needs roles assigned. Errors for graphs the solver would refuse (bad references, …).
Expected<CostByKind> EvaluateCost(const Graph& graph, const SolverOptions& options = {});

// The Jacobian of the whitened residuals (SPEC §1.5) at the graph's values, taken in the
// tangent space of each variable (6 columns for a pose, [ω; ρ] as SE3Manifold; 3 for a point),
// as the solver sees it (with object_point_variables world, an object-frame point's columns are
// those of w = L_a · m_L). Columns are grouped by variable in ascending vertex id; vertices in no
// edge and vertices constant by their role (hy's embedded frames) are not variables and have no
// columns. For analysis, benchmarks (the factorisation floor of docs/BENCHMARKS.md) and the
// information matrix of covariance.h.
struct SystemJacobian {
  Eigen::SparseMatrix<double, Eigen::RowMajor> jacobian;
  std::vector<VertexId> variables;  // the vertex of each column group, ascending
  std::vector<int> first_column;    // first column of each group (size = variables.size() + 1)
  // The groups the Schur solvers eliminate first with `options` (SolveReport::eliminated_first).
  std::vector<bool> eliminated_first;
};
Expected<SystemJacobian> EvaluateJacobian(const Graph& graph, const SolverOptions& options = {});

// Solves and writes the solution into `graph`'s vertices. An Error means nothing was solved
// (gauge freedom, invalid options, a malformed graph); a solve that ran but failed returns a
// report with usable == false (the graph then holds Ceres's best values).
Expected<SolveReport> Solve(const SolverOptions& options, Graph* graph);

double TotalCost(const CostByKind& cost_by_kind);

}  // namespace dynslam

#endif  // DYNSLAM_SOLVER_H_
