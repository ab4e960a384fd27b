// How a solve runs: SolverOptions and its option table (options.h), the one place where each
// solver option is named, explained and checked. docs/OPTIONS.md is generated from the table;
// docs/SOLVER.md gives the reasons behind the defaults.
#ifndef DYNSLAM_SOLVER_OPTIONS_H_
#define DYNSLAM_SOLVER_OPTIONS_H_

#include <array>
#include <functional>
#include <optional>
#include <string>

#include "dynslam/graph_schema.h"
#include "dynslam/options.h"

namespace dynslam {

// kAuto chooses per graph (ResolveAuto, solver.h).
enum class MinimizerType { kLevenbergMarquardt, kDogleg, kDynslamLm, kAuto };
enum class LinearSolverType {
  kSparseSchur,
  kSparseNormalCholesky,
  kIterativeSchur,
  kDenseSchur,
  kAuto,
};
enum class SparseBackend { kSuiteSparse, kEigen, kAuto };
// The frame a variable or residual is expressed in.
enum class Frame { kWorld, kObject };

// The spellings of the option table: "lm", "dogleg"; "sparse_schur", …; "suitesparse", "eigen";
// "auto"; "world", "object".
const char* Name(MinimizerType type);
const char* Name(LinearSolverType type);
const char* Name(SparseBackend backend);
const char* Name(Frame frame);

// ρ of SPEC §1.5 for one edge kind. Huber(k) and Cauchy(k) are Ceres's HuberLoss(k) and
// CauchyLoss(k) applied to the squared whitened residual.
struct RobustKernel {
  enum class Type { kNone, kHuber, kCauchy };
  Type type = Type::kNone;
  double threshold = 1.0;
};
// Indexed by static_cast<int>(EdgeKind); none by default (SPEC §1.5).
using RobustKernels = std::array<RobustKernel, kNumEdgeKinds>;
// "point=huber:1.345,dynamic_point=cauchy:2" (kinds by their SPEC §1.5 names); "" for none.
std::string RobustText(const RobustKernels& kernels);
std::optional<std::string> ParseRobust(const std::string& text, RobustKernels* kernels);
std::string RobustKindNames();  // the edge kinds' names, space-separated

struct StepRecord;
struct Graph;

// Every field is an option of SolverOptionTable() below, which says what it does; the callbacks
// at the end are for programs, not users.
struct SolverOptions {
  MinimizerType minimizer = MinimizerType::kAuto;
  LinearSolverType linear_solver = LinearSolverType::kAuto;
  SparseBackend sparse_backend = SparseBackend::kAuto;
  int threads = 1;
  int max_iterations = 500;  // GTSAM tight profile's maxIterations (SPEC §6)
  double max_time = 0;
  double function_tolerance = 1e-12;
  double gradient_tolerance = 1e-12;
  double parameter_tolerance = 1e-12;
  double remaining_chi2 = 0.01;
  double absolute_decrease = 0;  // 0: off
  bool extrapolation = true;
  bool gauge_moves = false;
  double initial_lambda = 0;    // 0: auto
  bool jacobi_scaling = true;
  int nonmonotonic_steps = -1;  // −1: auto
  int secant_memory = -1;       // −1: auto
  bool eliminate_object_points = false;
  Frame object_point_variables = Frame::kWorld;
  Frame kinematic_residual_frame = Frame::kWorld;
  bool fix_first = false;
  RobustKernels robust{};
  // SPEC §7, the released code's choices (never defaults; --compat sets them).
  bool dsc_motion_residual = false;
  double dsc_motion_sigma = 0.1;
  bool dsc_object_motion_residual = false;
  bool dsc_released_lm = false;

