// The GTSAM backend: the same graph files solved by GTSAM 4.2's optimisers (docs/GTSAM_BACKEND.md).
//
// An optional part of the build (-DDYNSLAM_WITH_GTSAM=ON, scripts/build_gtsam). Without it every
// function here exists and returns an Error that says how to build it, so callers need no
// #ifdef. The header has no GTSAM types: a consumer includes it without GTSAM's headers.
//
// Each edge becomes one GTSAM factor with the residual of SPEC §1.2–§1.3/§3.6 and a Gaussian
// noise model from its information (a robust one when SolverOptions::robust names a kernel for
// its kind, SPEC §1.5). Variables use GTSAM's Pose3 (Pose3/Rot3 expmap: right perturbation
// X·Exp(ξ), ξ = [ω; ρ], SPEC §1.3) and Point3.
#ifndef DYNSLAM_GTSAM_BACKEND_H_
#define DYNSLAM_GTSAM_BACKEND_H_

#include <optional>
#include <string>
#include <vector>

#include "dynslam/covariance.h"
#include "dynslam/graph.h"
#include "dynslam/solver.h"
#include "dynslam/solver_options.h"
#include "dynslam/status.h"

namespace dynslam {

// One of GTSAM's optimisers with its parameters (SPEC §6 for the LM profiles).
struct GtsamProfile {
  enum class Algorithm { kLevenbergMarquardt, kDogleg, kGaussNewton };
  std::string name;  // released, tight, tight_exact, dogleg, gn
  Algorithm algorithm = Algorithm::kLevenbergMarquardt;
  double lambda_initial = 1e-5;
  double lambda_factor = 10;
  double lambda_upper_bound = 1e5;
  double min_model_fidelity = 1e-3;
  double relative_error_tol = 1e-5;
  double absolute_error_tol = 1e-5;
  int max_iterations = 100;
  // EDGE_SE3_PRIOR and EDGE_SE3:QUAT with Log's derivative in their Jacobians (SPEC §6
  // tight_exact); otherwise GTSAM's PriorFactor<Pose3>/BetweenFactor<Pose3>, which omit it.
  bool exact_pose_jacobians = false;
};

// The names GtsamProfileNamed knows, in the order the docs list them.
std::vector<std::string> GtsamProfileNames();
// The profile `name` ("" is `released`, GTSAM's LM as the released code ran it); an Error
// naming the known ones otherwise.
Expected<GtsamProfile> GtsamProfileNamed(const std::string& name);

// A backend as users name it: "ceres" → none (the Ceres solver, solver.h); "gtsam" or
// "gtsam:PROFILE" → that profile. An Error naming the known backends and profiles otherwise, or
// GtsamBackendMissingMessage() for gtsam in a build without it.
Expected<std::optional<GtsamProfile>> ParseBackend(const std::string& text);

// Whether this build has the backend (DYNSLAM_WITH_GTSAM); when not, why and how to get it.
bool GtsamBackendBuilt();
std::string GtsamBackendMissingMessage();

// Solves `graph` with GTSAM and writes the solution into its vertices, like Solve (solver.h).
// From `options` it uses what does not belong to Ceres: robust kernels, the SPEC §7 residual
// choices (dsc_*), fix_first, max_time and should_stop/on_step. The report's convergence has one
// row per accepted iteration (GTSAM does not expose its rejected inner solves; `steps` counts
// them all), its `solver_json` the profile and GTSAM's build settings. A singular linear system
// (GTSAM's IndeterminantLinearSystemException) ends the solve with termination "failure" and a
// detail that names it.
Expected<SolveReport> SolveWithGtsam(const GtsamProfile& profile, const SolverOptions& options,
                                     Graph* graph);

// gtsam::Marginals (Cholesky) of `ids` at `solved` as SolveWithGtsam built it: the covariances
// of covariance.h in the same tangent order. A singular system is an Error naming the variable
// GTSAM could not eliminate.
Expected<CovarianceReport> GtsamCovariances(const Graph& solved, const GtsamProfile& profile,
                                            const SolverOptions& options,
                                            const std::vector<VertexId>& ids);

}  // namespace dynslam

#endif  // DYNSLAM_GTSAM_BACKEND_H_
