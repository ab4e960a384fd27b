// SolveWithGtsam and GtsamCovariances (gtsam_backend.h) on GTSAM 4.2.
#include <chrono>
#include <cmath>
#include <memory>
#include <string>

#include <gtsam/config.h>
#include <gtsam/inference/Ordering.h>
#include <gtsam/linear/linearExceptions.h>
#include <gtsam/nonlinear/DoglegOptimizer.h>
#include <gtsam/nonlinear/GaussNewtonOptimizer.h>
#include <gtsam/nonlinear/LevenbergMarquardtOptimizer.h>
#include <gtsam/nonlinear/Marginals.h>

#include "dynslam/gtsam_backend.h"
#include "src/gtsam/problem.h"
#include "src/json_io.h"

namespace dynslam {
namespace {

using Clock = std::chrono::steady_clock;
using gtsam_backend::Problem;

double SecondsSince(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

const char* AlgorithmName(GtsamProfile::Algorithm algorithm) {
  switch (algorithm) {
    case GtsamProfile::Algorithm::kDogleg: return "Dogleg";
    case GtsamProfile::Algorithm::kGaussNewton: return "GaussNewton";
    case GtsamProfile::Algorithm::kLevenbergMarquardt: break;
  }
  return "LevenbergMarquardt";
}

// The stopping parameters every GTSAM optimiser shares, from the profile.
template <typename Params>
Params WithStopping(Params params, const GtsamProfile& profile) {
  params.relativeErrorTol = profile.relative_error_tol;
  params.absoluteErrorTol = profile.absolute_error_tol;
  params.errorTol = 0;
  params.maxIterations = profile.max_iterations;
  params.setOrderingType("COLAMD");
  params.linearSolverType = gtsam::NonlinearOptimizerParams::MULTIFRONTAL_CHOLESKY;
  return params;
}

std::unique_ptr<gtsam::NonlinearOptimizer> MakeOptimizer(const GtsamProfile& profile,
                                                         const Problem& problem) {
  switch (profile.algorithm) {
    case GtsamProfile::Algorithm::kDogleg:
      return std::make_unique<gtsam::DoglegOptimizer>(
          problem.factors, problem.values, WithStopping(gtsam::DoglegParams(), profile));
    case GtsamProfile::Algorithm::kGaussNewton:
      return std::make_unique<gtsam::GaussNewtonOptimizer>(
          problem.factors, problem.values, WithStopping(gtsam::GaussNewtonParams(), profile));
    case GtsamProfile::Algorithm::kLevenbergMarquardt: break;
  }
  // SPEC §6: LegacyDefaults (λ·I damping, fixed λ factor) with the profile's values.
  gtsam::LevenbergMarquardtParams params =
      WithStopping(gtsam::LevenbergMarquardtParams::LegacyDefaults(), profile);
  params.lambdaInitial = profile.lambda_initial;
  params.lambdaFactor = profile.lambda_factor;
  params.lambdaUpperBound = profile.lambda_upper_bound;
  params.lambdaLowerBound = 0;
  params.minModelFidelity = profile.min_model_fidelity;
  params.diagonalDamping = false;
  params.useFixedLambdaFactor = true;
  return std::make_unique<gtsam::LevenbergMarquardtOptimizer>(problem.factors, problem.values,
                                                              params);
}

// summary.json's "solver" for a GTSAM solve.
std::string SolverJson(const GtsamProfile& profile, const SolverOptions& options) {
  JsonValue json{
      {"backend", "gtsam"},
      {"library", "GTSAM " GTSAM_VERSION_STRING},
      {"profile", profile.name},
      {"algorithm", AlgorithmName(profile.algorithm)},
      {"relativeErrorTol", profile.relative_error_tol},
      {"absoluteErrorTol", profile.absolute_error_tol},
      {"errorTol", 0},
      {"maxIterations", profile.max_iterations}};
  if (profile.algorithm == GtsamProfile::Algorithm::kLevenbergMarquardt) {
    json["lambdaInitial"] = profile.lambda_initial;
    json["lambdaFactor"] = profile.lambda_factor;
    json["lambdaUpperBound"] = profile.lambda_upper_bound;
    json["lambdaLowerBound"] = 0;
    json["minModelFidelity"] = profile.min_model_fidelity;
    json["diagonalDamping"] = false;
    json["useFixedLambdaFactor"] = true;
  }
  json["orderingType"] = "COLAMD";
  json["linearSolverType"] = "MULTIFRONTAL_CHOLESKY";
  json["pose_edge_jacobians"] =
      profile.exact_pose_jacobians
          ? "exact (Log's derivative included)"
          : "GTSAM's PriorFactor/BetweenFactor (Log's derivative omitted)";
  json["robust"] = RobustText(options.robust);
  json["dsc_motion_residual"] = options.dsc_motion_residual;
  json["dsc_motion_sigma"] = options.dsc_motion_sigma;
  json["dsc_object_motion_residual"] = options.dsc_object_motion_residual;
  json["fix_first"] = options.fix_first;
  json["max_time"] = options.max_time;
  json["threads"] = 1;
#ifdef GTSAM_USE_TBB
  json["GTSAM_USE_TBB"] = true;
#else
  json["GTSAM_USE_TBB"] = false;
#endif
#if defined(GTSAM_POSE3_EXPMAP) && defined(GTSAM_ROT3_EXPMAP)
  json["GTSAM_POSE3_EXPMAP"] = true;
#else
  json["GTSAM_POSE3_EXPMAP"] = false;
#endif
  return DumpJson(json);
}

// Which of GTSAM's checkConvergence rules stopped it (NonlinearOptimizer.cpp).
std::string ConvergenceDetail(const GtsamProfile& profile, double before, double after) {
  const double decrease = before - after;
  if (decrease < 0) return "the error increased (GTSAM stops)";
  if (decrease <= profile.absolute_error_tol) return "absolute decrease <= absoluteErrorTol";
  return "relative decrease <= relativeErrorTol";
}

// The loop of NonlinearOptimizer::defaultOptimize, one iterate() at a time so that each
// iteration is a convergence row and should_stop and max_time are polled between them. Same
// iterations, same values as optimize().
class Run {
 public:
  Run(const GtsamProfile& profile, const SolverOptions& options, Clock::time_point start,
      SolveReport* report)
      : profile_(profile), options_(options), start_(start), report_(report) {}

  void Iterate(gtsam::NonlinearOptimizer* optimizer) {
    auto* lm = dynamic_cast<gtsam::LevenbergMarquardtOptimizer*>(optimizer);
    auto* dogleg = dynamic_cast<gtsam::DoglegOptimizer*>(optimizer);
    double cost = optimizer->error();
    while (true) {
      if (optimizer->iterations() >= static_cast<size_t>(profile_.max_iterations)) {
        return Stop("no_convergence", "maxIterations reached");
      }
      if (options_.should_stop && options_.should_stop()) {
        return Stop("interrupted", "stopped on request; the solution is the last iteration's");
      }
      if (options_.max_time > 0 && SecondsSince(start_) >= options_.max_time) {
        return Stop("time_limit", "max_time reached; the solution is the last iteration's");
      }
      const int inner_before = lm != nullptr ? lm->getInnerIterations() : report_->steps;
      const double lambda = lm != nullptr ? lm->lambda()
                            : dogleg != nullptr ? 1.0 / dogleg->getDelta() : 0.0;
      optimizer->iterate();
      const double trial = optimizer->error();
      const int solves = lm != nullptr ? lm->getInnerIterations() - inner_before : 1;
      report_->steps += std::max(solves, 1);
      AddRow(lm != nullptr ? lambda * std::pow(profile_.lambda_factor, std::max(solves - 1, 0))
                           : lambda,
             cost, trial);
      if (gtsam::checkConvergence(profile_.relative_error_tol, profile_.absolute_error_tol, 0,
                                  cost, trial)) {
        return Stop("convergence", ConvergenceDetail(profile_, cost, trial));
      }
      if (!std::isfinite(cost)) return Stop("failure", "the error is not finite");
      cost = trial;
    }
  }

 private:
  void AddRow(double lambda, double cost, double trial) {
    StepRecord row;
    row.step = static_cast<int>(report_->convergence.size()) + 1;
    row.iteration = report_->iterations + 1;
    row.lambda = lambda;
    row.cost = cost;
    row.trial_cost = trial;
    row.accepted = trial < cost;
    row.time_s = SecondsSince(start_);
    report_->iterations += row.accepted;
    report_->convergence.push_back(row);
    if (options_.on_step) options_.on_step(row);
  }

  void Stop(const std::string& termination, const std::string& detail) {
    report_->termination = termination;
    report_->termination_detail = detail;
    report_->usable = termination != "failure";
  }

  const GtsamProfile& profile_;
  const SolverOptions& options_;
  const Clock::time_point start_;
  SolveReport* report_;
};

// The variable GTSAM names in an IndeterminantLinearSystemException, as text.
std::string Singular(const gtsam::IndeterminantLinearSystemException& e) {
  return "singular: GTSAM's linear system is indeterminant near vertex " +
         std::to_string(e.nearbyVariable()) +
         " (IndeterminantLinearSystemException; the graph leaves it undetermined)";
}

void CountVariablesAndEdges(const Graph& graph, const Problem& problem, SolveReport* report) {
  report->variables_by_role = CountVerticesByRole(graph);
  report->edges_by_kind = CountEdgesByKind(graph);
  report->held_constant = problem.held_constant;
  report->unused_variables = static_cast<int64_t>(UnusedVertices(graph).size());
  report->warnings = problem.warnings;
  if (report->unused_variables > 0) {
    report->warnings.push_back(std::to_string(report->unused_variables) +
                               " vertices are used by no edge and are held constant");
  }
}

}  // namespace

bool GtsamBackendBuilt() { return true; }

Expected<SolveReport> SolveWithGtsam(const GtsamProfile& profile, const SolverOptions& options,
                                     Graph* graph) {
  Expected<Problem> problem = gtsam_backend::BuildProblem(*graph, profile, options);
  if (!problem.ok()) return problem.error();
  SolveReport report;
  CountVariablesAndEdges(*graph, *problem, &report);
  report.options_used = options;
  report.solver_json = SolverJson(profile, options);
  report.eliminated_first = "none: GTSAM orders all variables with COLAMD";
  report.initial_cost_by_kind = gtsam_backend::CostsByKind(*problem, problem->values);
  report.initial_cost = TotalCost(report.initial_cost_by_kind);

  const Clock::time_point start = Clock::now();
  gtsam::Values solution = problem->values;
  try {
    std::unique_ptr<gtsam::NonlinearOptimizer> optimizer = MakeOptimizer(profile, *problem);
    Run(profile, options, start, &report).Iterate(optimizer.get());
    solution = optimizer->values();
  } catch (const gtsam::IndeterminantLinearSystemException& e) {
    report.termination = "failure";
    report.termination_detail = Singular(e);
    report.usable = false;
  } catch (const std::exception& e) {
    report.termination = "failure";
    report.termination_detail = std::string("GTSAM: ") + e.what();
    report.usable = false;
  }
  report.time_total_s = SecondsSince(start);
  report.time_minimizer_s = report.time_total_s;
  report.final_cost_by_kind = gtsam_backend::CostsByKind(*problem, solution);
  report.final_cost = TotalCost(report.final_cost_by_kind);
  gtsam_backend::WriteBack(solution, graph);
  return report;
}

Expected<CovarianceReport> GtsamCovariances(const Graph& solved, const GtsamProfile& profile,
                                            const SolverOptions& options,
                                            const std::vector<VertexId>& ids) {
  Expected<Problem> problem = gtsam_backend::BuildProblem(solved, profile, options);
  if (!problem.ok()) return problem.error();
  const Clock::time_point start = Clock::now();
  CovarianceReport report;
  try {
    const gtsam::Marginals marginals(problem->factors, problem->values,
                                     gtsam::Marginals::CHOLESKY);
    for (const VertexId id : ids) {
      const gtsam::Key key = static_cast<gtsam::Key>(id);
      const bool held = std::find(problem->held_constant.begin(), problem->held_constant.end(),
                                  id) != problem->held_constant.end();
      if (held || !problem->values.exists(key)) {
        report.held_constant.push_back(id);
        continue;
      }
      report.marginals.push_back({id, solved.RoleOf(id), marginals.marginalCovariance(key)});
    }
  } catch (const gtsam::IndeterminantLinearSystemException& e) {
    return Error{"", 0, Singular(e)};
  }
  report.columns = static_cast<int64_t>(problem->values.dim());
  report.time_s = SecondsSince(start);
  return report;
}

}  // namespace dynslam