  // Polled before the first step and after every step: when it returns true the solve ends
  // there, usable, with termination "interrupted", at the last accepted state (with
  // non-monotonic steps on, Ceres's lowest-cost accepted state). The command line sets it from
  // SIGINT/SIGTERM; the library itself installs no signal handler.
  std::function<bool()> should_stop;
  // Called after every linear solve Ceres reports (rejected ones included).
  std::function<void(const StepRecord&)> on_step;
  // For analysis (benchmarks/convergence_probe): called after every accepted step with a copy of
  // the graph holding the values reached. Costs a copy of every value per step; off when empty.
  std::function<void(const StepRecord&, const Graph&)> on_accepted_state;
};

// The tight rule (`tolerances = tight`, the reference tests): Ceres's tolerances alone, no
// remaining-χ² stop, no extrapolation and no gauge move — the path GTSAM's tight LM also takes.
inline SolverOptions TightRule(SolverOptions options) {
  options.remaining_chi2 = 0;
  options.extrapolation = false;
  options.gauge_moves = false;
  return options;
}

// The option table of SolverOptions. Groups: "solver" (how each step is computed), "stopping",
// "model" (how the graph is put to Ceres: same cost and optimum), "compatibility" (SPEC §7).
inline const OptionTable<SolverOptions>& SolverOptionTable() {
  using O = SolverOptions;
  static const OptionTable<O> table = [] {
    OptionTable<O> t = {
        Choice("minimizer", "solver", &O::minimizer,
               {MinimizerType::kAuto, MinimizerType::kLevenbergMarquardt, MinimizerType::kDogleg,
                MinimizerType::kDynslamLm},
               Name,
               "trust-region strategy: Ceres's Levenberg-Marquardt or Powell's dogleg, or "
               "dynslam_lm: dynslam's own LM loop over the same cost functions (CHOLMOD, "
               "secant_memory, no extrapolation or gauge moves yet; docs/SOLVER.md); auto: lm "
               "for oc_a, oc_b, oc_c and pose graphs, dogleg for wc, hy and other graphs with "
               "points"),
        Choice("linear_solver", "solver", &O::linear_solver,
               {LinearSolverType::kAuto, LinearSolverType::kSparseSchur,
                LinearSolverType::kSparseNormalCholesky, LinearSolverType::kIterativeSchur,
                LinearSolverType::kDenseSchur},
               Name,
               "linear solver of each step; the Schur solvers eliminate points first; auto: "
               "sparse_normal_cholesky"),
        Choice("sparse_backend", "solver", &O::sparse_backend,
               {SparseBackend::kAuto, SparseBackend::kSuiteSparse, SparseBackend::kEigen}, Name,
               "sparse Cholesky library (CHOLMOD or Eigen's SimplicialLDLT); auto: suitesparse "
               "when Ceres has it, else eigen"),
        Integer("threads", "solver", &O::threads,
                "threads for residual evaluation and linear algebra", 1, 256),
        Real("initial_lambda", "solver", &O::initial_lambda,
             "first LM damping, relative to diag(JᵀJ) (Ceres: 1 / initial trust-region radius); "
             "0: 1e-6 for graphs with points, 1e-10 for pose graphs",
             0, 1e16),
        Switch("jacobi_scaling", "solver", &O::jacobi_scaling,
               "LM damps with lambda·diag(JᵀJ) and dogleg's trust region is scaled by it "
               "(Ceres's way); off: lambda·I, GTSAM's LM damping, and an unscaled trust region "
               "(docs/CONVERGENCE.md §11)"),
        Integer("nonmonotonic_steps", "solver", &O::nonmonotonic_steps,
                "accept a step that raises the cost while it stays below the best of the last N "
                "accepted ones (Ceres's non-monotonic steps); -1: 5 for graphs with kinematic "
                "edges and kinematic_residual_frame object, else 0",
                -1, 1000),
        Integer("secant_memory", "solver", &O::secant_memory,
                "dynslam_lm: add to Gauss-Newton's model the curvature it leaves out, estimated "
                "from the last N accepted steps (structured secant, docs/SOLVER.md); 0: off; "
                "-1: 2 with dynslam_lm, else 0",
                -1, 64),
        Aliased({"extrapolate"}, Switch("extrapolation", "solver", &O::extrapolation,
               "when two accepted steps in a row gain at least 1.5x what their model predicted, "
               "try moving on along them 2, 4, 8, ... (at most 64) times as far while the cost "
               "falls, and try the same before a remaining_chi2 stop; only ever lowers the cost "
               "(docs/SOLVER.md)")),
        Aliased({"snap_segment_gauges"}, Switch("gauge_moves", "solver", &O::gauge_moves,
               "object-centric graphs: when a good step gains less than the object priors still "
               "cost, move each object segment rigidly so that its prior is met, kept only if "
               "the cost falls (docs/CONVERGENCE.md)")),
        Integer("max_iterations", "stopping", &O::max_iterations,
                "stop after this many linear solves (termination no_convergence)", 0, 1000000),
        Aliased({"max_time_s"}, Real("max_time", "stopping", &O::max_time,
             "stop after this many seconds, set-up included, checked between steps, and keep "
             "the solve as it stands (termination time_limit); 0: no limit",
             0, 1e9)),
        Real("function_tolerance", "stopping", &O::function_tolerance,
             "stop when |cost change| / cost is below this", 0, 1),
        Real("gradient_tolerance", "stopping", &O::gradient_tolerance,
             "stop when the max-norm of the projected gradient is below this", 0, 1),
        Real("parameter_tolerance", "stopping", &O::parameter_tolerance,
             "stop when the step is this small relative to the parameters", 0, 1),
        Real("remaining_chi2", "stopping", &O::remaining_chi2,
             "after two accepted steps in a row, stop once the chi2 (twice the cost) still to "
             "gain is estimated at most this: every variable then within sqrt(X) of its "
             "marginal sigma of the optimum; 0: off (docs/SOLVER.md)",
             0, 1e300),
        Real("absolute_decrease", "stopping", &O::absolute_decrease,
             "stop after an accepted step that lowered the cost by at most this (GTSAM's "
             "absoluteErrorTol); 0: off",
             0, 1e300),
        Switch("eliminate_object_points", "model", &O::eliminate_object_points,
               "Schur solvers: eliminate object-frame points first too (static and per-frame "
               "points always are)"),
        Choice("object_point_variables", "model", &O::object_point_variables,
               {Frame::kWorld, Frame::kObject}, Name,
               "what the solver varies for an object-frame point m_L: its world position "
               "L_a·m_L at an anchor pose (the same cost and optimum, fewer steps), or m_L "
               "itself (docs/CONVERGENCE.md)"),
        Choice("kinematic_residual_frame", "model", &O::kinematic_residual_frame,
               {Frame::kWorld, Frame::kObject}, Name,
               "frame of the object kinematic edge's whitened residual: turned into the world by "
               "the object's rotation (the same norm, cost and optimum, fewer steps), or as SPEC "
               "§1.3 writes it"),
        Switch("fix_first", "model", &O::fix_first,
               "hold the smallest-id pose constant (needed when the graph has no prior, SPEC "
               "§1.7)"),
        Switch("dsc_motion_residual", "compatibility", &O::dsc_motion_residual,
               "SPEC §7 item 2: EDGE_SE3_MOTION as (m_prev - H⁻¹·m_curr)/sigma, ignoring the "
               "file's information"),
        Real("dsc_motion_sigma", "compatibility", &O::dsc_motion_sigma,
             "the sigma of dsc_motion_residual", 1e-12, 1e12),
        Switch("dsc_object_motion_residual", "compatibility", &O::dsc_object_motion_residual,
               "SPEC §7 item 6: EDGE_SE3_OBJ_MOTION as L_curr⁻¹·H·L_prev·m_L"),
        Switch("dsc_released_lm", "compatibility", &O::dsc_released_lm,
               "SPEC §7 item 7: the released code's GTSAM Levenberg-Marquardt: damping from "
               "1e-5, giving up at 1e5, stopping at a relative change of 1e-5 or after 100 "
               "steps (docs/COMPAT.md)"),
    };
    Option<O> robust = Declare<O>("robust", "model", OptionType::kText,
                                  "robust kernels per edge kind (SPEC §1.5), e.g. "
                                  "point=huber:1.345,dynamic_point=cauchy:2; kinds: " +
                                      RobustKindNames(),
                                  "KIND=TYPE:K,...");
    robust.get = [](const O& o) { return RobustText(o.robust); };
    robust.set = [](const std::string& text, O* o) { return ParseRobust(text, &o->robust); };
    t.push_back(robust);
    Option<O> tolerances = Declare<O>(
        "tolerances", "stopping", OptionType::kPreset,
        "tight: Ceres's three tolerances alone, no remaining_chi2 rule, no extrapolation and no "
        "gauge moves (to the optimum to ~1e-10 relative; the reference tests); gtsam: the stop "
        "of GTSAM's Levenberg-Marquardt defaults, relative and absolute decrease 1e-5, at most "
        "100 steps, without remaining_chi2, extrapolation or gauge moves",
        "default|tight|gtsam");
    tolerances.values = {"default", "tight", "gtsam"};
    tolerances.sets = {"remaining_chi2", "extrapolation", "gauge_moves", "function_tolerance",
                       "absolute_decrease", "max_iterations"};
    tolerances.get = [](const O&) { return std::string("default"); };
    tolerances.set = [](const std::string& text, O* o) -> std::optional<std::string> {
      if (text == "tight" || text == "gtsam") *o = TightRule(*o);
      if (text == "gtsam") {  // GTSAM 4.2 LevenbergMarquardtParams' defaults
        o->function_tolerance = 1e-5;
        o->absolute_decrease = 1e-5;
        o->max_iterations = 100;
      } else if (text != "tight" && text != "default") {  // default: the options as they are
        return "'" + text + "' is not one of default|tight|gtsam";
      }
      return std::nullopt;
    };
    t.push_back(tolerances);
    return t;
  }();
  return table;
}

}  // namespace dynslam

#endif  // DYNSLAM_SOLVER_OPTIONS_H_
