// The graph file's vocabulary as tables (SPEC §1.2–§1.5): vertex roles with their labels, edge
// kinds, and one struct per edge tag that lists its fields in file order. The reader, the
// writer, role inference and checks, counting and the solver's assembly all read these tables;
// adding an edge tag means adding its struct here and its name to `EdgeTypes` (and, for the
// solver, its residual in src/edge_costs.h). No Ceres here.
//
// Information matrices are stored in tangent order [ω; ρ] (SPEC §0); the reader permutes the
// file's g2o order exactly once and the writer back (SPEC §1.2).
#ifndef DYNSLAM_GRAPH_SCHEMA_H_
#define DYNSLAM_GRAPH_SCHEMA_H_

#include <array>
#include <cstdint>
#include <initializer_list>
#include <string>
#include <tuple>
#include <type_traits>
#include <vector>

#include <Eigen/Core>

#include "dynslam/pose.h"

namespace dynslam {

// SPEC §1.2: a pose edge's 6×6 information is written translation first [ρ; ω] in the file and
// held in tangent order [ω; ρ] in memory; tangent index i is file index kFileIndexOfTangent[i]
// (the permutation is its own inverse).
inline constexpr int kFileIndexOfTangent[6] = {3, 4, 5, 0, 1, 2};

using VertexId = int64_t;  // SPEC §1.1: non-negative, below 2^63, one namespace

enum class VertexType { kPose, kPoint };

// --- roles (SPEC §1.4), in the order they are listed in summary.json (SPEC §4) ---

enum class Role {
  kUnknown,
  kCamera,
  kStaticPoint,
  kDynamicPoint,
  kMotion,
  kObjectPose,
  kObjectPoint,
  kHybridMotion,
  kEmbeddedFrame,
};

enum class LabelField { kObject, kFrame, kTracklet, kEmbedded };
inline const char* LabelFieldName(LabelField field) {
  switch (field) {
    case LabelField::kObject: return "object";
    case LabelField::kFrame: return "frame";
    case LabelField::kTracklet: return "tracklet";
    case LabelField::kEmbedded: return "embedded";
  }
  return "?";
}

struct RoleInfo {
  Role role;
  const char* name;       // SPEC §4 `variables` key
  const char* label_tag;  // SPEC §1.4
  VertexType type;
  std::array<LabelField, 3> fields;  // after the id, in file order; the first `num_fields`
  int num_fields;
  bool constant = false;  // never a variable: solvers hold it constant, write it back unchanged
};

inline constexpr RoleInfo kRoles[] = {
    {Role::kCamera, "camera", "LABEL_CAMERA", VertexType::kPose, {LabelField::kFrame}, 1},
    {Role::kStaticPoint, "static_point", "LABEL_STATIC_POINT", VertexType::kPoint,
     {LabelField::kTracklet}, 1},
    {Role::kDynamicPoint, "dynamic_point", "LABEL_DYNAMIC_POINT", VertexType::kPoint,
     {LabelField::kObject, LabelField::kFrame, LabelField::kTracklet}, 3},
    {Role::kMotion, "motion", "LABEL_MOTION", VertexType::kPose,
     {LabelField::kObject, LabelField::kFrame}, 2},
    {Role::kObjectPose, "object_pose", "LABEL_OBJECT_POSE", VertexType::kPose,
     {LabelField::kObject, LabelField::kFrame}, 2},
    {Role::kObjectPoint, "object_point", "LABEL_OBJECT_POINT", VertexType::kPoint,
     {LabelField::kObject, LabelField::kTracklet}, 2},
    {Role::kHybridMotion, "hybrid_motion", "LABEL_HYBRID_MOTION", VertexType::kPose,
     {LabelField::kObject, LabelField::kFrame, LabelField::kEmbedded}, 3},
    {Role::kEmbeddedFrame, "embedded_frame", "LABEL_EMBEDDED_FRAME", VertexType::kPose,
     {LabelField::kObject, LabelField::kFrame}, 2, true},
};
inline constexpr size_t kNumRoles = std::size(kRoles);

inline constexpr std::array<Role, kNumRoles> MakeAllRoles() {
  std::array<Role, kNumRoles> roles{};
  for (size_t i = 0; i < kNumRoles; ++i) roles[i] = kRoles[i].role;
  return roles;
}
inline constexpr std::array<Role, kNumRoles> kAllRoles = MakeAllRoles();

// The table row of `role`; null for kUnknown.
inline const RoleInfo* InfoOf(Role role) {
  for (const RoleInfo& info : kRoles) {
    if (info.role == role) return &info;
  }
  return nullptr;
}

// "camera", "static_point", …; "unknown" for kUnknown.
inline const char* RoleName(Role role) {
  const RoleInfo* info = InfoOf(role);
  return info == nullptr ? "unknown" : info->name;
}

// A vertex's role and indices. Fields that a role does not have stay -1.
struct Label {
  Role role = Role::kUnknown;
  int64_t object = -1;
  int64_t frame = -1;
  int64_t tracklet = -1;
  VertexId embedded = -1;  // a hybrid motion's embedded frame (SPEC §3.6)

