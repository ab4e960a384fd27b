#include "dynslam/covariance.h"

#include <algorithm>
#include <chrono>
#include <map>
#include <sstream>

#include "src/selected_inverse.h"

namespace dynslam {
namespace {

constexpr CovarianceKind kKinds[] = {CovarianceKind::kCameras, CovarianceKind::kMotions,
                                     CovarianceKind::kObjectPoses, CovarianceKind::kPoints,
                                     CovarianceKind::kAll};

bool RoleIsOfKind(Role role, CovarianceKind kind) {
  switch (kind) {
    case CovarianceKind::kCameras: return role == Role::kCamera;
    case CovarianceKind::kMotions: return role == Role::kMotion || role == Role::kHybridMotion;
    case CovarianceKind::kObjectPoses: return role == Role::kObjectPose;
    case CovarianceKind::kPoints:
      return role == Role::kStaticPoint || role == Role::kDynamicPoint ||
             role == Role::kObjectPoint;
    case CovarianceKind::kAll: return true;
  }
  return false;
}

// H = JᵀJ over the columns of the variables not held constant.
Eigen::SparseMatrix<double> Information(const SystemJacobian& system,
                                        const std::vector<bool>& keep_column) {
  std::vector<int> new_index(keep_column.size(), -1);
  int columns = 0;
  for (size_t c = 0; c < keep_column.size(); ++c) {
    if (keep_column[c]) new_index[c] = columns++;
  }
  std::vector<Eigen::Triplet<double>> kept;
  kept.reserve(static_cast<size_t>(system.jacobian.nonZeros()));
  for (int r = 0; r < system.jacobian.outerSize(); ++r) {
    for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(system.jacobian, r); it;
         ++it) {
      if (new_index[it.col()] >= 0) kept.emplace_back(r, new_index[it.col()], it.value());
    }
  }
  Eigen::SparseMatrix<double> jacobian(system.jacobian.rows(), columns);
  jacobian.setFromTriplets(kept.begin(), kept.end());
  return Eigen::SparseMatrix<double>(jacobian.transpose() * jacobian);
}

}  // namespace

const char* Name(CovarianceKind kind) {
  switch (kind) {
    case CovarianceKind::kCameras: return "cameras";
    case CovarianceKind::kMotions: return "motions";
    case CovarianceKind::kObjectPoses: return "object_poses";
    case CovarianceKind::kPoints: return "points";
    case CovarianceKind::kAll: return "all";
  }
  return "";
}

bool Parse(const std::string& text, CovarianceKind* kind) {
  for (const CovarianceKind k : kKinds) {
    if (text == Name(k)) {
      *kind = k;
      return true;
    }
  }
  return false;
}

std::optional<std::string> ParseCovarianceKinds(const std::string& text,
                                                std::vector<CovarianceKind>* kinds) {
  kinds->clear();
  std::stringstream items(text);
  std::string item;
  std::optional<std::string> unknown;
  while (!unknown && std::getline(items, item, ',')) {
    CovarianceKind kind;
    if (Parse(item, &kind)) {
      kinds->push_back(kind);
    } else {
      unknown = item;
    }
  }
  if (!unknown && !kinds->empty()) return std::nullopt;
  std::string names;
  for (const CovarianceKind k : kKinds) names += std::string(names.empty() ? "" : ", ") + Name(k);
  return "unknown kind '" + unknown.value_or(text) + "' (" + names + ")";
}

std::vector<VertexId> VerticesOfKinds(const Graph& graph,
                                      const std::vector<CovarianceKind>& kinds) {
  std::vector<VertexId> ids;
  for (const auto& [id, vertex] : graph.vertices) {
    const Role role = vertex.label.role;
    if (InfoOf(role) != nullptr && InfoOf(role)->constant) continue;  // never a variable
    for (const CovarianceKind kind : kinds) {
      if (RoleIsOfKind(role, kind)) {
        ids.push_back(id);
        break;
      }
    }
  }
  return ids;
}

std::string DirectionName(const Graph& graph, const WeakDirection& direction) {
  static const char* const kPose[] = {"omega_x", "omega_y", "omega_z", "rho_x", "rho_y", "rho_z"};
  static const char* const kPoint[] = {"x", "y", "z"};
  return graph.vertices.at(direction.id).type == VertexType::kPose ? kPose[direction.component]
                                                                   : kPoint[direction.component];
}

Expected<CovarianceReport> ComputeCovariances(const Graph& solved, const SolveReport& report,
                                              const std::vector<VertexId>& ids) {
  const auto start = std::chrono::steady_clock::now();
  for (const VertexId id : ids) {
    if (solved.vertices.count(id) == 0) {
      return Error{"", 0, "covariance of vertex " + std::to_string(id) + ": no such vertex"};
    }
  }
  // The information of SPEC §1.3's residuals in the variables themselves: the object-frame
  // points' own coordinates, not the solver's anchored chart, and the kinematic residual in the
  // object frame — turned into the world by L_curr's rotation its Jacobian gains a term in the
  // residual, so JᵀJ would differ wherever the residual is not zero (solver.h).
  SolverOptions options = report.options_used;
  options.object_point_variables = Frame::kObject;
  options.kinematic_residual_frame = Frame::kObject;
  Expected<SystemJacobian> system = EvaluateJacobian(solved, options);
  if (!system.ok()) return system.error();

  std::vector<bool> keep_column(static_cast<size_t>(system->first_column.back()), true);
  std::map<VertexId, size_t> variable_of;
  for (size_t v = 0; v < system->variables.size(); ++v) variable_of[system->variables[v]] = v;
  // Held constant by the solve (--fix-first's pose; EvaluateJacobian leaves out the others).
  for (const VertexId id : report.held_constant) {
    auto it = variable_of.find(id);
    if (it == variable_of.end()) continue;
    for (int c = system->first_column[it->second]; c < system->first_column[it->second + 1]; ++c) {
      keep_column[c] = false;
    }
    variable_of.erase(it);
  }
  // Column of each kept variable's first tangent component, in H's numbering.
  std::vector<int> h_column(keep_column.size() + 1, 0);
  for (size_t c = 0; c < keep_column.size(); ++c) h_column[c + 1] = h_column[c] + keep_column[c];

  CovarianceReport out;
  SelectedInverse inverse(Information(*system, keep_column));
  out.columns = h_column.back();
  std::vector<std::pair<VertexId, int>> owner(out.columns);  // H's column → (vertex, component)
  for (const auto& [id, v] : variable_of) {
    const int first = h_column[system->first_column[v]];
    for (int c = first; c < h_column[system->first_column[v + 1]]; ++c) owner[c] = {id, c - first};
  }
  for (const int weak : inverse.WeakColumns(kWeakPivot)) {
    out.weak_directions.push_back({owner[weak].first, owner[weak].second});
  }
  if (out.weak_directions.empty()) {
    inverse.Invert();
    for (const VertexId id : ids) {
      auto it = variable_of.find(id);
      if (it == variable_of.end()) {
        out.held_constant.push_back(id);
        continue;
      }
      const int first = h_column[system->first_column[it->second]];
      const int size = h_column[system->first_column[it->second + 1]] - first;
      MarginalCovariance block{id, solved.vertices.at(id).label.role,
                               Eigen::MatrixXd(size, size)};
      for (int r = 0; r < size; ++r) {
        for (int c = 0; c < size; ++c) block.covariance(r, c) = inverse(first + r, first + c);
      }
      out.marginals.push_back(std::move(block));
    }
  }
  out.time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

}  // namespace dynslam
