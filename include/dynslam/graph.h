// A graph file in memory: vertices, edges and labels as plain data, no Ceres (SPEC §1).
//
// The edge structs, roles and edge kinds are the tables of graph_schema.h.
//
// Roles (camera, static point, …) come from labels when the file has them, otherwise they are
// inferred from the edges (SPEC §1.4, §3.1); `AssignRoles` does either and checks consistency.
// Edge kinds (SPEC §1.5: prior, odometry, …) follow from the roles of an edge's vertices.
#ifndef DYNSLAM_GRAPH_H_
#define DYNSLAM_GRAPH_H_

#include <array>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "dynslam/graph_schema.h"
#include "dynslam/pose.h"
#include "dynslam/status.h"

namespace dynslam {

struct Vertex {
  VertexType type = VertexType::kPose;
  // Pose: the 7-double block of pose.h. Point: x y z in the first three entries.
  std::array<double, kPoseSize> value{0, 0, 0, 1, 0, 0, 0};
  Label label;
  int64_t line = 0;  // line of the file that declared it; 0 when built in memory

  Pose pose() const { return Pose{value}; }
  void set_pose(const Pose& pose) { value = pose.data; }
  Eigen::Map<const Eigen::Vector3d> point() const {
    return Eigen::Map<const Eigen::Vector3d>(value.data());
  }
  Eigen::Map<Eigen::Vector3d> point() { return Eigen::Map<Eigen::Vector3d>(value.data()); }
};

struct Graph {
  // Ascending id: the order vertices are written in (SPEC §3.4). Node-based, so a pointer to
  // a vertex stays valid while others are added.
  std::map<VertexId, Vertex> vertices;

  // One vector per edge struct of graph_schema.h's EdgeTypes.
  EdgeTypes::Vectors edges;
  template <typename Edge>
  std::vector<Edge>& Edges() {
    return std::get<std::vector<Edge>>(edges);
  }
  template <typename Edge>
  const std::vector<Edge>& Edges() const {
    return std::get<std::vector<Edge>>(edges);
  }
  // f(const std::vector<Edge>&) for every edge struct, in EdgeTypes order.
  template <typename F>
  void ForEachEdgeVector(F&& f) const {
    std::apply([&](const auto&... vectors) { (f(vectors), ...); }, edges);
  }

  std::optional<std::string> formulation;  // LABEL_FORMULATION, when present
  bool labelled = false;                   // true when the file carried labels (SPEC §1.4)

  const Vertex* Find(VertexId id) const;
  Vertex* Find(VertexId id);
  size_t NumEdges() const;
  // The role of vertex `id`; kUnknown when there is no such vertex.
  Role RoleOf(VertexId id) const {
    const Vertex* vertex = Find(id);
    return vertex == nullptr ? Role::kUnknown : vertex->label.role;
  }
  // Vertices but constants (roles with RoleInfo::constant: hy's embedded frames).
  size_t NumVariables() const;
};

// Kind of an edge from the roles of its vertices (SPEC §1.5; each struct's `Kind`). Requires
// roles assigned (AssignRoles).
template <typename Edge>
EdgeKind KindOf(const Graph& graph, const Edge& edge) {
  return edge.Kind([&](VertexId id) { return graph.RoleOf(id); });
}

// Number of edges of each kind, indexed by static_cast<int>(EdgeKind).
std::array<int64_t, kNumEdgeKinds> CountEdgesByKind(const Graph& graph);

// Number of vertices of each role, in the order of kAllRoles (constants such as hy's embedded
// frames included).
std::array<int64_t, kNumRoles> CountVerticesByRole(const Graph& graph);

// Gives every vertex a role. A labelled graph keeps its labels and is checked for consistency
// with its edges (SPEC §1.4); an unlabelled one gets roles inferred from its edges (SPEC §3.1 and
// the §1.3 edges for object-centric files; poses in no role-giving edge are cameras, points with
// no dynamic edge static points). Errors name `file` and the offending line.
Status AssignRoles(Graph& graph, const std::string& file);

// Ids of vertices no edge uses (SPEC §1.6: reported; a solver holds them constant).
std::vector<VertexId> UnusedVertices(const Graph& graph);

}  // namespace dynslam

#endif  // DYNSLAM_GRAPH_H_