  int64_t& at(LabelField field) {
    switch (field) {
      case LabelField::kObject: return object;
      case LabelField::kFrame: return frame;
      case LabelField::kTracklet: return tracklet;
      case LabelField::kEmbedded: return embedded;
    }
    return object;
  }
  int64_t at(LabelField field) const { return const_cast<Label*>(this)->at(field); }
};

// --- edge kinds (SPEC §1.5), in the order costs are reported and edges are written (§3.4) ---

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
  kHybridPoint,
  kHybridSmoothing,
};
// In EdgeKind's order.
inline constexpr const char* kEdgeKindNames[] = {
    "prior",         "odometry",     "smoothing",    "point",
    "dynamic_point", "motion",       "object_point", "object_motion",
    "kinematic",     "object_prior", "hybrid_point", "hybrid_smoothing",
};
inline constexpr int kNumEdgeKinds = static_cast<int>(std::size(kEdgeKindNames));

inline constexpr std::array<EdgeKind, kNumEdgeKinds> MakeAllEdgeKinds() {
  std::array<EdgeKind, kNumEdgeKinds> kinds{};
  for (int i = 0; i < kNumEdgeKinds; ++i) kinds[i] = static_cast<EdgeKind>(i);
  return kinds;
}
inline constexpr std::array<EdgeKind, kNumEdgeKinds> kAllEdgeKinds = MakeAllEdgeKinds();

inline const char* EdgeKindName(EdgeKind kind) { return kEdgeKindNames[static_cast<int>(kind)]; }

// --- edges: one struct per tag ---
//
// `Fields(edge, visitor)` hands every field to the visitor in file order:
//   v.Vertex(VertexField, VertexId&)    a vertex reference
//   v.Integer(name, int64_t&)           a non-negative integer (object id, frame)
//   v.OptionalOffsetParameter(name, bool& present) g2o's offset-parameter id: absent or `0`
//   v.OptionalFlag(name, bool&)         a trailing `0`/`1`, absent means 0
//   v.OptionalMeasurement(Eigen::Vector3d&) a trailing `zx zy zz`, absent means 0 (written
//                                       only when not 0)
//   v.Measurement(Pose&) / v.Measurement(Eigen::Vector3d&)
//   v.Information(Eigen::Matrix3d&) / v.Information(Matrix6d&)
// A tag has at most one optional field. Besides its fields, each struct says:
//   Kind(role_of)          its kind from the roles of its vertices (role_of(id) → Role);
//   Invalid()              a field value the tag forbids ("" when none);
//   Inconsistent(label_of) how a labelled file's labels contradict the edge's fields ("" when
//                          they agree; label_of(id) → const Label&, roles already checked);
//   Infer(label_at)        the labels an unlabelled file's vertices take from the edge
//                          (label_at(id) → Label&), after every role is known.

// A vertex field: its name in messages, the vertex type, the role it gives a vertex of an
// unlabelled file (kUnknown: none), the roles a labelled file may give it, and whether it is a
// residual's parameter (false: a reference the residual does not use).
struct VertexField {
  const char* name;
  VertexType type;
  Role claim;
  std::initializer_list<Role> allowed;
  bool parameter = true;
};

// A visitor that ignores every field; visitors interested in some fields derive from it.
struct IgnoreFields {
  void Vertex(const VertexField&, VertexId) {}
  void Integer(const char*, int64_t) {}
  void OptionalOffsetParameter(const char*, bool) {}
  void OptionalFlag(const char*, bool) {}
  template <typename T>
  void Measurement(const T&) {}
  void OptionalMeasurement(const Eigen::Vector3d&) {}
  template <typename T>
  void Information(const T&) {}
};

