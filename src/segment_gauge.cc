#include "src/segment_gauge.h"

#include <map>
#include <numeric>
#include <type_traits>
#include <unordered_map>

#include "dynslam/se3.h"

namespace dynslam {
namespace {

// Union–find over block indices.
class Components {
 public:
  explicit Components(size_t n) : parent_(n) { std::iota(parent_.begin(), parent_.end(), 0); }
  size_t Root(size_t i) {
    while (parent_[i] != i) i = parent_[i] = parent_[parent_[i]];
    return i;
  }
  void Join(size_t a, size_t b) { parent_[Root(a)] = Root(b); }

 private:
  std::vector<size_t> parent_;
};

bool InSegment(Role role) { return role == Role::kObjectPose || role == Role::kObjectPoint; }

// Edges whose residual the gauge leaves unchanged (object point, object motion), or changes only
// through G's translation (kinematic): they join their object vertices into one segment.
bool JoinsSegment(EdgeKind kind) {
  return kind == EdgeKind::kObjectPoint || kind == EdgeKind::kObjectMotion ||
         kind == EdgeKind::kKinematic;
}

struct Candidate {
  std::vector<size_t> poses, points;
  std::vector<const PriorEdge*> priors;
  bool usable = true;
};

}  // namespace

SegmentGauges SegmentGauges::Find(const Graph& graph, const Layout& layout) {
  Components components(graph.vertices.size());
  std::unordered_map<size_t, const PriorEdge*> prior_of;  // object pose → its prior
  std::vector<size_t> spoiled;  // object vertices some other edge also uses
  graph.ForEachEdgeVector([&](const auto& edges) {
    for (const auto& e : edges) {
      const EdgeKind kind = KindOf(graph, e);
      std::vector<size_t> members;
      for (const VertexId id : VertexIds(e, true)) {
        if (InSegment(graph.RoleOf(id))) members.push_back(layout.index(id));
      }
      if (members.empty()) continue;
      if (JoinsSegment(kind)) {
        for (const size_t m : members) components.Join(m, members.front());
      } else if constexpr (std::is_same_v<std::decay_t<decltype(e)>, PriorEdge>) {
        if (!prior_of.emplace(members.front(), &e).second) {
          spoiled.push_back(members.front());  // two priors on one pose
        }
      } else {
        spoiled.insert(spoiled.end(), members.begin(), members.end());
      }
    }
  });

  std::map<size_t, Candidate> candidates;  // by root: segments in a fixed order
  for (const auto& [id, vertex] : graph.vertices) {
    if (!InSegment(vertex.label.role)) continue;
    const size_t index = layout.index(id);
    Candidate& c = candidates[components.Root(index)];
    c.usable = c.usable && layout.movable(id);
    if (vertex.label.role == Role::kObjectPose) {
      c.poses.push_back(index);
      if (auto prior = prior_of.find(index); prior != prior_of.end()) {
        c.priors.push_back(prior->second);
      }
    } else if (!layout.world_anchored(id)) {
      c.points.push_back(index);
    }
  }
  for (const size_t index : spoiled) candidates[components.Root(index)].usable = false;

  SegmentGauges gauges;
  for (auto& [root, c] : candidates) {
    if (!c.usable || c.priors.size() != 1) continue;
    const PriorEdge& prior = *c.priors.front();
    gauges.segments_.push_back({layout.index(prior.pose), prior.measurement,
                                PosePriorError(prior.measurement, prior.information),
                                std::move(c.poses), std::move(c.points)});
  }
  return gauges;
}

double SegmentGauges::PriorCost(const Values& values) const {
  double cost = 0;
  for (const Segment& s : segments_) {
    Vector6d r;
    s.error(values[s.prior_pose].data(), r.data());
    cost += 0.5 * r.squaredNorm();
  }
  return cost;
}

void SegmentGauges::Snap(Values* values) const {
  for (const Segment& s : segments_) {
    Pose first;
    first.data = (*values)[s.prior_pose];
    const Pose g = Compose(Inverse(first), s.measurement);
    const Pose g_inverse = Inverse(g);
    for (const size_t i : s.poses) {
      Pose pose;
      pose.data = (*values)[i];
      (*values)[i] = Compose(pose, g).data;
    }
    for (const size_t i : s.points) {
      double* m = (*values)[i].data();
      PoseTransformPoint(g_inverse.data.data(), m, m);
    }
  }
}

}  // namespace dynslam
