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
#include "dynslam/status.h"

namespace dynslam {

// kAuto (the defaults) chooses per graph (ResolveAuto): sparse normal Cholesky on SuiteSparse
// (Eigen if this Ceres lacks it) for every graph; Powell's dogleg for wc and hy (the formulation
// table's rule, formulation.h) and other graphs with point variables, Levenberg–Marquardt for
// oc_a, oc_b, oc_c and pose graphs
// — per class, the fastest to the optimum in the benchmarks that also stays out of the poor
// basins seen on simulated scenes (docs/SOLVER.md, docs/BENCHMARKS.md).
enum class MinimizerType { kLevenbergMarquardt, kDogleg, kAuto };
enum class LinearSolverType {
  kSparseSchur,
  kSparseNormalCholesky,
  kIterativeSchur,
  kDenseSchur,
  kAuto,
};
enum class SparseBackend { kSuiteSparse, kEigen, kAuto };

// Command-line spellings: "lm", "dogleg"; "sparse_schur", …; "suitesparse", "eigen"; "auto".
const char* Name(MinimizerType type);
const char* Name(LinearSolverType type);
const char* Name(SparseBackend backend);
bool Parse(const std::string& text, MinimizerType* type);
bool Parse(const std::string& text, LinearSolverType* type);
bool Parse(const std::string& text, SparseBackend* backend);

// ρ of SPEC §1.5 for one edge kind. Huber(k) and Cauchy(k) are Ceres's HuberLoss(k) and
// CauchyLoss(k) applied to the squared whitened residual.
struct RobustKernel {
  enum class Type { kNone, kHuber, kCauchy };
  Type type = Type::kNone;
  double threshold = 1.0;
};

struct SolverOptions {
  MinimizerType minimizer = MinimizerType::kAuto;
  LinearSolverType linear_solver = LinearSolverType::kAuto;
  SparseBackend sparse_backend = SparseBackend::kAuto;
  int threads = 1;
  int max_iterations = 500;  // GTSAM tight profile's maxIterations (SPEC §6)
  // Ceres's tolerances (Solver::Options); tighter than Ceres's defaults so that a solve lands
  // on the optimum to ~1e-10 relative (the GTSAM tight_exact reference, SPEC §6). A function
  // tolerance of 1e-10 saves up to half the steps but leaves motions 0.1–0.2 mm from
  // tight_exact on kitti_0003 wc and synthetic oc_c (docs/SOLVER.md).
  double function_tolerance = 1e-12;
  double gradient_tolerance = 1e-12;
  double parameter_tolerance = 1e-12;
  // The default stopping rule (docs/SOLVER.md "When a solve stops"): after two accepted steps in
  // a row, stop once the χ² (twice the cost) still to be gained is estimated at most this. A χ²
  // gap δ puts every variable, and every function of them, within √δ of its marginal σ of the
  // optimum (to first order), so 0.01 is a tenth of a σ. 0 turns the rule off: the tight rule,
  // Ceres's tolerances alone (`--tolerances tight`; the reference tests).
  double remaining_chi2 = 0.01;
  // The first LM damping, relative to diag(JᵀJ) (Ceres: 1 / initial_trust_region_radius; its
  // default is 1e-4). 0 (auto): 1e-6 for graphs with points, 1e-10 for pose graphs, where the
  // first step is then nearly Gauss–Newton's (docs/SOLVER.md has the measurements).
  double initial_lambda = 0;
  // Ceres's non-monotonic steps: accept a step that raises the cost when the cost is still below
  // the best of the last N accepted steps. −1 (auto): N = 5 when the graph has kinematic edges
  // and world_frame_kinematic_residual is off (there it took 3–5× fewer steps), else 0: with the
  // world-frame residual the monotonic solver has the shorter tail (docs/CONVERGENCE.md).
  int nonmonotonic_steps = -1;
  // When two accepted steps in a row decrease the cost by at least 1.5× what their quadratic
  // model predicted (ρ ≥ 1.5: the model's curvature along the step is too high, and the steps
  // shrink geometrically), try moving on along those two steps 2, 4, 8, … (at most 64) times as
  // far while the cost keeps falling, keep the lowest, and restart Ceres there; the same try is
  // made before the remaining_chi2 rule stops a solve (docs/SOLVER.md "Extrapolation"). Only
  // ever lowers the cost. TightRule turns it off.
  bool extrapolate = true;
  // Object-centric graphs: after an accepted step of quality ρ ≥ 0.75 whose decrease is smaller
  // than what the object segments' priors still cost, move each segment rigidly by the pose
  // that zeroes its prior residual (L_k → L_k·G for all its object poses, m_L → G⁻¹·m_L), keep
  // the move if the total cost falls, and restart Ceres there. In oc_a no other residual
  // changes, so exactly the priors' cost comes off. Only ever lowers the cost; TightRule turns
  // it off. Off by default: on whole KITTI 0020 oc_a it took 410 steps to a stop 15.6 lower
  // than the default's 500, but on 0018 oc_a 5 more steps to the same cost and on 0005 oc_a a
  // stop 3.7 higher (docs/CONVERGENCE.md §7).
  bool snap_segment_gauges = false;
  // Schur solvers: also eliminate object-frame points first. Off by default: each such point is
  // tied to every object pose and motion of its segment, so eliminating it makes the reduced
  // system dense per segment (3× slower linear solves on kitti_0003 oc_b, docs/SOLVER.md).
  bool eliminate_object_points = false;
  // Object-centric graphs: the solver carries each object-frame point m_L as its world position
  // w = L_a · m_L at an anchor pose L_a (the smallest-id object pose of its edges) and writes
  // m_L back. The same cost and optimum in a chart where a segment's gauge is a straight line
  // (docs/CONVERGENCE.md has the measurements). Off: the solver's variables are m_L themselves.
  bool world_anchored_object_points = true;
  // EDGE_SE3_OBJ_KINEMATIC's whitened residual turned into the world frame by L_curr's rotation:
  // the same norm, so the same cost and optimum, but a residual that a segment's gauge rotation
  // leaves unchanged, where the object-frame one turns with it and Gauss–Newton mistakes that
  // for curvature (docs/CONVERGENCE.md).
  bool world_frame_kinematic_residual = true;
  // SPEC §1.7: a graph with no prior is refused unless the smallest-id pose is held constant.
  bool fix_first = false;
  // SPEC §7, the released code's residuals (never defaults): item 2, EDGE_SE3_MOTION as
  // (m_prev − H⁻¹·m_curr)/σ with σ = dsc_motion_sigma, ignoring the file's information and z;
  // item 6, EDGE_SE3_OBJ_MOTION as L_curr⁻¹·H·L_prev·m_L.
  bool dsc_motion_residual = false;
  double dsc_motion_sigma = 0.1;
  bool dsc_object_motion_residual = false;
  // SPEC §7 item 7, the released code's GTSAM Levenberg–Marquardt (docs/COMPAT.md): damping λ·I
  // from λ = 1e-5 (Ceres: Jacobi scaling off, LM diagonal held at 1), giving up once λ ≥ 1e5,
  // stopping at the first step that changes the cost by ≤ 1e-5 relative, or is accepted with a
  // decrease ≤ 1e-5, or after 100 accepted steps. ResolveAuto sets the minimizer (LM),
  // initial_lambda, the tolerances and max_iterations to match. Ceres moves λ by its own rule
  // (÷ at most 3 after a success, × 2, 4, 8, … after failures), GTSAM by a fixed factor of 10.
  bool dsc_released_lm = false;
  // Indexed by static_cast<int>(EdgeKind); none by default (SPEC §1.5).
  std::array<RobustKernel, kNumEdgeKinds> kernels{};
  // Polled before the first step and after every step: when it returns true the solve ends
  // there, usable, with termination "interrupted", at the last accepted state (with
  // non-monotonic steps on, Ceres's lowest-cost accepted state). The command
  // line sets it from SIGINT/SIGTERM; the library itself installs no signal handler.
  std::function<bool()> should_stop;
  // Seconds from the start of Solve (set-up included) after which the solve ends as with
  // should_stop, with termination "time_limit"; 0: no limit. Checked between steps, so a solve
  // overruns the limit by at most one step.
  double max_time_s = 0;
  // Called after every linear solve Ceres reports (rejected ones included).
  std::function<void(const struct StepRecord&)> on_step;
  // For analysis (benchmarks/convergence_probe): called after every accepted step with a copy of
  // the graph holding the values reached. Costs a copy of every value per step; off when empty.
  std::function<void(const struct StepRecord&, const Graph&)> on_accepted_state;
};

// The tight rule (`--tolerances tight`, the reference tests): Ceres's tolerances alone, no
// remaining-χ² stop, no extrapolation and no gauge move — the path GTSAM's tight LM also takes.
inline SolverOptions TightRule(SolverOptions options) {
  options.remaining_chi2 = 0;
  options.extrapolate = false;
  options.snap_segment_gauges = false;
  return options;
}

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
  // A move along the previous step (SolverOptions::extrapolate), not a linear solve: lambda 0.
  bool extrapolation = false;
  // A move of the object segments' gauges (SolverOptions::snap_segment_gauges), not a linear
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
  int extrapolations = 0;  // SolverOptions::extrapolate rows
  int gauge_moves = 0;     // SolverOptions::snap_segment_gauges rows; convergence has steps +
                           // extrapolations + these rows
  // "convergence", "no_convergence" (max_iterations), "interrupted" (should_stop),
  // "time_limit" (max_time_s) or "failure"; all but "failure" leave a usable solution.
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
// as the solver sees it (with world_anchored_object_points, an object-frame point's columns are
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
