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

// An error unless vertex `id` has one of `roles`.
Status Expect(const Graph& graph, VertexId id, std::initializer_list<Role> roles, int64_t line,
              const char* tag, const char* field) {
  const Role role = graph.RoleOf(id);
  if (std::find(roles.begin(), roles.end(), role) != roles.end()) return Status::Ok();
  std::string wanted;
  for (const Role r : roles) wanted += std::string(wanted.empty() ? "" : " or ") + RoleName(r);
  return Error{"", line,
               std::string(tag) + " field '" + field + "' is " + IdText(id) + ", a " +
                   RoleName(role) + "; expected a " + wanted + " (its label disagrees with the edge)"};
}

// Roles from the edges of an unlabelled graph (SPEC §3.1 and the §1.3 edges): every vertex
// field's `claim` (graph_schema.h).
Status InferRoles(Graph& graph) {
  RoleClaims claims;
  graph.ForEachEdgeVector([&](const auto& edges) {
    for (const auto& e : edges) {
      ForEachVertexField(e, [&](const VertexField& field, VertexId id) {
        if (field.claim != Role::kUnknown) claims.Claim(id, field.claim, e.line, e.kTag);
      });
    }
  });
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
  graph.ForEachEdgeVector([&](const auto& edges) {
    for (const auto& e : edges) {
      e.Infer([&](VertexId id) -> Label& { return graph.vertices.at(id).label; });
    }
  });
  return Status::Ok();
}

// Labels against edges (SPEC §1.4): every vertex field's `allowed` roles, then each struct's
// `Inconsistent`.
Status CheckLabelledRoles(const Graph& graph) {
  Status status;
  graph.ForEachEdgeVector([&](const auto& edges) {
    for (const auto& e : edges) {
      ForEachVertexField(e, [&](const VertexField& field, VertexId id) {
        if (status.ok()) status = Expect(graph, id, field.allowed, e.line, e.kTag, field.name);
      });
    }
  });
  if (!status.ok()) return status;
  graph.ForEachEdgeVector([&](const auto& edges) {
    for (const auto& e : edges) {
      if (!status.ok()) return;
      const std::string inconsistent =
          e.Inconsistent([&](VertexId id) -> const Label& { return graph.Find(id)->label; });
      if (!inconsistent.empty()) status = Error{"", e.line, inconsistent};
    }
  });
  if (!status.ok()) return status;
  return Status::Ok();
}

// Checks shared by labelled and unlabelled graphs: odometry/smoothing join poses of one role,
// motion edges use dynamic points observed by their `camera`, tracklets do not branch (§1.6).
Status CheckEdgesAgainstRoles(const Graph& graph) {
  for (const BetweenEdge& e : graph.Edges<BetweenEdge>()) {
    const Role a = graph.RoleOf(e.from), b = graph.RoleOf(e.to);
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
  for (const PointEdge& e : graph.Edges<PointEdge>()) observers.emplace(e.point, std::pair{e.pose, e.line});
  std::unordered_map<VertexId, int64_t> as_prev, as_curr;  // point → line of its motion edge
  for (const MotionEdge& e : graph.Edges<MotionEdge>()) {
    for (const VertexId id : {e.prev, e.curr}) {
      if (graph.RoleOf(id) != Role::kDynamicPoint) {
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

const Vertex* Graph::Find(VertexId id) const {
  auto it = vertices.find(id);
  return it == vertices.end() ? nullptr : &it->second;
}

Vertex* Graph::Find(VertexId id) {
  auto it = vertices.find(id);
  return it == vertices.end() ? nullptr : &it->second;
}

size_t Graph::NumVariables() const {
  return std::count_if(vertices.begin(), vertices.end(), [](const auto& entry) {
    const RoleInfo* role = InfoOf(entry.second.label.role);
    return role == nullptr || !role->constant;
  });
}

size_t Graph::NumEdges() const {
  size_t n = 0;
  ForEachEdgeVector([&](const auto& edges) { n += edges.size(); });
  return n;
}

std::array<int64_t, kNumEdgeKinds> CountEdgesByKind(const Graph& graph) {
  std::array<int64_t, kNumEdgeKinds> counts{};
  graph.ForEachEdgeVector([&](const auto& edges) {
    for (const auto& edge : edges) ++counts[static_cast<int>(KindOf(graph, edge))];
  });
  return counts;
}

std::array<int64_t, kNumRoles> CountVerticesByRole(const Graph& graph) {
  std::array<int64_t, kNumRoles> counts{};
  for (const auto& [id, vertex] : graph.vertices) {
    for (size_t r = 0; r < kNumRoles; ++r) counts[r] += vertex.label.role == kAllRoles[r];
  }
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
  graph.ForEachEdgeVector([&](const auto& edges) {
    for (const auto& e : edges) {
      for (const VertexId id : VertexIds(e)) used.insert(id);
    }
  });
  std::vector<VertexId> unused;
  for (const auto& [id, vertex] : graph.vertices) {
    if (used.count(id) == 0) unused.push_back(id);
  }
  return unused;
}

}  // namespace dynslam