// The hooks of an edge struct that most tags leave empty; a struct that needs one hides it.
struct EdgeDefaults {
  const char* Invalid() const { return ""; }
  template <typename LabelOf>
  std::string Inconsistent(const LabelOf&) const {
    return "";
  }
  template <typename LabelAt>
  void Infer(const LabelAt&) const {}
};

// SPEC §1.2 EDGE_SE3_PRIOR: r = Log(Z⁻¹ · X).
struct PriorEdge : EdgeDefaults {
  static constexpr const char* kTag = "EDGE_SE3_PRIOR";
  VertexId pose = 0;
  Pose measurement;
  Matrix6d information = Matrix6d::Identity();
  bool has_parameter_id = false;  // the g2o form `EDGE_SE3_PRIOR id 0 …` (kept for round trips)
  int64_t line = 0;

  template <typename Self, typename V>
  static void Fields(Self& e, V& v) {
    v.Vertex({"id", VertexType::kPose, Role::kUnknown,
              {Role::kCamera, Role::kObjectPose, Role::kMotion, Role::kHybridMotion}},
             e.pose);
    v.OptionalOffsetParameter("param", e.has_parameter_id);
    v.Measurement(e.measurement);
    v.Information(e.information);
  }
  template <typename RoleOf>
  EdgeKind Kind(const RoleOf& role_of) const {
    const Role role = role_of(pose);  // a hybrid segment's anchor is an object prior (§3.6)
    return role == Role::kObjectPose || role == Role::kHybridMotion ? EdgeKind::kObjectPrior
                                                                     : EdgeKind::kPrior;
  }
};

// SPEC §1.2 EDGE_SE3:QUAT: r = Log(Z⁻¹ · A⁻¹ · B). Odometry (cameras) or smoothing (motions).
struct BetweenEdge : EdgeDefaults {
  static constexpr const char* kTag = "EDGE_SE3:QUAT";
  VertexId from = 0;  // A
  VertexId to = 0;    // B
  Pose measurement;
  Matrix6d information = Matrix6d::Identity();
  int64_t line = 0;

  template <typename Self, typename V>
  static void Fields(Self& e, V& v) {
    v.Vertex({"a", VertexType::kPose, Role::kUnknown, {Role::kCamera, Role::kMotion}}, e.from);
    v.Vertex({"b", VertexType::kPose, Role::kUnknown, {Role::kCamera, Role::kMotion}}, e.to);
    v.Measurement(e.measurement);
    v.Information(e.information);
  }
  template <typename RoleOf>
  EdgeKind Kind(const RoleOf& role_of) const {
    return role_of(from) == Role::kMotion ? EdgeKind::kSmoothing : EdgeKind::kOdometry;
  }
};

// SPEC §1.2 EDGE_SE3_TRACKXYZ: r = X⁻¹ · m − z.
struct PointEdge : EdgeDefaults {
  static constexpr const char* kTag = "EDGE_SE3_TRACKXYZ";
  VertexId pose = 0;
  VertexId point = 0;
  Eigen::Vector3d measurement = Eigen::Vector3d::Zero();  // point in the camera frame
  Eigen::Matrix3d information = Eigen::Matrix3d::Identity();
  bool is_dynamic = false;
  int64_t line = 0;

  template <typename Self, typename V>
  static void Fields(Self& e, V& v) {
    const Role point_role = e.is_dynamic ? Role::kDynamicPoint : Role::kStaticPoint;
    v.Vertex({"pose", VertexType::kPose, Role::kCamera, {Role::kCamera}}, e.pose);
    v.Vertex({"point", VertexType::kPoint, point_role, {point_role}}, e.point);
    v.Measurement(e.measurement);
    v.Information(e.information);
    v.OptionalFlag("is_dynamic", e.is_dynamic);
  }
  template <typename RoleOf>
  EdgeKind Kind(const RoleOf& role_of) const {
    return role_of(point) == Role::kDynamicPoint ? EdgeKind::kDynamicPoint : EdgeKind::kPoint;
  }
};

// SPEC §1.2 EDGE_SE3_MOTION: r = m_curr − H · m_prev − z (ternary world-centric motion edge).
struct MotionEdge : EdgeDefaults {
  static constexpr const char* kTag = "EDGE_SE3_MOTION";
  VertexId prev = 0;
  VertexId curr = 0;
  VertexId motion = 0;
  Eigen::Vector3d measurement = Eigen::Vector3d::Zero();
  Eigen::Matrix3d information = Eigen::Matrix3d::Identity();
  int64_t object = 0;    // front end's object id j
  int64_t frame = 0;     // frame k of `curr`
  VertexId camera = 0;   // camera that observed `curr` (a vertex reference)
  int64_t line = 0;

