// A graph file in memory: vertices, edges and labels as plain data, no Ceres (SPEC §1).
//
// Every edge tag of SPEC §1.2 and §1.3 has its own struct holding exactly the fields of the
// file. Information matrices are stored in tangent order [ω; ρ] (SPEC §0): graph_io permutes
// the file's g2o order exactly once on reading and back on writing (SPEC §1.2).
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

#include "dynslam/pose.h"
#include "dynslam/status.h"

namespace dynslam {

using VertexId = int64_t;  // SPEC §1.1: non-negative, below 2^63, one namespace

enum class VertexType { kPose, kPoint };

// SPEC §1.4 label tags, in the order roles are listed in summary.json (SPEC §4).
enum class Role {
  kUnknown,
  kCamera,
  kStaticPoint,
  kDynamicPoint,
  kMotion,
  kObjectPose,
  kObjectPoint,
};
inline constexpr std::array<Role, 6> kAllRoles = {
    Role::kCamera, Role::kStaticPoint, Role::kDynamicPoint,
    Role::kMotion, Role::kObjectPose,  Role::kObjectPoint};
// "camera", "static_point", … (SPEC §4 `variables` keys); "unknown" for kUnknown.
const char* RoleName(Role role);

// A vertex's role and indices. Fields that a role does not have stay -1
// (SPEC §1.4: camera has frame; static point tracklet; dynamic point object, frame, tracklet;
// motion and object pose object, frame; object point object, tracklet).
struct Label {
  Role role = Role::kUnknown;
  int64_t object = -1;
  int64_t frame = -1;
  int64_t tracklet = -1;
};

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

// SPEC §1.2 EDGE_SE3_PRIOR: r = Log(Z⁻¹ · X).
struct PriorEdge {
  VertexId pose = 0;
  Pose measurement;
  Matrix6d information = Matrix6d::Identity();  // tangent order [ω; ρ]
  bool has_parameter_id = false;  // the g2o form `EDGE_SE3_PRIOR id 0 …` (kept for round trips)
  int64_t line = 0;
};

// SPEC §1.2 EDGE_SE3:QUAT: r = Log(Z⁻¹ · A⁻¹ · B). Odometry (cameras) or smoothing (motions).
struct BetweenEdge {
  VertexId from = 0;  // A
  VertexId to = 0;    // B
  Pose measurement;
  Matrix6d information = Matrix6d::Identity();  // tangent order [ω; ρ]
  int64_t line = 0;
};

// SPEC §1.2 EDGE_SE3_TRACKXYZ: r = X⁻¹ · m − z.
struct PointEdge {
  VertexId pose = 0;
  VertexId point = 0;
  Eigen::Vector3d measurement = Eigen::Vector3d::Zero();  // point in the camera frame
  Eigen::Matrix3d information = Eigen::Matrix3d::Identity();
  bool is_dynamic = false;
  int64_t line = 0;
};

// SPEC §1.2 EDGE_SE3_MOTION: r = m_curr − H · m_prev − z (ternary world-centric motion edge).
struct MotionEdge {
  VertexId prev = 0;
  VertexId curr = 0;
  VertexId motion = 0;
  Eigen::Vector3d measurement = Eigen::Vector3d::Zero();
  Eigen::Matrix3d information = Eigen::Matrix3d::Identity();
  int64_t object = 0;    // front end's object id j
  int64_t frame = 0;     // frame k of `curr`
  VertexId camera = 0;   // camera that observed `curr` (a vertex reference)
  int64_t line = 0;
};

// SPEC §1.3 EDGE_SE3_OBJ_TRACKXYZ: r = X⁻¹ · L · m_L − z.
struct ObjectPointEdge {
  VertexId camera = 0;
  VertexId object_pose = 0;
  VertexId point = 0;
  Eigen::Vector3d measurement = Eigen::Vector3d::Zero();
  Eigen::Matrix3d information = Eigen::Matrix3d::Identity();
  int64_t line = 0;
};

// SPEC §1.3 EDGE_SE3_OBJ_MOTION: r = L_curr · m_L − H · L_prev · m_L.
struct ObjectMotionEdge {
  VertexId pose_prev = 0;
  VertexId pose_curr = 0;
  VertexId motion = 0;
  VertexId point = 0;
  Eigen::Matrix3d information = Eigen::Matrix3d::Identity();
  int64_t line = 0;
};

// SPEC §1.3 EDGE_SE3_OBJ_KINEMATIC: r = Log(L_curr⁻¹ · H · L_prev).
struct KinematicEdge {
  VertexId pose_prev = 0;
  VertexId pose_curr = 0;
  VertexId motion = 0;
  Matrix6d information = Matrix6d::Identity();  // tangent order [ω; ρ]
  int64_t line = 0;
};

// SPEC §1.5 edge kinds, in the order costs are reported and edges are written (§3.4).
enum class EdgeKind {
  kPrior,
  kOdometry,
  kSmoothing,
  kPoint,
  kDynamicPoint,
  kMotion,
  kObjectPoint,
  kObjectMotion,
  kKinematic,
  kObjectPrior,
};
inline constexpr int kNumEdgeKinds = 10;
inline constexpr std::array<EdgeKind, kNumEdgeKinds> kAllEdgeKinds = {
    EdgeKind::kPrior,        EdgeKind::kOdometry,     EdgeKind::kSmoothing,
    EdgeKind::kPoint,        EdgeKind::kDynamicPoint, EdgeKind::kMotion,
    EdgeKind::kObjectPoint,  EdgeKind::kObjectMotion, EdgeKind::kKinematic,
    EdgeKind::kObjectPrior};
// "prior", "odometry", … (SPEC §1.5 names).
const char* EdgeKindName(EdgeKind kind);

struct Graph {
  // Ascending id: the order vertices are written in (SPEC §3.4). Node-based, so a pointer to
  // a vertex stays valid while others are added.
  std::map<VertexId, Vertex> vertices;

