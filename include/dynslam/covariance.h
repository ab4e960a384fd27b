// Marginal covariances of a solved graph's variables: the blocks of the inverse of the
// information matrix JᵀJ at the solution, J the whitened residuals' Jacobian (SPEC §1.5) — what
// GTSAM's Marginals gives. Each block is in SPEC §1.3's tangent order: a pose's [ω; ρ] (rad, m)
// for the right perturbation X·Exp(ξ), a point's x, y, z (m); an object-frame point's in its
// object's frame. docs/COVARIANCE.md says what they mean and cost.
#ifndef DYNSLAM_COVARIANCE_H_
#define DYNSLAM_COVARIANCE_H_

#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "dynslam/graph.h"
#include "dynslam/solver.h"
#include "dynslam/status.h"

namespace dynslam {

// What to compute, by role: "cameras" (camera), "motions" (motion, hybrid_motion),
// "object_poses" (object_pose), "points" (static, dynamic and object-frame points), "all".
enum class CovarianceKind { kCameras, kMotions, kObjectPoses, kPoints, kAll };
const char* Name(CovarianceKind kind);
bool Parse(const std::string& text, CovarianceKind* kind);
// "cameras,motions" → kinds; for an unknown or empty name, the problem ("unknown kind 'poses'
// (cameras, motions, object_poses, points, all)") and `kinds` unspecified.
std::optional<std::string> ParseCovarianceKinds(const std::string& text,
                                                std::vector<CovarianceKind>* kinds);
// The vertices of `graph` of those kinds, ascending.
std::vector<VertexId> VerticesOfKinds(const Graph& graph, const std::vector<CovarianceKind>& kinds);

struct MarginalCovariance {
  VertexId id = 0;
  Role role = Role::kUnknown;
  Eigen::MatrixXd covariance;  // 6×6 for a pose, 3×3 for a point
};

// A direction the information matrix does not determine: a tangent component of a variable
// along which JᵀJ is singular (or nearly so) given the others.
struct WeakDirection {
  VertexId id = 0;
  int component = 0;  // 0–5: ω_x, ω_y, ω_z, ρ_x, ρ_y, ρ_z of a pose; 0–2: x, y, z of a point
};
// "omega_z", "rho_x", "x", … : the tangent component `direction` names, on its vertex of `graph`.
std::string DirectionName(const Graph& graph, const WeakDirection& direction);

struct CovarianceReport {
  std::vector<MarginalCovariance> marginals;  // the requested variables, ascending id
  std::vector<VertexId> held_constant;        // requested but held constant: no covariance
  // Non-empty: JᵀJ is singular to kWeakPivot, and `marginals` is empty (no garbage matrix).
  std::vector<WeakDirection> weak_directions;
  int64_t columns = 0;  // size of the information matrix factorised
  double time_s = 0;
};

// A pivot of JᵀJ's LDLᵀ at most this times its diagonal entry marks a weak direction: there the
// information is 1e-10 of what the variable's own edges give, σ 1e5 times theirs.
inline constexpr double kWeakPivot = 1e-10;

// The marginal covariances of `ids` of `solved` (a graph at its solution, roles assigned) as
// `report` solved it: its resolved options (robust kernels included) and the vertices it held
// constant. An Error for a graph the solver would refuse or an id that is not a vertex; a
// singular information matrix is not an error but weak_directions.
Expected<CovarianceReport> ComputeCovariances(const Graph& solved, const SolveReport& report,
                                              const std::vector<VertexId>& ids);

}  // namespace dynslam

#endif  // DYNSLAM_COVARIANCE_H_
