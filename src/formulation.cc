#include "dynslam/formulation.h"

#include <algorithm>
#include <map>
#include <set>
#include <sstream>
#include <unordered_map>

#include <Eigen/SVD>

#include "dynslam/se3.h"  // header-only, Eigen only

namespace dynslam {
namespace {

// A maximal chain of dynamic points linked by motion edges (SPEC §3.1), or one static point.
struct Tracklet {
  bool dynamic = false;
  int64_t object = -1;
  int64_t id = -1;                          // tracklet id (labels or SPEC §3.1 numbering)
  std::vector<VertexId> points;             // in time order
  std::vector<const MotionEdge*> edges;     // edges[i] joins points[i] and points[i + 1]
};

// A maximal run of frames k0..k1 of one object joined by motion edges (SPEC §3.1).
struct Segment {
  int64_t object = 0;
  int64_t first = 0;  // k0
  int64_t last = 0;   // k1
  bool kept = false;
  std::vector<Tracklet*> tracklets;
  int64_t frames() const { return last - first + 1; }
};

// Kinds every formulation carries over from the front end (SPEC §3.2): not in `emits`.
bool IsSharedEdgeKind(EdgeKind kind) {
  return kind == EdgeKind::kPrior || kind == EdgeKind::kOdometry || kind == EdgeKind::kPoint;
}

std::string Count(int64_t n, const char* what) { return std::to_string(n) + " " + what; }

// Information 1/σ_r² on ω and 1/σ_t² on ρ (tangent order [ω; ρ], SPEC §0).
Matrix6d InformationFromSigmas(double sigma_rotation, double sigma_translation) {
  Vector6d diagonal;
  diagonal << Eigen::Vector3d::Constant(1 / (sigma_rotation * sigma_rotation)),
      Eigen::Vector3d::Constant(1 / (sigma_translation * sigma_translation));
  return diagonal.asDiagonal();
}

// What one build adds to the analysis: the next free id, the ids it gave, and how many first
// poses came from the ground truth.
struct BuildState {
  VertexId next_id = 0;
  std::map<const Tracklet*, VertexId> object_point;                  // oc: m_L per tracklet
  std::map<const Segment*, std::map<int64_t, VertexId>> pose_ids;  // oc: frame → L_k
  int from_truth = 0;
};

// Analyse() reads the front end once (tracklets, segments, what is kept and dropped, SPEC §3.1);
// Build() is const: each formulation's steps read that analysis and write only their graph and
// BuildState, so every formulation is built from the same analysis.
class Builder {
 public:
  Builder(const Graph& front_end, const BuildOptions& options, const GroundTruth* gt,
          BuildReport* report, const std::string& name)
      : fe_(front_end), options_(options), gt_(gt), report_(report), name_(name) {}

  Status Analyse();
  Expected<Graph> Build(Formulation formulation) const;

 private:
  Error Fail(int64_t line, const std::string& message) const { return Error{name_, line, message}; }
  void Say(const std::string& line) const {
    if (report_ != nullptr) report_->lines.push_back(line);
  }
  Status FindTracklets();
  Status FindSegments();
  void ReportDrops();
  void WarnUnderdeterminedMotions();

  bool Kept(const Tracklet& t) const {
    auto it = segment_of_.find(&t);
    return t.dynamic && t.points.size() > 1 && it != segment_of_.end() && it->second->kept;
  }
  // SPEC §3.2: a smoothing edge is kept when it joins the motions of consecutive frames of one
  // kept segment. Two kept motions of one object at frames k and k+1 are in one segment (its
  // motions are those of every frame k0+1 … k1), so this is the whole test.
  bool KeptSmoothing(const BetweenEdge& e) const {
    if (kept_motions_.count(e.from) == 0 || kept_motions_.count(e.to) == 0) return false;
    const Label& a = fe_.Find(e.from)->label;
    const Label& b = fe_.Find(e.to)->label;
    return a.object == b.object && (a.frame - b.frame == 1 || b.frame - a.frame == 1);
  }
  Pose MotionValue(VertexId id) const {
    return options_.motion_init == MotionInit::kIdentity ? Pose::Identity()
                                                         : fe_.Find(id)->pose();
  }
  // Object poses and object-frame points of one kept segment (SPEC §3.3), into `out`.
  void InitialiseSegment(const Segment& segment, BuildState& state, Graph& out) const;
  // SPEC §3.3's first-frame rule: the true object pose seen from its camera, placed in the
  // drifted initial world; false when the ground truth lacks the object or the camera at k.
  bool PoseFromTruth(int64_t object, int64_t k, Pose* pose) const;
  // The centroid of the initial world points of `segment` at frame k, identity rotation.
  Pose Centroid(const Segment& segment, int64_t k) const;
  // --compat dynosam (§3.6): X_k · mean of every measurement z of the object at k (dropped
  // tracklets included), identity rotation; a point's world position from its measurement.
  Pose MeasuredCentroid(int64_t object, int64_t k) const;
  Eigen::Vector3d MeasuredWorldPoint(VertexId point) const;

  // The build steps: every formulation starts with AddShared; then its own.
  void AddShared(Graph& out, bool with_motions) const;
  void AddWorldCentric(Graph& out) const;
  void AddObjectCentric(Graph& out, Formulation formulation, BuildState& state) const;
  void AddHybrid(Graph& out, BuildState& state) const;
  // SPEC §3.6: one segment's embedded frame, hybrid motions (ids in `motion_ids` by frame),
  // object points, point edges and anchor.
  void AddHybridSegment(const Segment& segment, BuildState& state, Graph& out,
                        std::map<int64_t, VertexId>* motion_ids) const;
  Matrix6d HybridSmoothingInformation(const BetweenEdge& e, const Pose& embedded) const;
  void AddVertex(Graph& out, VertexId id, const Label& label) const {
    Vertex vertex = *fe_.Find(id);
    vertex.label = label;
    vertex.line = 0;
    out.vertices.emplace(id, vertex);
  }

  const Graph& fe_;
  const BuildOptions& options_;
  const GroundTruth* gt_;
  BuildReport* report_;
  std::string name_;