  std::vector<PriorEdge> priors;
  std::vector<BetweenEdge> betweens;
  std::vector<PointEdge> point_edges;
  std::vector<MotionEdge> motion_edges;
  std::vector<ObjectPointEdge> object_point_edges;
  std::vector<ObjectMotionEdge> object_motion_edges;
  std::vector<KinematicEdge> kinematic_edges;

  std::optional<std::string> formulation;  // LABEL_FORMULATION, when present
  bool labelled = false;                   // true when the file carried labels (SPEC §1.4)

  const Vertex* Find(VertexId id) const;
  Vertex* Find(VertexId id);
  size_t NumEdges() const;
};

// Kind of each edge from the roles of its vertices (SPEC §1.5): a prior on an object pose is
// `object_prior`, any other prior `prior`; EDGE_SE3:QUAT between cameras is `odometry`,
// between motions `smoothing`. Requires roles assigned (AssignRoles).
EdgeKind KindOf(const Graph& graph, const PriorEdge& edge);
EdgeKind KindOf(const Graph& graph, const BetweenEdge& edge);
EdgeKind KindOf(const Graph& graph, const PointEdge& edge);
inline EdgeKind KindOf(const Graph&, const MotionEdge&) { return EdgeKind::kMotion; }
inline EdgeKind KindOf(const Graph&, const ObjectPointEdge&) { return EdgeKind::kObjectPoint; }
inline EdgeKind KindOf(const Graph&, const ObjectMotionEdge&) { return EdgeKind::kObjectMotion; }
inline EdgeKind KindOf(const Graph&, const KinematicEdge&) { return EdgeKind::kKinematic; }

// Number of edges of each kind, indexed by static_cast<int>(EdgeKind).
std::array<int64_t, kNumEdgeKinds> CountEdgesByKind(const Graph& graph);

// Gives every vertex a role. A labelled graph keeps its labels and is checked for consistency
// with its edges (SPEC §1.4); an unlabelled one gets roles inferred from its edges (SPEC §3.1 and
// the §1.3 edges for object-centric files; poses in no role-giving edge are cameras, points with
// no dynamic edge static points). Errors name `file` and the offending line.
Status AssignRoles(Graph& graph, const std::string& file);

// Ids of vertices no edge uses (SPEC §1.6: reported; a solver holds them constant).
std::vector<VertexId> UnusedVertices(const Graph& graph);

}  // namespace dynslam

#endif  // DYNSLAM_GRAPH_H_
