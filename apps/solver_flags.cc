#include "solver_flags.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>

namespace dynslam::cli {
namespace {

// "kind=huber:1.5,kind=cauchy:2" → options->kernels.
std::optional<std::string> ParseRobust(const std::string& text, SolverOptions* options) {
  std::stringstream items(text);
  std::string item;
  while (std::getline(items, item, ',')) {
    if (item.empty()) continue;
    const size_t eq = item.find('=');
    const size_t colon = item.find(':', eq == std::string::npos ? 0 : eq);
    if (eq == std::string::npos || colon == std::string::npos) {
      return "--robust: '" + item + "' is not KIND=huber:K or KIND=cauchy:K";
    }
    const std::string kind_name = item.substr(0, eq);
    const std::string type = item.substr(eq + 1, colon - eq - 1);
    const std::string threshold_text = item.substr(colon + 1);
    int kind = -1;
    for (const EdgeKind k : kAllEdgeKinds) {
      if (kind_name == EdgeKindName(k)) kind = static_cast<int>(k);
    }
    if (kind < 0) return "--robust: unknown edge kind '" + kind_name + "'";
    RobustKernel kernel;
    if (type == "huber") {
      kernel.type = RobustKernel::Type::kHuber;
    } else if (type == "cauchy") {
      kernel.type = RobustKernel::Type::kCauchy;
    } else {
      return "--robust: unknown kernel '" + type + "' (huber or cauchy)";
    }
    char* end = nullptr;
    kernel.threshold = std::strtod(threshold_text.c_str(), &end);
    if (threshold_text.empty() || *end != '\0' || !(kernel.threshold > 0) ||
        !std::isfinite(kernel.threshold)) {
      return "--robust: threshold '" + threshold_text + "' is not a positive number";
    }
    options->kernels[kind] = kernel;
  }
  return std::nullopt;
}

}  // namespace

SolverFlags::SolverFlags(ArgParser* parser)
    : minimizer_(Name(defaults_.minimizer)),
      linear_solver_(Name(defaults_.linear_solver)),
      sparse_backend_(Name(defaults_.sparse_backend)),
      threads_(defaults_.threads),
      max_iterations_(defaults_.max_iterations),
      max_time_(defaults_.max_time_s),
      function_tolerance_(defaults_.function_tolerance),
      gradient_tolerance_(defaults_.gradient_tolerance),
      parameter_tolerance_(defaults_.parameter_tolerance),
      remaining_chi2_(defaults_.remaining_chi2),
      initial_lambda_(defaults_.initial_lambda),
      nonmonotonic_steps_(defaults_.nonmonotonic_steps),
      fix_first_(defaults_.fix_first),
      eliminate_object_points_(defaults_.eliminate_object_points),
      parser_(parser) {
  parser->AddChoice("minimizer", &minimizer_, {"auto", "lm", "dogleg"},
                    "trust-region strategy: Levenberg-Marquardt or Powell's dogleg; auto: dogleg "
                    "for wc and hy (and other graphs with points), else lm");
  parser->AddChoice("linear-solver", &linear_solver_,
                    {"auto", "sparse_schur", "sparse_normal_cholesky", "iterative_schur",
                     "dense_schur"},
                    "linear solver of each step; the Schur solvers eliminate points first; auto: "
                    "sparse_normal_cholesky");
  parser->AddChoice("sparse-backend", &sparse_backend_, {"auto", "suitesparse", "eigen"},
                    "sparse Cholesky library (CHOLMOD or Eigen's SimplicialLDLT); auto: "
                    "suitesparse when Ceres has it, else eigen");
  parser->AddInt("threads", &threads_, "threads for evaluation and linear algebra", 1, 256);
  parser->AddInt("max-iterations", &max_iterations_, "most linear solves", 0, 1000000);
  parser->AddDouble("max-time", &max_time_,
                    "stop a solve after this many seconds (checked between steps) and save it "
                    "as it stands: termination time_limit; 0: no limit",
                    0, 1e9);
  parser->AddDouble("function-tolerance", &function_tolerance_,
                    "stop when |cost change| / cost is below this", 0, 1);
  parser->AddDouble("gradient-tolerance", &gradient_tolerance_,
                    "stop when the max-norm of the projected gradient is below this", 0, 1);
  parser->AddDouble("parameter-tolerance", &parameter_tolerance_,
                    "stop when the step is this small relative to the parameters", 0, 1);
  parser->AddDouble("remaining-chi2", &remaining_chi2_,
                    "stop once the chi2 (twice the cost) still to gain is estimated at most "
                    "this: every variable within sqrt(X) of its marginal sigma of the optimum; "
                    "0: off (docs/SOLVER.md)",
                    0, 1e300);
  parser->AddChoice("tolerances", &tolerances_, {"default", "tight"},
                    "tight: no --remaining-chi2 rule, no --extrapolation and no "
                    "--gauge-moves, only the three "
                    "tolerances (to the optimum to ~1e-10 relative; the reference tests)");
  parser->AddChoice("extrapolation", &extrapolation_, {"on", "off"},
                    "on: when two steps in a row gain 1.5x what their model predicted, try "
                    "moving on along them 2, 4, 8, ... times as far, and do so before a "
                    "--remaining-chi2 stop (docs/SOLVER.md)");
  parser->AddChoice("gauge-moves", &gauge_moves_, {"on", "off"},
                    "on: object-centric graphs, when a good step gains less than the object "
                    "priors still cost, move each object segment rigidly so that its prior is "
                    "met (kept only if the cost falls; off by default: docs/CONVERGENCE.md §7)");
  parser->AddDouble("initial-lambda", &initial_lambda_,
                    "first LM damping, relative to diag(JᵀJ) (Ceres: 1 / initial trust-region "
                    "radius); 0: 1e-6 for graphs with points, 1e-10 for pose graphs",
                    0, 1e16);
  parser->AddInt("nonmonotonic-steps", &nonmonotonic_steps_,
                 "accept up to N consecutive steps that raise the cost (Ceres's non-monotonic "
                 "steps); -1: 5 when the graph has kinematic edges (oc_b, oc_c) and "
                 "--kinematic-residual-frame object, else 0",
                 -1, 1000);
  parser->AddFlag("eliminate-object-points", &eliminate_object_points_,
                  "Schur solvers: eliminate object-frame points first too (slower on the "
                  "reference scenes; static points are always eliminated first)");
  parser->AddChoice("object-point-variables", &object_point_variables_, {"world", "object"},
                    "what the solver varies for an object-frame point: its world position at "
                    "an anchor pose (the same cost and optimum, far fewer steps), or its "
                    "object-frame coordinates (docs/CONVERGENCE.md)");
  parser->AddChoice("kinematic-residual-frame", &kinematic_residual_frame_, {"world", "object"},
                    "frame of the object kinematic edge's whitened residual: turned into the "
                    "world by the object's rotation (the same cost and optimum, fewer steps), or "
                    "as SPEC §1.3 writes it (docs/CONVERGENCE.md)");
  parser->AddFlag("fix-first", &fix_first_,
                  "hold the smallest-id pose constant (needed when the graph has no prior)");
  std::string kinds;
  for (const EdgeKind kind : kAllEdgeKinds) {
    kinds += std::string(kinds.empty() ? "" : " ") + EdgeKindName(kind);
  }
  parser->AddString("robust", &robust_,
                    "robust kernels per edge kind, e.g. point=huber:1.345,dynamic_point=cauchy:2 "
                    "(kinds: " + kinds + ")",
                    "KIND=TYPE:K,...");
}

std::optional<std::string> SolverFlags::Finish(SolverOptions* options) const {
  *options = defaults_;
  Parse(minimizer_, &options->minimizer);
  Parse(linear_solver_, &options->linear_solver);
  Parse(sparse_backend_, &options->sparse_backend);
  options->threads = static_cast<int>(threads_);
  options->max_iterations = static_cast<int>(max_iterations_);
  options->max_time_s = max_time_;
  options->function_tolerance = function_tolerance_;
  options->gradient_tolerance = gradient_tolerance_;
  options->parameter_tolerance = parameter_tolerance_;
  options->remaining_chi2 = remaining_chi2_;
  if (tolerances_ == "tight") {
    if (parser_->Given("remaining-chi2") && remaining_chi2_ > 0) {
      return std::string("--tolerances tight turns --remaining-chi2 off; give one of them");
    }
    if (parser_->Given("extrapolation") && extrapolation_ == "on") {
      return std::string("--tolerances tight turns --extrapolation off; give one of them");
    }
    if (parser_->Given("gauge-moves") && gauge_moves_ == "on") {
      return std::string("--tolerances tight turns --gauge-moves off; give one of them");
    }
    *options = TightRule(*options);
  } else {
    options->extrapolate = extrapolation_ == "on";
    options->snap_segment_gauges = gauge_moves_ == "on";
  }
  options->initial_lambda = initial_lambda_;
  options->nonmonotonic_steps = static_cast<int>(nonmonotonic_steps_);
  options->fix_first = fix_first_;
  options->eliminate_object_points = eliminate_object_points_;
  options->world_anchored_object_points = object_point_variables_ == "world";
  options->world_frame_kinematic_residual = kinematic_residual_frame_ == "world";
  return ParseRobust(robust_, options);
}

void PrintProgressAfterOneSecond(SolverOptions* options) {
  options->on_step = [](const StepRecord& row) {
    if (row.time_s < 1.0) return;
    std::fprintf(stderr, "step %4d  iteration %4d  cost %.10e  trial %.10e  lambda %.1e  %s  %.2f s\n",
                 row.step, row.iteration, row.cost, row.trial_cost, row.lambda,
                 row.accepted ? "accepted" : "rejected", row.time_s);
  };
}

}  // namespace dynslam::cli