  template <typename Self, typename V>
  static void Fields(Self& e, V& v) {
    v.Vertex({"prev", VertexType::kPoint, Role::kDynamicPoint, {Role::kDynamicPoint}}, e.prev);
    v.Vertex({"curr", VertexType::kPoint, Role::kDynamicPoint, {Role::kDynamicPoint}}, e.curr);
    v.Vertex({"motion", VertexType::kPose, Role::kMotion, {Role::kMotion}}, e.motion);
    v.Measurement(e.measurement);
    v.Information(e.information);
    v.Integer("object", e.object);
    v.Integer("frame", e.frame);
    v.Vertex({"camera", VertexType::kPose, Role::kCamera, {Role::kCamera}, false}, e.camera);
  }
  template <typename RoleOf>
  EdgeKind Kind(const RoleOf&) const {
    return EdgeKind::kMotion;
  }
  const char* Invalid() const {  // hides EdgeDefaults'
    return frame < 1 ? "frame must be at least 1 (the current point's frame k)" : "";
  }
  template <typename LabelOf>
  std::string Inconsistent(const LabelOf& label_of) const {
    const Label &p = label_of(prev), &c = label_of(curr), &h = label_of(motion);
    if (p.object != object || c.object != object || h.object != object) {
      return "EDGE_SE3_MOTION of object " + std::to_string(object) +
             " joins vertices labelled with objects " + std::to_string(p.object) + ", " +
             std::to_string(c.object) + " and " + std::to_string(h.object);
    }
    if (c.frame != frame || h.frame != frame || p.frame != frame - 1) {
      return "EDGE_SE3_MOTION at frame " + std::to_string(frame) +
             " joins points labelled at frames " + std::to_string(p.frame) + " and " +
             std::to_string(c.frame) + " and a motion at frame " + std::to_string(h.frame) +
             "; expected k-1, k and k";
    }
    return "";
  }
  // Dynamic points and motions take object and frame from their motion edges (SPEC §3.1).
  template <typename LabelAt>
  void Infer(const LabelAt& label_at) const {
    for (const auto& [id, at_frame] : {std::pair{motion, frame}, std::pair{curr, frame},
                                       std::pair{prev, frame - 1}}) {
      Label& label = label_at(id);
      label.object = object;
      label.frame = at_frame;
    }
  }
};

// SPEC §1.3 EDGE_SE3_OBJ_TRACKXYZ: r = X⁻¹ · L · m_L − z.
struct ObjectPointEdge : EdgeDefaults {
  static constexpr const char* kTag = "EDGE_SE3_OBJ_TRACKXYZ";
  VertexId camera = 0;
  VertexId object_pose = 0;
  VertexId point = 0;
  Eigen::Vector3d measurement = Eigen::Vector3d::Zero();
  Eigen::Matrix3d information = Eigen::Matrix3d::Identity();
  int64_t line = 0;

  template <typename Self, typename V>
  static void Fields(Self& e, V& v) {
    v.Vertex({"camera", VertexType::kPose, Role::kCamera, {Role::kCamera}}, e.camera);
    v.Vertex({"objpose", VertexType::kPose, Role::kObjectPose, {Role::kObjectPose}},
             e.object_pose);
    v.Vertex({"point", VertexType::kPoint, Role::kObjectPoint, {Role::kObjectPoint}}, e.point);
    v.Measurement(e.measurement);
    v.Information(e.information);
  }
  template <typename RoleOf>
  EdgeKind Kind(const RoleOf&) const {
    return EdgeKind::kObjectPoint;
  }
};

// SPEC §1.3 EDGE_SE3_OBJ_MOTION: r = L_curr · m_L − H · L_prev · m_L − z; z is the front-end
// motion edge's, a trailing optional field (0 when absent).
struct ObjectMotionEdge : EdgeDefaults {
  static constexpr const char* kTag = "EDGE_SE3_OBJ_MOTION";
  VertexId pose_prev = 0;
  VertexId pose_curr = 0;
  VertexId motion = 0;
  VertexId point = 0;
  Eigen::Matrix3d information = Eigen::Matrix3d::Identity();
  Eigen::Vector3d measurement = Eigen::Vector3d::Zero();
  int64_t line = 0;

