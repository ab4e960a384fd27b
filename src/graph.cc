#include "dynslam/graph.h"

#include <algorithm>
#include <unordered_map>
#include <unordered_set>

namespace dynslam {
namespace {

std::string IdText(VertexId id) { return "vertex " + std::to_string(id); }

// Collects the role each edge field implies for its vertex, and reports the first conflict.
class RoleClaims {
 public:
  RoleClaims() = default;

  void Claim(VertexId id, Role role, int64_t line, const char* tag) {
    if (!status_.ok()) return;
    auto [it, inserted] = claims_.try_emplace(id, Claimed{role, line, tag});
    if (!inserted && it->second.role != role) {
      status_ = Error{"", line,
                      std::string(tag) + " uses " + IdText(id) + " as " + RoleName(role) +
                          ", but the " + it->second.tag + " on line " +
                          std::to_string(it->second.line) + " uses it as " +
                          RoleName(it->second.role)};
    }
  }

  Role Of(VertexId id) const {
    auto it = claims_.find(id);
    return it == claims_.end() ? Role::kUnknown : it->second.role;
  }
  const Status& status() const { return status_; }

 private:
  struct Claimed {
    Role role;
    int64_t line;
    const char* tag;
  };
  std::unordered_map<VertexId, Claimed> claims_;
  Status status_;
};

Role RoleOf(const Graph& graph, VertexId id) {
  const Vertex* vertex = graph.Find(id);
  return vertex == nullptr ? Role::kUnknown : vertex->label.role;
}

// An error unless vertex `id` has one of `roles`.
Status Expect(const Graph& graph, VertexId id, std::initializer_list<Role> roles, int64_t line,
              const char* tag, const char* field) {
  const Role role = RoleOf(graph, id);
  if (std::find(roles.begin(), roles.end(), role) != roles.end()) return Status::Ok();
  std::string wanted;
  for (const Role r : roles) wanted += std::string(wanted.empty() ? "" : " or ") + RoleName(r);
  return Error{"", line,
               std::string(tag) + " field '" + field + "' is " + IdText(id) + ", a " +
                   RoleName(role) + "; expected a " + wanted + " (its label disagrees with the edge)"};
}

// Roles from the edges of an unlabelled graph (SPEC §3.1 and the §1.3 edges).
Status InferRoles(Graph& graph) {
  RoleClaims claims;
  for (const PointEdge& e : graph.point_edges) {
    claims.Claim(e.pose, Role::kCamera, e.line, "EDGE_SE3_TRACKXYZ");
    claims.Claim(e.point, e.is_dynamic ? Role::kDynamicPoint : Role::kStaticPoint, e.line,
                 "EDGE_SE3_TRACKXYZ");
  }
  for (const MotionEdge& e : graph.motion_edges) {
    claims.Claim(e.prev, Role::kDynamicPoint, e.line, "EDGE_SE3_MOTION");
    claims.Claim(e.curr, Role::kDynamicPoint, e.line, "EDGE_SE3_MOTION");
    claims.Claim(e.motion, Role::kMotion, e.line, "EDGE_SE3_MOTION");
    claims.Claim(e.camera, Role::kCamera, e.line, "EDGE_SE3_MOTION");
  }
  for (const ObjectPointEdge& e : graph.object_point_edges) {
    claims.Claim(e.camera, Role::kCamera, e.line, "EDGE_SE3_OBJ_TRACKXYZ");
    claims.Claim(e.object_pose, Role::kObjectPose, e.line, "EDGE_SE3_OBJ_TRACKXYZ");
    claims.Claim(e.point, Role::kObjectPoint, e.line, "EDGE_SE3_OBJ_TRACKXYZ");
  }
  for (const ObjectMotionEdge& e : graph.object_motion_edges) {
    claims.Claim(e.pose_prev, Role::kObjectPose, e.line, "EDGE_SE3_OBJ_MOTION");
    claims.Claim(e.pose_curr, Role::kObjectPose, e.line, "EDGE_SE3_OBJ_MOTION");
    claims.Claim(e.motion, Role::kMotion, e.line, "EDGE_SE3_OBJ_MOTION");
    claims.Claim(e.point, Role::kObjectPoint, e.line, "EDGE_SE3_OBJ_MOTION");
  }
  for (const KinematicEdge& e : graph.kinematic_edges) {
    claims.Claim(e.pose_prev, Role::kObjectPose, e.line, "EDGE_SE3_OBJ_KINEMATIC");
    claims.Claim(e.pose_curr, Role::kObjectPose, e.line, "EDGE_SE3_OBJ_KINEMATIC");
    claims.Claim(e.motion, Role::kMotion, e.line, "EDGE_SE3_OBJ_KINEMATIC");
  }
  if (!claims.status().ok()) return claims.status();

  // Poses in no role-giving edge are cameras; points, static points. Cameras sorted by id get
  // frames 0, 1, 2, … (the released code's rule, SPEC §3.1).
  int64_t frame = 0;
  for (auto& [id, vertex] : graph.vertices) {
    Role role = claims.Of(id);
    if (role == Role::kUnknown) {
      role = vertex.type == VertexType::kPose ? Role::kCamera : Role::kStaticPoint;
    }
    vertex.label = Label{role};
    if (role == Role::kCamera) vertex.label.frame = frame++;
  }
  // Dynamic points and motions take object and frame from their motion edges.
  for (const MotionEdge& e : graph.motion_edges) {
    Label& motion = graph.vertices.at(e.motion).label;
    motion.object = e.object;
    motion.frame = e.frame;
    Label& curr = graph.vertices.at(e.curr).label;
    curr.object = e.object;
    curr.frame = e.frame;
    Label& prev = graph.vertices.at(e.prev).label;
    prev.object = e.object;
    prev.frame = e.frame - 1;
  }
  return Status::Ok();
}

// Labels against edges (SPEC §1.4).
Status CheckLabelledRoles(const Graph& graph) {
  using R = Role;
  for (const PriorEdge& e : graph.priors) {
    if (Status s = Expect(graph, e.pose, {R::kCamera, R::kObjectPose, R::kMotion}, e.line,
                          "EDGE_SE3_PRIOR", "id");
        !s.ok()) {
      return s;
    }
  }
  for (const PointEdge& e : graph.point_edges) {
    if (Status s = Expect(graph, e.pose, {R::kCamera}, e.line, "EDGE_SE3_TRACKXYZ", "pose"); !s.ok()) {
      return s;
    }
    const R point_role = e.is_dynamic ? R::kDynamicPoint : R::kStaticPoint;
    if (Status s = Expect(graph, e.point, {point_role}, e.line, "EDGE_SE3_TRACKXYZ", "point");
        !s.ok()) {
      return s;
    }
  }
  for (const MotionEdge& e : graph.motion_edges) {
    const char* tag = "EDGE_SE3_MOTION";
    for (const auto& [id, field] : {std::pair{e.prev, "prev"}, std::pair{e.curr, "curr"}}) {
      if (Status s = Expect(graph, id, {R::kDynamicPoint}, e.line, tag, field); !s.ok()) return s;
    }
    if (Status s = Expect(graph, e.motion, {R::kMotion}, e.line, tag, "motion"); !s.ok()) return s;
    if (Status s = Expect(graph, e.camera, {R::kCamera}, e.line, tag, "camera"); !s.ok()) return s;
    const Label& prev = graph.Find(e.prev)->label;
    const Label& curr = graph.Find(e.curr)->label;
    const Label& motion = graph.Find(e.motion)->label;
    if (prev.object != e.object || curr.object != e.object || motion.object != e.object) {
      return Error{"", e.line,
                   "EDGE_SE3_MOTION of object " + std::to_string(e.object) +
                       " joins vertices labelled with objects " + std::to_string(prev.object) +
                       ", " + std::to_string(curr.object) + " and " + std::to_string(motion.object)};
    }
    if (curr.frame != e.frame || motion.frame != e.frame || prev.frame != e.frame - 1) {
      return Error{"", e.line,
                   "EDGE_SE3_MOTION at frame " + std::to_string(e.frame) +
                       " joins points labelled at frames " + std::to_string(prev.frame) + " and " +
                       std::to_string(curr.frame) + " and a motion at frame " +
                       std::to_string(motion.frame) + "; expected k-1, k and k"};
    }
  }
  for (const BetweenEdge& e : graph.betweens) {
    if (Status s = Expect(graph, e.from, {R::kCamera, R::kMotion}, e.line, "EDGE_SE3:QUAT", "a");
        !s.ok()) {
      return s;
    }
  }
  for (const ObjectPointEdge& e : graph.object_point_edges) {
    const char* tag = "EDGE_SE3_OBJ_TRACKXYZ";
    if (Status s = Expect(graph, e.camera, {R::kCamera}, e.line, tag, "camera"); !s.ok()) return s;
    if (Status s = Expect(graph, e.object_pose, {R::kObjectPose}, e.line, tag, "objpose"); !s.ok()) {
      return s;
    }
    if (Status s = Expect(graph, e.point, {R::kObjectPoint}, e.line, tag, "point"); !s.ok()) return s;
  }
  for (const ObjectMotionEdge& e : graph.object_motion_edges) {
    const char* tag = "EDGE_SE3_OBJ_MOTION";
    for (const auto& [id, field] :
         {std::pair{e.pose_prev, "pose_prev"}, std::pair{e.pose_curr, "pose_curr"}}) {
      if (Status s = Expect(graph, id, {R::kObjectPose}, e.line, tag, field); !s.ok()) return s;
    }
    if (Status s = Expect(graph, e.motion, {R::kMotion}, e.line, tag, "motion"); !s.ok()) return s;
    if (Status s = Expect(graph, e.point, {R::kObjectPoint}, e.line, tag, "point"); !s.ok()) return s;
  }
  for (const KinematicEdge& e : graph.kinematic_edges) {
    const char* tag = "EDGE_SE3_OBJ_KINEMATIC";
    for (const auto& [id, field] :
         {std::pair{e.pose_prev, "pose_prev"}, std::pair{e.pose_curr, "pose_curr"}}) {
      if (Status s = Expect(graph, id, {R::kObjectPose}, e.line, tag, field); !s.ok()) return s;
    }
    if (Status s = Expect(graph, e.motion, {R::kMotion}, e.line, tag, "motion"); !s.ok()) return s;
  }
  return Status::Ok();
}

// Checks shared by labelled and unlabelled graphs: odometry/smoothing join poses of one role,
// motion edges use dynamic points observed by their `camera`, tracklets do not branch (§1.6).
Status CheckEdgesAgainstRoles(const Graph& graph) {
  for (const BetweenEdge& e : graph.betweens) {
    const Role a = RoleOf(graph, e.from), b = RoleOf(graph, e.to);
    if (a != b || (a != Role::kCamera && a != Role::kMotion)) {
      return Error{"", e.line,
                   "EDGE_SE3:QUAT joins " + IdText(e.from) + " (" + RoleName(a) + ") and " +
                       IdText(e.to) + " (" + RoleName(b) +
                       "); it must join two cameras (odometry) or two motions (smoothing)"};
    }
  }
  // point → (camera, line) of every EDGE_SE3_TRACKXYZ observing it. The check below is about
  // the set, so it does not depend on the order of the lines (found by fuzzing).
  std::unordered_multimap<VertexId, std::pair<VertexId, int64_t>> observers;
  for (const PointEdge& e : graph.point_edges) observers.emplace(e.point, std::pair{e.pose, e.line});
  std::unordered_map<VertexId, int64_t> as_prev, as_curr;  // point → line of its motion edge
  for (const MotionEdge& e : graph.motion_edges) {
    for (const VertexId id : {e.prev, e.curr}) {
      if (RoleOf(graph, id) != Role::kDynamicPoint) {
        return Error{"", e.line,
                     "EDGE_SE3_MOTION uses point " + std::to_string(id) +
                         ", which is not a dynamic point (its EDGE_SE3_TRACKXYZ has is_dynamic = 0)"};
      }
    }
    // SPEC §1.2: `camera` is the camera of the current point's EDGE_SE3_TRACKXYZ, so the
    // current point must have one.
    const auto [first, last] = observers.equal_range(e.curr);
    if (first == last) {
      return Error{"", e.line,
                   "EDGE_SE3_MOTION names camera " + std::to_string(e.camera) + ", but point " +
                       std::to_string(e.curr) +
                       " ('curr') has no EDGE_SE3_TRACKXYZ: a dynamic point must be observed"};
    }
    if (std::none_of(first, last, [&](const auto& observer) {
          return observer.second.first == e.camera;
        })) {
      return Error{"", e.line,
                   "EDGE_SE3_MOTION names camera " + std::to_string(e.camera) + ", but point " +
                       std::to_string(e.curr) + " is observed by camera " +
                       std::to_string(first->second.first) + " (line " +
                       std::to_string(first->second.second) + ")"};
    }
    if (auto [it, inserted] = as_prev.emplace(e.prev, e.line); !inserted) {
      return Error{"", e.line,
                   "tracklet branches: point " + std::to_string(e.prev) +
                       " is 'prev' of two motion edges (the other on line " +
                       std::to_string(it->second) + ")"};
    }
    if (auto [it, inserted] = as_curr.emplace(e.curr, e.line); !inserted) {
      return Error{"", e.line,
                   "tracklet branches: point " + std::to_string(e.curr) +
                       " is 'curr' of two motion edges (the other on line " +
                       std::to_string(it->second) + ")"};
    }
  }
  return Status::Ok();
}

}  // namespace

const char* RoleName(Role role) {
  switch (role) {
    case Role::kUnknown: return "unknown";
    case Role::kCamera: return "camera";
    case Role::kStaticPoint: return "static_point";
    case Role::kDynamicPoint: return "dynamic_point";
    case Role::kMotion: return "motion";
    case Role::kObjectPose: return "object_pose";
    case Role::kObjectPoint: return "object_point";
  }
  return "unknown";
}

const char* EdgeKindName(EdgeKind kind) {
  switch (kind) {
    case EdgeKind::kPrior: return "prior";
    case EdgeKind::kOdometry: return "odometry";
    case EdgeKind::kSmoothing: return "smoothing";
    case EdgeKind::kPoint: return "point";
    case EdgeKind::kDynamicPoint: return "dynamic_point";
    case EdgeKind::kMotion: return "motion";
    case EdgeKind::kObjectPoint: return "object_point";
    case EdgeKind::kObjectMotion: return "object_motion";
    case EdgeKind::kKinematic: return "kinematic";
    case EdgeKind::kObjectPrior: return "object_prior";
  }
  return "?";
}

const Vertex* Graph::Find(VertexId id) const {
  auto it = vertices.find(id);
  return it == vertices.end() ? nullptr : &it->second;
}

Vertex* Graph::Find(VertexId id) {
  auto it = vertices.find(id);
  return it == vertices.end() ? nullptr : &it->second;
}

size_t Graph::NumEdges() const {
  return priors.size() + betweens.size() + point_edges.size() + motion_edges.size() +
         object_point_edges.size() + object_motion_edges.size() + kinematic_edges.size();
}

EdgeKind KindOf(const Graph& graph, const PriorEdge& edge) {
  return RoleOf(graph, edge.pose) == Role::kObjectPose ? EdgeKind::kObjectPrior : EdgeKind::kPrior;
}

EdgeKind KindOf(const Graph& graph, const BetweenEdge& edge) {
  return RoleOf(graph, edge.from) == Role::kMotion ? EdgeKind::kSmoothing : EdgeKind::kOdometry;
}

EdgeKind KindOf(const Graph& graph, const PointEdge& edge) {
  return RoleOf(graph, edge.point) == Role::kDynamicPoint ? EdgeKind::kDynamicPoint
                                                          : EdgeKind::kPoint;
}

std::array<int64_t, kNumEdgeKinds> CountEdgesByKind(const Graph& graph) {
  std::array<int64_t, kNumEdgeKinds> counts{};
  auto count = [&](const auto& edges) {
    for (const auto& edge : edges) ++counts[static_cast<int>(KindOf(graph, edge))];
  };
  count(graph.priors);
  count(graph.betweens);
  count(graph.point_edges);
  count(graph.motion_edges);
  count(graph.object_point_edges);
  count(graph.object_motion_edges);
  count(graph.kinematic_edges);
  return counts;
}

Status AssignRoles(Graph& graph, const std::string& file) {
  Status status = graph.labelled ? CheckLabelledRoles(graph) : InferRoles(graph);
  if (status.ok()) status = CheckEdgesAgainstRoles(graph);
  if (status.ok()) return status;
  Error error = status.error();
  error.file = file;
  return error;
}

std::vector<VertexId> UnusedVertices(const Graph& graph) {
  std::unordered_set<VertexId> used;
  for (const auto& e : graph.priors) used.insert(e.pose);
  for (const auto& e : graph.betweens) used.insert({e.from, e.to});
  for (const auto& e : graph.point_edges) used.insert({e.pose, e.point});
  for (const auto& e : graph.motion_edges) used.insert({e.prev, e.curr, e.motion, e.camera});
  for (const auto& e : graph.object_point_edges) used.insert({e.camera, e.object_pose, e.point});
  for (const auto& e : graph.object_motion_edges) {
    used.insert({e.pose_prev, e.pose_curr, e.motion, e.point});
  }
  for (const auto& e : graph.kinematic_edges) used.insert({e.pose_prev, e.pose_curr, e.motion});
  std::vector<VertexId> unused;
  for (const auto& [id, vertex] : graph.vertices) {
    if (used.count(id) == 0) unused.push_back(id);
  }
  return unused;
}

}  // namespace dynslam