  std::map<int64_t, VertexId> camera_of_frame_;
  std::unordered_map<VertexId, const PointEdge*> dynamic_observation_;
  std::vector<Tracklet> tracklets_;  // static and dynamic, sorted by first point id
  std::unordered_map<VertexId, Tracklet*> tracklet_of_point_;
  std::map<std::pair<int64_t, int64_t>, VertexId> motion_at_;  // (object, frame) → motion
  std::vector<Segment> segments_;                                // by object, then time
  std::unordered_map<const Tracklet*, Segment*> segment_of_;
  std::set<VertexId> kept_motions_;
};

Status Builder::FindTracklets() {
  std::unordered_map<VertexId, const MotionEdge*> next, previous;
  for (const MotionEdge& e : fe_.Edges<MotionEdge>()) {
    next[e.prev] = &e;
    previous[e.curr] = &e;
  }
  for (const PointEdge& e : fe_.Edges<PointEdge>()) {
    if (!e.is_dynamic) continue;
    if (auto [it, inserted] = dynamic_observation_.emplace(e.point, &e); !inserted) {
      return Fail(e.line, "dynamic point " + std::to_string(e.point) +
                              " is observed twice (also on line " +
                              std::to_string(it->second->line) +
                              "); each dynamic point is observed by exactly one camera (SPEC §3.1)");
    }
  }
  for (const auto& [id, vertex] : fe_.vertices) {
    if (vertex.label.role == Role::kStaticPoint) {
      Tracklet t;
      t.points.push_back(id);
      t.id = vertex.label.tracklet;
      tracklets_.push_back(t);
    } else if (vertex.label.role == Role::kDynamicPoint) {
      if (dynamic_observation_.count(id) == 0) {
        return Fail(vertex.line, "dynamic point " + std::to_string(id) +
                                     " has no EDGE_SE3_TRACKXYZ observing it");
      }
      if (previous.count(id) > 0) continue;  // not the head of its chain
      Tracklet t;
      t.dynamic = true;
      t.object = vertex.label.object;
      t.id = vertex.label.tracklet;
      for (VertexId p = id;;) {
        t.points.push_back(p);
        auto it = next.find(p);
        if (it == next.end()) break;
        const MotionEdge* e = it->second;
        // A tracklet is one object at consecutive frames (found by fuzzing: an unlabelled file
        // can chain edges whose frames or objects disagree).
        if (!t.edges.empty() && (e->frame != t.edges.back()->frame + 1 || e->object != t.object)) {
          return Fail(e->line, "EDGE_SE3_MOTION continues the tracklet of line " +
                                   std::to_string(t.edges.back()->line) + " (object " +
                                   std::to_string(t.object) + ", frame " +
                                   std::to_string(t.edges.back()->frame) + ") with object " +
                                   std::to_string(e->object) + " at frame " +
                                   std::to_string(e->frame) + "; expected the same object at frame " +
                                   std::to_string(t.edges.back()->frame + 1));
        }
        t.edges.push_back(e);
        t.object = e->object;
        p = e->curr;
      }
      tracklets_.push_back(t);
    }
  }
  size_t chained = 0;
  for (const Tracklet& t : tracklets_) chained += t.dynamic ? t.points.size() : 0;
  if (chained != dynamic_observation_.size()) {
    return Fail(0, "motion edges form a cycle among dynamic points (a tracklet must have a start)");
  }
  // Ids: from labels, else one sequence over all tracklets by first point id (SPEC §3.1).
  std::sort(tracklets_.begin(), tracklets_.end(),
            [](const Tracklet& a, const Tracklet& b) { return a.points[0] < b.points[0]; });
  if (!fe_.labelled) {
    for (size_t i = 0; i < tracklets_.size(); ++i) tracklets_[i].id = static_cast<int64_t>(i);
  }
  for (Tracklet& t : tracklets_) {
    for (const VertexId p : t.points) tracklet_of_point_[p] = &t;
  }
  return Status::Ok();
}

Status Builder::FindSegments() {
  for (const auto& [id, vertex] : fe_.vertices) {
    const Label& label = vertex.label;
    if (label.role == Role::kCamera) {
      if (auto [it, inserted] = camera_of_frame_.emplace(label.frame, id); !inserted) {
        return Fail(vertex.line, "cameras " + std::to_string(it->second) + " and " +
                                     std::to_string(id) + " are both at frame " +
                                     std::to_string(label.frame));
      }
    } else if (label.role == Role::kMotion) {
      if (auto [it, inserted] = motion_at_.emplace(std::pair{label.object, label.frame}, id);
          !inserted) {
        return Fail(vertex.line, "object " + std::to_string(label.object) +
                                     " has two motions at frame " + std::to_string(label.frame) +
                                     " (vertices " + std::to_string(it->second) + " and " +
                                     std::to_string(id) + ", SPEC §3.1)");
      }
    }
  }
  std::map<int64_t, std::set<int64_t>> joined_frames;  // object → frames k with an edge (k−1, k)
  for (const MotionEdge& e : fe_.Edges<MotionEdge>()) {
    const Label& motion = fe_.Find(e.motion)->label;
    if (motion.object != e.object || motion.frame != e.frame) {
      return Fail(e.line, "EDGE_SE3_MOTION of object " + std::to_string(e.object) + " at frame " +
                              std::to_string(e.frame) + " uses motion " +
                              std::to_string(e.motion) + " of object " +
                              std::to_string(motion.object) + " at frame " +
                              std::to_string(motion.frame));
    }
    joined_frames[e.object].insert(e.frame);
  }
  for (const auto& [object, frames] : joined_frames) {
    for (auto it = frames.begin(); it != frames.end();) {
      Segment segment;
      segment.object = object;
      segment.first = *it - 1;
      int64_t last = *it;
      while (++it != frames.end() && *it == last + 1) last = *it;
      segment.last = last;
      segment.kept = segment.frames() >= options_.min_object_frames;
      segments_.push_back(segment);
    }
  }
  for (Tracklet& t : tracklets_) {
    if (!t.dynamic || t.points.size() < 2) continue;
    const int64_t first_frame = fe_.Find(t.points[0])->label.frame;
    for (Segment& s : segments_) {
      if (s.object == t.object && s.first <= first_frame && first_frame <= s.last) {
        s.tracklets.push_back(&t);
        segment_of_[&t] = &s;
      }
    }
  }
  for (const Segment& s : segments_) {
    if (!s.kept) continue;
    for (int64_t k = s.first + 1; k <= s.last; ++k) kept_motions_.insert(motion_at_.at({s.object, k}));
  }
  return Status::Ok();
}

// A rigid motion needs three non-collinear points: a kept motion that fewer than three point
// pairs (motion edges) of its segment support is fixed only through the smoothing (and, oc_b/oc_c,
// kinematic) edges. Named per segment before solving; the segment is kept (SPEC §3.1 keeps it).
void Builder::WarnUnderdeterminedMotions() {
  if (report_ == nullptr) return;
  constexpr int64_t kPointsForARigidMotion = 3;
  for (const Segment& s : segments_) {
    if (!s.kept) continue;
    std::map<int64_t, int64_t> pairs_at;  // frame k → motion edges (k−1, k)
    for (const Tracklet* t : s.tracklets) {
      for (const MotionEdge* e : t->edges) ++pairs_at[e->frame];
    }
    int64_t weak = 0, first_weak = -1;
    for (int64_t k = s.first + 1; k <= s.last; ++k) {
      if (pairs_at[k] >= kPointsForARigidMotion) continue;
      if (weak++ == 0) first_weak = k;
    }
    if (weak == 0) continue;
    report_->warnings.push_back(
        "object " + std::to_string(s.object) + " frames " + std::to_string(s.first) + ".." +
        std::to_string(s.last) + ": " + Count(weak, "of its") + " " +
        Count(s.last - s.first, "motions") + " rest on fewer than 3 tracked points (first: frame " +
        std::to_string(first_weak) + ", " + Count(pairs_at[first_weak], "points") +
        "); the data cannot determine them, only smoothing and kinematic edges do");
  }
}

void Builder::ReportDrops() {
  std::set<int64_t> objects;
  int64_t dynamic_points = 0, dynamic_tracklets = 0, statics = 0, length_one = 0, kept_segments = 0;
  for (const Tracklet& t : tracklets_) {
    if (!t.dynamic) {
      ++statics;
      continue;
    }
    ++dynamic_tracklets;
    dynamic_points += static_cast<int64_t>(t.points.size());
    length_one += t.points.size() == 1;
    if (t.object >= 0) objects.insert(t.object);  // unknown for an unlabelled length-one point
  }
  for (const Segment& s : segments_) kept_segments += s.kept;
  Say("front-end " + name_ + (fe_.labelled ? " (labelled): " : " (unlabelled): ") +
      Count(static_cast<int64_t>(camera_of_frame_.size()), "cameras") + ", " +
      Count(statics, "static points") + ", " + Count(dynamic_points, "dynamic points in ") +
      Count(dynamic_tracklets, "tracklets") + ", " +
      Count(static_cast<int64_t>(motion_at_.size()), "motions") + ", " +
      Count(static_cast<int64_t>(objects.size()), "objects") + ", " +
      Count(kept_segments, "segments kept"));
  if (length_one > 0) {
    Say("dropped: " + Count(length_one, "tracklets of length one") + " (" +
        Count(length_one, "points") + ", " + Count(length_one, "point edges") +
        "): in no motion edge");
  }
  for (const Segment& s : segments_) {
    if (s.kept) continue;
    int64_t points = 0, edges = 0;
    for (const Tracklet* t : s.tracklets) {
      points += static_cast<int64_t>(t->points.size());
      edges += static_cast<int64_t>(t->edges.size());
    }
    int64_t smoothing = 0;
    for (const BetweenEdge& e : fe_.Edges<BetweenEdge>()) {
      const Label& a = fe_.Find(e.from)->label;
      smoothing += a.role == Role::kMotion && a.object == s.object && a.frame > s.first &&
                   a.frame <= s.last;
    }
    Say("dropped: object " + std::to_string(s.object) + " frames " + std::to_string(s.first) +
        ".." + std::to_string(s.last) + " (" + Count(s.frames(), "frames") + ") < " +
        std::to_string(options_.min_object_frames) + ": " +
        Count(static_cast<int64_t>(s.tracklets.size()), "tracklets") + ", " +
        Count(points, "points") + ", " + Count(s.last - s.first, "motions") + ", " +
        Count(points, "point edges") + ", " + Count(edges, "motion edges") + ", " +
        Count(smoothing, "smoothing edges"));
  }
  // Motions in no segment: a labelled file's motion vertex that no motion edge uses (an
  // unlabelled file has no such motion: its motions are known from their edges).
  int64_t motions_in_no_segment = 0;
  for (const auto& [key, id] : motion_at_) {
    bool in_segment = false;
    for (const Segment& s : segments_) {
      in_segment |= s.object == key.first && s.first < key.second && key.second <= s.last;
    }
    motions_in_no_segment += !in_segment;
  }
  if (motions_in_no_segment > 0) {
    Say("dropped: " + Count(motions_in_no_segment, "motions") + ": in no motion edge");
  }
  int64_t dropped_smoothing = 0, not_consecutive = 0;
  for (const BetweenEdge& e : fe_.Edges<BetweenEdge>()) {
    if (fe_.Find(e.from)->label.role != Role::kMotion) continue;
    if (kept_motions_.count(e.from) == 0 || kept_motions_.count(e.to) == 0) {
      ++dropped_smoothing;
    } else if (!KeptSmoothing(e)) {
      ++not_consecutive;
    }
  }
  if (dropped_smoothing > 0) {
    Say("dropped: " + Count(dropped_smoothing, "smoothing edges") +
        " in all (one of their motions is dropped)");
  }
  if (not_consecutive > 0) {
    Say("dropped: " + Count(not_consecutive, "smoothing edges") +
        ": they do not join motions of consecutive frames of one segment");
  }
  for (const Segment& s : segments_) {
    if (!s.kept) continue;
    Say("kept: object " + std::to_string(s.object) + " frames " + std::to_string(s.first) + ".." +
        std::to_string(s.last) + " (" + Count(s.frames(), "frames") + "), " +
        Count(static_cast<int64_t>(s.tracklets.size()), "tracklets"));
  }
}

Status Builder::Analyse() {
  if (Status s = FindTracklets(); !s.ok()) return s;
  if (Status s = FindSegments(); !s.ok()) return s;
  ReportDrops();
  WarnUnderdeterminedMotions();
  return Status::Ok();
}

// The least-squares rigid transform (Kabsch, with the determinant fix) mapping `from` onto
// `to`; false when fewer than 3 pairs or the second singular value is below 1e-9 × the first.
bool Align(const std::vector<Eigen::Vector3d>& from, const std::vector<Eigen::Vector3d>& to,
           Pose* pose) {
  if (from.size() < 3) return false;
  Eigen::Vector3d from_mean = Eigen::Vector3d::Zero(), to_mean = Eigen::Vector3d::Zero();
  for (size_t i = 0; i < from.size(); ++i) {
    from_mean += from[i];
    to_mean += to[i];
  }
  from_mean /= static_cast<double>(from.size());
  to_mean /= static_cast<double>(to.size());
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  for (size_t i = 0; i < from.size(); ++i) {
    covariance += (from[i] - from_mean) * (to[i] - to_mean).transpose();
  }
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(covariance, Eigen::ComputeFullU | Eigen::ComputeFullV);
  const Eigen::Vector3d singular = svd.singularValues();
  if (!(singular[1] >= 1e-9 * singular[0]) || singular[0] == 0) return false;
  Eigen::Matrix3d fix = Eigen::Matrix3d::Identity();
  fix(2, 2) = (svd.matrixV() * svd.matrixU().transpose()).determinant() < 0 ? -1 : 1;
  const Eigen::Matrix3d rotation = svd.matrixV() * fix * svd.matrixU().transpose();
  *pose = Pose::FromRotationTranslation(Eigen::Quaterniond(rotation).normalized(),
                                        to_mean - rotation * from_mean);
  return true;
}

bool Builder::PoseFromTruth(int64_t object, int64_t k, Pose* pose) const {
  const Pose* x_gt = gt_ != nullptr ? gt_->Camera(k) : nullptr;
  const Pose* l_gt = gt_ != nullptr ? gt_->Object(object, k) : nullptr;
  auto camera = camera_of_frame_.find(k);
  if (x_gt == nullptr || l_gt == nullptr || camera == camera_of_frame_.end()) return false;
  *pose = Compose(Compose(fe_.Find(camera->second)->pose(), Inverse(*x_gt)), *l_gt);
  return true;
}

Eigen::Vector3d Builder::MeasuredWorldPoint(VertexId point) const {
  const PointEdge& observation = *dynamic_observation_.at(point);
  return Transform(fe_.Find(observation.pose)->pose(), observation.measurement);
}

Pose Builder::MeasuredCentroid(int64_t object, int64_t k) const {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  int64_t n = 0;
  for (const auto& [id, vertex] : fe_.vertices) {  // by id: a reproducible sum
    const Label& label = vertex.label;
    if (label.role != Role::kDynamicPoint || label.object != object || label.frame != k) continue;
    sum += dynamic_observation_.at(id)->measurement;
    ++n;
  }
  const Pose camera = fe_.Find(camera_of_frame_.at(k))->pose();
  return Pose::FromRotationTranslation(Eigen::Quaterniond::Identity(),
                                       Transform(camera, sum / static_cast<double>(n)));
}

Pose Builder::Centroid(const Segment& segment, int64_t k) const {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  int64_t n = 0;
  for (const Tracklet* t : segment.tracklets) {
    for (const VertexId p : t->points) {
      if (fe_.Find(p)->label.frame != k) continue;
      sum += fe_.Find(p)->point();
      ++n;
    }
  }
  return Pose::FromRotationTranslation(Eigen::Quaterniond::Identity(),
                                       sum / static_cast<double>(n));
}

void Builder::InitialiseSegment(const Segment& segment, BuildState& state, Graph& out) const {
  const int64_t j = segment.object;
  // Dynamic points of this segment by frame: (tracklet, world point at that frame).
  std::map<int64_t, std::vector<std::pair<Tracklet*, VertexId>>> observed;
  for (Tracklet* t : segment.tracklets) {
    for (const VertexId p : t->points) observed[fe_.Find(p)->label.frame].emplace_back(t, p);
  }
  auto centroid = [&](int64_t k) { return Centroid(segment, k); };
  std::map<int64_t, Pose> poses;
  std::map<const Tracklet*, Eigen::Vector3d> object_points;
  auto from_truth = [&](int64_t k, Pose* pose) {
    const bool found = PoseFromTruth(j, k, pose);
    state.from_truth += found;
    return found;
  };
  auto chained = [&](int64_t k) {
    return Compose(MotionValue(motion_at_.at({j, k})), poses.at(k - 1));
  };
  auto aligned = [&](int64_t k) {
    std::vector<Eigen::Vector3d> from, to;
    for (const auto& [t, p] : observed[k]) {
      auto m = object_points.find(t);
      if (m == object_points.end()) continue;  // begins at k
      from.push_back(m->second);
      to.push_back(fe_.Find(p)->point());
    }
    Pose pose;
    return Align(from, to, &pose) ? pose : chained(k);
  };
  const ObjectInit rule = options_.object_init;
  for (int64_t k = segment.first; k <= segment.last; ++k) {
    Pose pose;
    const Pose* l_gt = gt_ != nullptr ? gt_->Object(j, k) : nullptr;
    if (k == segment.first && options_.dsc_object_centric_noise && l_gt != nullptr) {
      pose = Pose::FromRotationTranslation(Eigen::Quaterniond::Identity(), l_gt->translation());
      ++state.from_truth;
    } else if (rule == ObjectInit::kCentroid) {
      pose = centroid(k);
    } else if (k == segment.first) {
      if (!from_truth(k, &pose)) pose = centroid(k);
    } else if (rule == ObjectInit::kTruth) {
      if (!from_truth(k, &pose)) pose = chained(k);
    } else if (rule == ObjectInit::kAlign) {
      pose = aligned(k);
    } else {
      pose = chained(k);
    }
    poses[k] = pose;
    for (const auto& [t, p] : observed[k]) {
      if (t->points.front() == p) object_points[t] = Transform(Inverse(pose), fe_.Find(p)->point());
    }
  }
  // Ids in the order of SPEC §3.4: poses by frame, then points by first front-end point id.
  std::map<int64_t, VertexId> pose_ids;
  for (const auto& [k, pose] : poses) {
    Vertex vertex;
    vertex.type = VertexType::kPose;
    vertex.set_pose(pose);
    vertex.label = Label{Role::kObjectPose, j, k, -1};
    pose_ids[k] = state.next_id;
    out.vertices.emplace(state.next_id++, vertex);
  }
  std::vector<Tracklet*> ordered = segment.tracklets;
  std::sort(ordered.begin(), ordered.end(),
            [](const Tracklet* a, const Tracklet* b) { return a->points[0] < b->points[0]; });
  for (Tracklet* t : ordered) {
    Vertex vertex;
    vertex.type = VertexType::kPoint;
    vertex.value.fill(0);
    vertex.point() = object_points.at(t);
    vertex.label = Label{Role::kObjectPoint, j, -1, t->id};
    state.object_point[t] = state.next_id;
    out.vertices.emplace(state.next_id++, vertex);
  }
  // Prior on the first pose at its initial value (SPEC §3.3), information in [ω; ρ] order.
  PriorEdge prior;
  prior.pose = pose_ids.at(segment.first);
  prior.measurement = poses.at(segment.first);
  prior.information.setZero();
  prior.information.diagonal() << Eigen::Vector3d::Constant(
      1.0 / options_.object_prior_rotation_variance),
      Eigen::Vector3d::Constant(1.0 / options_.object_prior_translation_variance);
  out.Edges<PriorEdge>().push_back(prior);
  state.pose_ids[&segment] = pose_ids;
}

// SPEC §3.3: object poses per frame, object-frame points, their measurements, and the
// variant's motion and kinematic edges.
void Builder::AddObjectCentric(Graph& out, Formulation formulation, BuildState& state) const {
  for (const Segment& segment : segments_) {  // by object, then time (SPEC §3.4)
    if (segment.kept) InitialiseSegment(segment, state, out);
  }
  const Matrix6d kinematic_information =
      InformationFromSigmas(options_.kinematic_sigma, options_.kinematic_sigma);
  // SPEC §7 item 5: one information per point-edge kind (the first edge's), σ = 0.2 motions.
  const PointEdge* first_dynamic = nullptr;
  for (const PointEdge& e : fe_.Edges<PointEdge>()) {
    if (e.is_dynamic && first_dynamic == nullptr) first_dynamic = &e;
  }
  if (options_.dsc_object_centric_noise) {
    const PointEdge* first_static = nullptr;
    for (PointEdge& e : out.Edges<PointEdge>()) {
      if (first_static == nullptr) first_static = &e;
      e.information = first_static->information;
    }
  }
  for (const Segment& segment : segments_) {
    if (!segment.kept) continue;
    const std::map<int64_t, VertexId>& pose_ids = state.pose_ids.at(&segment);
    for (const Tracklet* t : segment.tracklets) {
      for (const VertexId p : t->points) {
        const PointEdge& observation = *dynamic_observation_.at(p);
        ObjectPointEdge e;
        e.camera = observation.pose;
        e.object_pose = pose_ids.at(fe_.Find(p)->label.frame);
        e.point = state.object_point.at(t);
        e.measurement = observation.measurement;
        e.information = options_.dsc_object_centric_noise ? first_dynamic->information
                                                           : observation.information;
        out.Edges<ObjectPointEdge>().push_back(e);
      }
      if (formulation == Formulation::kObjectCentricC) continue;
      for (const MotionEdge* m : t->edges) {
        ObjectMotionEdge e;
        e.pose_prev = pose_ids.at(m->frame - 1);
        e.pose_curr = pose_ids.at(m->frame);
        e.motion = m->motion;
        e.point = state.object_point.at(t);
        e.measurement = m->measurement;
        e.information = options_.dsc_object_centric_noise
                            ? Eigen::Matrix3d(Eigen::Matrix3d::Identity() / (0.2 * 0.2))
                            : m->information;
        out.Edges<ObjectMotionEdge>().push_back(e);
      }
    }
    if (formulation == Formulation::kObjectCentricA) continue;
    for (int64_t k = segment.first + 1; k <= segment.last; ++k) {
      KinematicEdge e;
      e.pose_prev = pose_ids.at(k - 1);
      e.pose_curr = pose_ids.at(k);
      e.motion = motion_at_.at({segment.object, k});
      e.information = kinematic_information;
      out.Edges<KinematicEdge>().push_back(e);
    }
  }
  int64_t poses = 0;
  for (const auto& [segment, ids] : state.pose_ids) poses += static_cast<int64_t>(ids.size());
  Say("object poses: " + std::to_string(poses) + ", " + std::to_string(state.from_truth) +
      " initialised from ground truth (--object-init " + ObjectInitName(options_.object_init) +
      ")");
}

// Shared by every formulation: cameras, static points, prior, odometry, static measurements;
// `with_motions`: the kept motions and the smoothing edges between them (SPEC §3.2, §3.3).
void Builder::AddShared(Graph& out, bool with_motions) const {
  for (const auto& [frame, id] : camera_of_frame_) AddVertex(out, id, fe_.Find(id)->label);
  for (const Tracklet& t : tracklets_) {
    if (!t.dynamic) AddVertex(out, t.points[0], Label{Role::kStaticPoint, -1, -1, t.id});
  }
  if (with_motions) {
    for (const VertexId id : kept_motions_) {
      AddVertex(out, id, fe_.Find(id)->label);
      out.vertices.at(id).set_pose(MotionValue(id));
    }
  }
  for (const PriorEdge& e : fe_.Edges<PriorEdge>()) out.Edges<PriorEdge>().push_back(e);
  for (const BetweenEdge& e : fe_.Edges<BetweenEdge>()) {
    const bool odometry = fe_.Find(e.from)->label.role == Role::kCamera;
    if (odometry || (with_motions && KeptSmoothing(e))) out.Edges<BetweenEdge>().push_back(e);
  }
  for (const PointEdge& e : fe_.Edges<PointEdge>()) {
    if (!e.is_dynamic) out.Edges<PointEdge>().push_back(e);
  }
}

// SPEC §3.2: the kept dynamic points, their measurements and motion edges.
void Builder::AddWorldCentric(Graph& out) const {
  for (const Tracklet& t : tracklets_) {
    if (!Kept(t)) continue;
    for (const VertexId p : t.points) {
      Label label = fe_.Find(p)->label;
      label.tracklet = t.id;
      AddVertex(out, p, label);
      out.Edges<PointEdge>().push_back(*dynamic_observation_.at(p));
    }
    for (const MotionEdge* e : t.edges) out.Edges<MotionEdge>().push_back(*e);
  }
}

// SPEC §3.6: per kept segment an embedded frame, hybrid motions, object points, their
// measurements and an anchor; the front end's smoothing edges re-expressed on three motions.
void Builder::AddHybrid(Graph& out, BuildState& state) const {
  std::map<int64_t, std::map<int64_t, VertexId>> motion_ids;  // object → frame → H^e_k
  for (const Segment& segment : segments_) {  // by object, then time (SPEC §3.4)
    if (segment.kept) AddHybridSegment(segment, state, out, &motion_ids[segment.object]);
  }
  // The embedded frame of `object`'s hybrid motion at frame k (the motion's label names it).
  auto embedded_at = [&](int64_t object, int64_t k) {
    return out.vertices.at(motion_ids.at(object).at(k)).label.embedded;
  };
  auto add_smoothing = [&](int64_t object, int64_t k, const Matrix6d& information) {
    const std::map<int64_t, VertexId>& ids = motion_ids.at(object);
    HybridSmoothingEdge edge;
    edge.motion_a = ids.at(k - 2);
    edge.motion_b = ids.at(k - 1);
    edge.motion_c = ids.at(k);
    edge.embedded = embedded_at(object, k);
    edge.information = information;
    out.Edges<HybridSmoothingEdge>().push_back(edge);
  };
  if (options_.dynosam_smoothing) {  // §3.6 --compat dynosam item 1
    for (const Segment& segment : segments_) {
      if (!segment.kept) continue;
      for (int64_t k = segment.first + 2; k <= segment.last; ++k) {
        add_smoothing(segment.object, k, InformationFromSigmas(0.01, 0.1));
      }
    }
  } else {
    int64_t not_identity = 0, first_line = 0;
    for (const BetweenEdge& e : fe_.Edges<BetweenEdge>()) {
      if (fe_.Find(e.from)->label.role != Role::kMotion || !KeptSmoothing(e)) continue;
      const Label& a = fe_.Find(e.from)->label;
      const int64_t k = std::max(a.frame, fe_.Find(e.to)->label.frame);
      const Pose embedded = out.vertices.at(embedded_at(a.object, k)).pose();
      add_smoothing(a.object, k, HybridSmoothingInformation(e, embedded));
      const Eigen::Quaterniond rotation = e.measurement.rotation();
      if (!e.measurement.translation().isZero(0) || !rotation.vec().isZero(0)) {
        if (not_identity++ == 0) first_line = e.line;
      }
    }
    if (not_identity > 0 && report_ != nullptr) {
      report_->warnings.push_back(
          name_ + ":" + std::to_string(first_line) + ": " + Count(not_identity, "smoothing edges") +
          " with a measurement other than the identity, which EDGE_SE3_HY_SMOOTHING has no field "
          "for (SPEC §3.6): ignored");
    }
  }
  int64_t kept = 0;
  for (const Segment& segment : segments_) kept += segment.kept;
  Say("embedded frames: " + std::to_string(kept) + ", " + std::to_string(state.from_truth) +
      " from ground truth (constant; --object-init " + ObjectInitName(options_.object_init) + ")");
}

// SPEC §3.6 `hybrid_smoothing_info`, in [ω; ρ] order.
Matrix6d Builder::HybridSmoothingInformation(const BetweenEdge& e, const Pose& embedded) const {
  switch (options_.hybrid_smoothing_info) {
    case HybridSmoothingInfo::kFrontEnd: return e.information;
    case HybridSmoothingInfo::kWorld: {
      const Matrix6d ad = Adjoint(embedded);
      return ad.transpose() * e.information * ad;
    }
    case HybridSmoothingInfo::kSigmas:
      return InformationFromSigmas(options_.hybrid_smoothing_sigma_rotation,
                                   options_.hybrid_smoothing_sigma_translation);
  }
  return e.information;
}

void Builder::AddHybridSegment(const Segment& segment, BuildState& state, Graph& out,
                               std::map<int64_t, VertexId>* motion_ids) const {
  const int64_t j = segment.object, k0 = segment.first;
  auto add_pose = [&](const Pose& pose, const Label& label) {
    Vertex vertex;
    vertex.type = VertexType::kPose;
    vertex.set_pose(pose);
    vertex.label = label;
    out.vertices.emplace(state.next_id, vertex);
    return state.next_id++;
  };
  // L_e: §3.3's first-frame value (ground truth, else the centroid), or DynoSAM's.
  Pose l_e;
  if (options_.dynosam_embedded_frame) {
    l_e = MeasuredCentroid(j, k0);
  } else if (options_.object_init != ObjectInit::kCentroid && PoseFromTruth(j, k0, &l_e)) {
    ++state.from_truth;
  } else {
    l_e = Centroid(segment, k0);
  }
  const VertexId embedded = add_pose(l_e, Label{Role::kEmbeddedFrame, j, k0});
  std::map<int64_t, Pose> h;  // H^e_k = H_k · H^e_{k−1}, H^e_{k0} = I
  for (int64_t k = k0; k <= segment.last; ++k) {
    h[k] = k == k0 ? Pose::Identity() : Compose(MotionValue(motion_at_.at({j, k})), h.at(k - 1));
    Label label{Role::kHybridMotion, j, k};
    label.embedded = embedded;
    (*motion_ids)[k] = add_pose(h[k], label);
  }
  std::vector<Tracklet*> ordered = segment.tracklets;
  std::sort(ordered.begin(), ordered.end(),
            [](const Tracklet* a, const Tracklet* b) { return a->points[0] < b->points[0]; });
  for (Tracklet* t : ordered) {  // m = L_e⁻¹ · (H^e_kf)⁻¹ · m_W,kf
    const Vertex& first = *fe_.Find(t->points[0]);
    const Eigen::Vector3d m_w = options_.dynosam_points_from_measurements
                                    ? MeasuredWorldPoint(t->points[0])
                                    : Eigen::Vector3d(first.point());
    Vertex vertex;
    vertex.type = VertexType::kPoint;
    vertex.value.fill(0);
    vertex.point() = Transform(Inverse(Compose(h.at(first.label.frame), l_e)), m_w);
    vertex.label = Label{Role::kObjectPoint, j, -1, t->id};
    const VertexId point = state.next_id++;
    out.vertices.emplace(point, vertex);
    for (const VertexId p : t->points) {
      const PointEdge& observation = *dynamic_observation_.at(p);
      HybridPointEdge e;
      e.camera = observation.pose;
      e.motion = motion_ids->at(fe_.Find(p)->label.frame);
      e.embedded = embedded;
      e.point = point;
      e.measurement = observation.measurement;
      e.information = observation.information;
      out.Edges<HybridPointEdge>().push_back(e);
    }
  }
  PriorEdge anchor;  // H^e_{k0} at I (σ = hybrid_anchor_sigma)
  anchor.pose = motion_ids->at(k0);
  anchor.information =
      InformationFromSigmas(options_.hybrid_anchor_sigma, options_.hybrid_anchor_sigma);
  out.Edges<PriorEdge>().push_back(anchor);
}

Expected<Graph> Builder::Build(Formulation formulation) const {
  Graph out;
  out.formulation = FormulationName(formulation);
  out.labelled = true;
  BuildState state;  // new vertices get ids from max_id + 1 (SPEC §3.4)
  state.next_id = fe_.vertices.empty() ? 0 : fe_.vertices.rbegin()->first + 1;
  AddShared(out, formulation != Formulation::kHybrid);
  switch (formulation) {
    case Formulation::kWorldCentric: AddWorldCentric(out); break;
    case Formulation::kObjectCentricA:
    case Formulation::kObjectCentricB:
    case Formulation::kObjectCentricC: AddObjectCentric(out, formulation, state); break;
    case Formulation::kHybrid: AddHybrid(out, state); break;
  }
  // The built graph must read back as a consistent labelled file (SPEC §1.4).
  if (Status s = AssignRoles(out, name_); !s.ok()) return s.error();

  std::string variables, edges;
  int64_t total_variables = 0, total_edges = 0;
  for (const Role role : kAllRoles) {
    int64_t n = 0;
    for (const auto& [id, vertex] : out.vertices) n += vertex.label.role == role;
    const bool constant = InfoOf(role)->constant;  // listed, not a variable (SPEC §3.6)
    if (n > 0) {
      variables += std::string(variables.empty() ? "" : ", ") + RoleName(role) + " " +
                   std::to_string(n) + (constant ? " constant" : "");
    }
    if (!constant) total_variables += n;
  }
  const auto counts = CountEdgesByKind(out);
  for (const EdgeKind kind : kAllEdgeKinds) {
    const int64_t n = counts[static_cast<int>(kind)];
    if (n > 0) edges += std::string(edges.empty() ? "" : ", ") + EdgeKindName(kind) + " " + std::to_string(n);
    total_edges += n;
  }
  Say(std::string(FormulationName(formulation)) + ": " + std::to_string(total_variables) +
      " variables (" + variables + ")");
  Say(std::string(FormulationName(formulation)) + ": " + std::to_string(total_edges) + " edges (" +
      edges + ")");
  return out;
}

}  // namespace

const std::vector<FormulationInfo>& Formulations() {
  using K = EdgeKind;
  // Dogleg lost to LM on object-centric graphs: on simulated KITTI 0002 oc_b it ended in a basin
  // twice the cost LM reaches (scripts/demo), and on the whole of 0006 oc_a its trust region
  // shrank until the function tolerance stopped it 1.1e-5 above LM's optimum
  // (docs/CONVERGENCE.md). hy: see docs/SOLVER.md.
  static const std::vector<FormulationInfo> table = {
      {Formulation::kWorldCentric, "wc", "world-centric (paper Fig. 2)", false,
       {K::kSmoothing, K::kDynamicPoint, K::kMotion}, {K::kMotion}, false},
      {Formulation::kObjectCentricA, "oc_a", "object-centric (a), no kinematic edge", true,
       {K::kSmoothing, K::kObjectPoint, K::kObjectMotion, K::kObjectPrior}, {K::kObjectMotion},
       true},
      {Formulation::kObjectCentricB, "oc_b", "object-centric (b), motion and kinematic edges", true,
       {K::kSmoothing, K::kObjectPoint, K::kObjectMotion, K::kKinematic, K::kObjectPrior},
       {K::kObjectMotion, K::kKinematic}, true},
      {Formulation::kObjectCentricC, "oc_c", "object-centric (c), kinematic edge only", true,
       {K::kSmoothing, K::kObjectPoint, K::kKinematic, K::kObjectPrior}, {K::kKinematic}, true},
      {Formulation::kHybrid, "hy", "hybrid (DynoSAM): embedded frames, world-frame motions", true,
       {K::kHybridPoint, K::kHybridSmoothing, K::kObjectPrior}, {K::kHybridPoint}, false},
  };
  return table;
}

const FormulationInfo& InfoOf(Formulation formulation) {
  for (const FormulationInfo& info : Formulations()) {
    if (info.formulation == formulation) return info;
  }
  return Formulations().front();  // unreachable: every enumerator has a row
}

const char* FormulationName(Formulation formulation) { return InfoOf(formulation).name; }

bool ParseFormulation(const std::string& text, Formulation* formulation) {
  for (const FormulationInfo& info : Formulations()) {
    if (text == info.name) {
      *formulation = info.formulation;
      return true;
    }
  }
  return false;
}

std::string FormulationNames(const char* separator) {
  std::string names;
  for (const FormulationInfo& info : Formulations()) {
    names += (names.empty() ? "" : separator) + std::string(info.name);
  }
  return names;
}

std::optional<Formulation> FormulationOfGraph(const Graph& graph, std::string* source) {
  if (source != nullptr) *source = graph.formulation ? "label" : "inferred";
  Formulation labelled;
  if (graph.formulation) {
    if (ParseFormulation(*graph.formulation, &labelled)) return labelled;
    return std::nullopt;  // "frontend"
  }
  const auto counts = CountEdgesByKind(graph);
  auto present = [&](EdgeKind kind) { return counts[static_cast<int>(kind)] > 0; };
  for (const FormulationInfo& info : Formulations()) {
    const bool identified =
        std::all_of(info.identified_by.begin(), info.identified_by.end(), present);
    const bool covered = std::all_of(kAllEdgeKinds.begin(), kAllEdgeKinds.end(), [&](EdgeKind k) {
      return !present(k) || IsSharedEdgeKind(k) ||
             std::find(info.emits.begin(), info.emits.end(), k) != info.emits.end();
    });
    if (identified && covered) return info.formulation;
  }
  return std::nullopt;
}

std::string FormulationLabelOf(const Graph& graph, std::string* source) {
  if (const std::optional<Formulation> f = FormulationOfGraph(graph, source)) {
    return FormulationName(*f);
  }
  if (graph.formulation) return *graph.formulation;
  const auto counts = CountEdgesByKind(graph);
  for (const EdgeKind kind : kAllEdgeKinds) {
    if (!IsSharedEdgeKind(kind) && counts[static_cast<int>(kind)] > 0) return "mixed";
  }
  return counts[static_cast<int>(EdgeKind::kPoint)] > 0 ? "static" : "pose_graph";
}

const char* ObjectInitName(ObjectInit rule) {
  switch (rule) {
    case ObjectInit::kMotion: return "motion";
    case ObjectInit::kAlign: return "align";
    case ObjectInit::kTruth: return "truth";
    case ObjectInit::kCentroid: return "centroid";
  }
  return "?";
}

bool ParseObjectInit(const std::string& text, ObjectInit* rule) {
  for (const ObjectInit r : kAllObjectInits) {
    if (text == ObjectInitName(r)) {
      *rule = r;
      return true;
    }
  }
  return false;
}

const char* MotionInitName(MotionInit init) {
  return init == MotionInit::kIdentity ? "identity" : "frontend";
}

std::string HybridSmoothingInfoText(const BuildOptions& options) {
  switch (options.hybrid_smoothing_info) {
    case HybridSmoothingInfo::kFrontEnd: return "frontend";
    case HybridSmoothingInfo::kWorld: return "world";
    case HybridSmoothingInfo::kSigmas: break;
  }
  return RealText(options.hybrid_smoothing_sigma_rotation) + "," +
         RealText(options.hybrid_smoothing_sigma_translation);
}

std::optional<std::string> ParseHybridSmoothingInfo(const std::string& text,
                                                    BuildOptions* options) {
  if (text == "frontend" || text == "world") {
    options->hybrid_smoothing_info =
        text == "world" ? HybridSmoothingInfo::kWorld : HybridSmoothingInfo::kFrontEnd;
    return std::nullopt;
  }
  const size_t comma = text.find(',');
  double sigmas[2];
  const std::string parts[2] = {text.substr(0, comma),
                                comma == std::string::npos ? "" : text.substr(comma + 1)};
  for (int i = 0; i < 2; ++i) {
    if (ParseReal(parts[i], 0, 1e300, &sigmas[i]) || !(sigmas[i] > 0)) {
      return "'" + text + "' is not frontend, world or two positive sigmas SIGMA_R,SIGMA_T";
    }
  }
  options->hybrid_smoothing_info = HybridSmoothingInfo::kSigmas;
  options->hybrid_smoothing_sigma_rotation = sigmas[0];
  options->hybrid_smoothing_sigma_translation = sigmas[1];
  return std::nullopt;
}

std::string BuildReport::ToText() const {
  std::string text;
  for (const std::string& line : lines) text += line + "\n";
  for (const std::string& warning : warnings) text += "warning: " + warning + "\n";
  return text;
}

Expected<Graph> BuildFormulation(const Graph& front_end, Formulation formulation,
                                 const BuildOptions& options, const GroundTruth* ground_truth,
                                 BuildReport* report, const std::string& name) {
  if (options.min_object_frames < 2) {
    return Error{"", 0, "min_object_frames must be at least 2 (a segment needs one motion)"};
  }
  if (!(options.kinematic_sigma > 0) || !(options.object_prior_rotation_variance > 0) ||
      !(options.object_prior_translation_variance > 0)) {
    return Error{"", 0, "kinematic sigma and object prior variances must be positive"};
  }
  Builder builder(front_end, options, ground_truth, report, name);
  if (Status s = builder.Analyse(); !s.ok()) return s.error();
  return builder.Build(formulation);
}

bool IsObjectCentric(Formulation formulation) {
  return formulation == Formulation::kObjectCentricA ||
         formulation == Formulation::kObjectCentricB ||
         formulation == Formulation::kObjectCentricC;
}

namespace {

bool SameLabel(const Label& a, const Label& b) {
  return a.role == b.role && a.object == b.object && a.frame == b.frame &&
         a.tracklet == b.tracklet;
}

// Empty when `graph` has exactly the vertex ids and labels of `expected`; else the first
// vertex that differs.
std::optional<std::string> FirstDifferentVertex(const Graph& graph, const Graph& expected) {
  auto a = graph.vertices.begin(), b = expected.vertices.begin();
  for (; a != graph.vertices.end() && b != expected.vertices.end(); ++a, ++b) {
    if (a->first != b->first || !SameLabel(a->second.label, b->second.label)) break;
  }
  if (a == graph.vertices.end() && b == expected.vertices.end()) return std::nullopt;
  const VertexId id = b != expected.vertices.end() ? b->first : a->first;
  return "vertex " + std::to_string(id);
}

}  // namespace

Status StartFromWorldCentric(const Graph& front_end, const Graph& world_centric,
                             const BuildOptions& options, const GroundTruth* ground_truth,
                             Graph* built, const std::string& start_name) {
  const std::optional<Formulation> formulation = FormulationOfGraph(*built);
  if (!formulation || !IsObjectCentric(*formulation)) {
    return Error{"", 0, "a start from wc applies to oc_a, oc_b and oc_c, not " +
                            FormulationLabelOf(*built)};
  }
  BuildOptions from_estimates = options;
  from_estimates.motion_init = MotionInit::kFrontEnd;  // the motions are wc's solved ones
  Expected<Graph> expected = BuildFormulation(front_end, Formulation::kWorldCentric,
                                              from_estimates, ground_truth, nullptr);
  if (!expected.ok()) return expected.error();
  if (std::optional<std::string> differs = FirstDifferentVertex(world_centric, *expected)) {
    return Error{start_name, 0, "not the wc graph of this front end with these build options (" +
                                    *differs + " differs or is missing; it is " +
                                    FormulationLabelOf(world_centric) + ")"};
  }
  Graph estimates = front_end;
  for (const auto& [id, solved] : world_centric.vertices) {
    estimates.vertices.at(id).value = solved.value;  // every wc vertex is a front-end vertex
  }
  Expected<Graph> start =
      BuildFormulation(estimates, *formulation, from_estimates, ground_truth, nullptr);
  if (!start.ok()) return start.error();
  if (std::optional<std::string> differs = FirstDifferentVertex(*built, *start)) {
    return Error{"", 0, "the graph to start is not " + std::string(FormulationName(*formulation)) +
                            " of this front end with these build options (" + *differs + ")"};
  }
  for (auto& [id, vertex] : built->vertices) vertex.value = start->vertices.at(id).value;
  return Status::Ok();
}

}  // namespace dynslam