  template <typename Self, typename V>
  static void Fields(Self& e, V& v) {
    v.Vertex({"pose_prev", VertexType::kPose, Role::kObjectPose, {Role::kObjectPose}},
             e.pose_prev);
    v.Vertex({"pose_curr", VertexType::kPose, Role::kObjectPose, {Role::kObjectPose}},
             e.pose_curr);
    v.Vertex({"motion", VertexType::kPose, Role::kMotion, {Role::kMotion}}, e.motion);
    v.Vertex({"point", VertexType::kPoint, Role::kObjectPoint, {Role::kObjectPoint}}, e.point);
    v.Information(e.information);
    v.OptionalMeasurement(e.measurement);
  }
  template <typename RoleOf>
  EdgeKind Kind(const RoleOf&) const {
    return EdgeKind::kObjectMotion;
  }
};

// SPEC §1.3 EDGE_SE3_OBJ_KINEMATIC: r = Log(L_curr⁻¹ · H · L_prev).
struct KinematicEdge : EdgeDefaults {
  static constexpr const char* kTag = "EDGE_SE3_OBJ_KINEMATIC";
  VertexId pose_prev = 0;
  VertexId pose_curr = 0;
  VertexId motion = 0;
  Matrix6d information = Matrix6d::Identity();
  int64_t line = 0;

  template <typename Self, typename V>
  static void Fields(Self& e, V& v) {
    v.Vertex({"pose_prev", VertexType::kPose, Role::kObjectPose, {Role::kObjectPose}},
             e.pose_prev);
    v.Vertex({"pose_curr", VertexType::kPose, Role::kObjectPose, {Role::kObjectPose}},
             e.pose_curr);
    v.Vertex({"motion", VertexType::kPose, Role::kMotion, {Role::kMotion}}, e.motion);
    v.Information(e.information);
  }
  template <typename RoleOf>
  EdgeKind Kind(const RoleOf&) const {
    return EdgeKind::kKinematic;
  }
};

// SPEC §3.6 EDGE_SE3_HY_TRACKXYZ: r = X⁻¹ · H · L_e · m − z.
struct HybridPointEdge : EdgeDefaults {
  static constexpr const char* kTag = "EDGE_SE3_HY_TRACKXYZ";
  VertexId camera = 0;
  VertexId motion = 0;    // H^e_k
  VertexId embedded = 0;  // L_e (constant)
  VertexId point = 0;     // m, in the object frame
  Eigen::Vector3d measurement = Eigen::Vector3d::Zero();
  Eigen::Matrix3d information = Eigen::Matrix3d::Identity();
  int64_t line = 0;

  template <typename Self, typename V>
  static void Fields(Self& e, V& v) {
    v.Vertex({"camera", VertexType::kPose, Role::kCamera, {Role::kCamera}}, e.camera);
    v.Vertex({"motion", VertexType::kPose, Role::kHybridMotion, {Role::kHybridMotion}}, e.motion);
    v.Vertex({"embedded", VertexType::kPose, Role::kEmbeddedFrame, {Role::kEmbeddedFrame}},
             e.embedded);
    v.Vertex({"point", VertexType::kPoint, Role::kObjectPoint, {Role::kObjectPoint}}, e.point);
    v.Measurement(e.measurement);
    v.Information(e.information);
  }
  template <typename RoleOf>
  EdgeKind Kind(const RoleOf&) const {
    return EdgeKind::kHybridPoint;
  }
  // The camera's frame is the motion's, motion and point are of one object, the motion's
  // embedded frame is the edge's and not later than the motion.
  template <typename LabelOf>
  std::string Inconsistent(const LabelOf& label_of) const {
    const Label &x = label_of(camera), &h = label_of(motion), &m = label_of(point);
    const std::string tag = kTag;
    if (x.frame != h.frame) {
      return tag + " joins a camera at frame " + std::to_string(x.frame) +
             " and a motion at frame " + std::to_string(h.frame);
    }
    if (h.object != m.object) {
      return tag + " joins a motion of object " + std::to_string(h.object) +
             " and a point of object " + std::to_string(m.object);
    }
    return HybridMotionAgrees(tag, h, embedded, label_of(embedded));
  }

  // Shared with HybridSmoothingEdge: `h` is a motion from embedded frame `id` (labelled `l_e`).
  static std::string HybridMotionAgrees(const std::string& tag, const Label& h, VertexId id,
                                        const Label& l_e) {
    if (h.embedded != id) {
      return tag + " names embedded frame " + std::to_string(id) + ", but its motion at frame " +
             std::to_string(h.frame) + " is labelled with embedded frame " +
             std::to_string(h.embedded);
    }
    if (l_e.object != h.object || l_e.frame > h.frame) {
      return tag + ": embedded frame " + std::to_string(id) + " (object " +
             std::to_string(l_e.object) + ", frame " + std::to_string(l_e.frame) +
             ") must be of the motion's object " + std::to_string(h.object) +
             " and not later than its frame " + std::to_string(h.frame);
    }
    return "";
  }
};

// SPEC §3.6 EDGE_SE3_HY_SMOOTHING: r = Log((L_a⁻¹ L_b)⁻¹ (L_b⁻¹ L_c)), L_x = H_x · L_e.
struct HybridSmoothingEdge : EdgeDefaults {
  static constexpr const char* kTag = "EDGE_SE3_HY_SMOOTHING";
  VertexId motion_a = 0;  // H^e_{k−2}
  VertexId motion_b = 0;  // H^e_{k−1}
  VertexId motion_c = 0;  // H^e_k
  VertexId embedded = 0;  // L_e (constant)
  Matrix6d information = Matrix6d::Identity();
  int64_t line = 0;

  template <typename Self, typename V>
  static void Fields(Self& e, V& v) {
    v.Vertex({"motion_a", VertexType::kPose, Role::kHybridMotion, {Role::kHybridMotion}},
             e.motion_a);
    v.Vertex({"motion_b", VertexType::kPose, Role::kHybridMotion, {Role::kHybridMotion}},
             e.motion_b);
    v.Vertex({"motion_c", VertexType::kPose, Role::kHybridMotion, {Role::kHybridMotion}},
             e.motion_c);
    v.Vertex({"embedded", VertexType::kPose, Role::kEmbeddedFrame, {Role::kEmbeddedFrame}},
             e.embedded);
    v.Information(e.information);
  }
  template <typename RoleOf>
  EdgeKind Kind(const RoleOf&) const {
    return EdgeKind::kHybridSmoothing;
  }
  // Motions of one object at frames k−2, k−1, k, all from the edge's embedded frame.
  template <typename LabelOf>
  std::string Inconsistent(const LabelOf& label_of) const {
    const Label &a = label_of(motion_a), &b = label_of(motion_b), &c = label_of(motion_c);
    const std::string tag = kTag;
    if (a.object != c.object || b.object != c.object || a.frame != c.frame - 2 ||
        b.frame != c.frame - 1) {
      return tag + " joins motions labelled (object, frame) (" + std::to_string(a.object) + ", " +
             std::to_string(a.frame) + "), (" + std::to_string(b.object) + ", " +
             std::to_string(b.frame) + "), (" + std::to_string(c.object) + ", " +
             std::to_string(c.frame) + "); expected one object at frames k-2, k-1, k";
    }
    for (const Label* h : {&a, &b, &c}) {
      const std::string wrong =
          HybridPointEdge::HybridMotionAgrees(tag, *h, embedded, label_of(embedded));
      if (!wrong.empty()) return wrong;
    }
    return "";
  }
};

// Every edge struct, in the order the reader looks tags up and the solver adds residuals.
template <typename... Edges>
struct TypeList {
  using Vectors = std::tuple<std::vector<Edges>...>;
  template <typename F>
  static void ForEach(F&& f) {
    (f(static_cast<Edges*>(nullptr)), ...);
  }
};
using EdgeTypes = TypeList<PriorEdge, BetweenEdge, PointEdge, MotionEdge, ObjectPointEdge,
                           ObjectMotionEdge, KinematicEdge, HybridPointEdge, HybridSmoothingEdge>;

// f(const VertexField&, VertexId) for every vertex field of `edge`, in file order.
template <typename Edge, typename F>
void ForEachVertexField(const Edge& edge, F&& f) {
  struct Visit : IgnoreFields {
    std::remove_reference_t<F>* f;
    void Vertex(const VertexField& field, VertexId id) { (*f)(field, id); }
  } visit;
  visit.f = &f;
  Edge::Fields(edge, visit);
}

// Ids of an edge's vertex fields in file order; `parameters_only` leaves out references.
template <typename Edge>
std::vector<VertexId> VertexIds(const Edge& edge, bool parameters_only = false) {
  std::vector<VertexId> ids;
  ForEachVertexField(edge, [&](const VertexField& field, VertexId id) {
    if (field.parameter || !parameters_only) ids.push_back(id);
  });
  return ids;
}

}  // namespace dynslam

#endif  // DYNSLAM_GRAPH_SCHEMA_H_
