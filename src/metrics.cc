#include "dynslam/metrics.h"

#include <cmath>
#include <vector>

#include "dynslam/se3.h"  // header-only, Eigen only
#include "src/json_io.h"

namespace dynslam {
namespace {

constexpr double kDegreesPerRadian = 180.0 / M_PI;

struct Accumulator {
  std::map<int64_t, std::vector<std::pair<double, double>>> per_object;

  std::pair<double, double> Add(int64_t object, const Pose& estimate, const Pose& truth) {
    per_object[object].push_back(PoseError(estimate, truth));
    return per_object[object].back();
  }

  ObjectErrors Finish() const {
    ObjectErrors errors;
    for (const auto& [object, samples] : per_object) {
      ErrorMean mean;
      mean.count = static_cast<int64_t>(samples.size());
      for (const auto& [rot, trans] : samples) {
        mean.mean_rot_deg += rot / mean.count;
        mean.mean_trans_m += trans / mean.count;
      }
      errors.per_object[object] = mean;
      errors.count += mean.count;
    }
    errors.objects = static_cast<int64_t>(errors.per_object.size());
    for (const auto& [object, mean] : errors.per_object) {
      errors.mean_rot_deg += mean.mean_rot_deg / errors.objects;
      errors.mean_trans_m += mean.mean_trans_m / errors.objects;
    }
    return errors;
  }
};

// Variables of one role by (object, frame).
std::map<std::pair<int64_t, int64_t>, Pose> ByObjectAndFrame(const Graph& graph, Role role) {
  std::map<std::pair<int64_t, int64_t>, Pose> poses;
  for (const auto& [id, vertex] : graph.vertices) {
    if (vertex.label.role == role) poses[{vertex.label.object, vertex.label.frame}] = vertex.pose();
  }
  return poses;
}

// Object-centric or hybrid: the graph carries its object poses (SPEC §5).
bool CarriesObjectPoses(const Graph& graph) {
  for (const auto& [id, vertex] : graph.vertices) {
    const Role role = vertex.label.role;
    if (role == Role::kObjectPose || role == Role::kHybridMotion) return true;
  }
  return false;
}

// Hybrid motions by (object, frame), each with the id of its embedded frame.
struct HybridMotion {
  Pose motion;
  VertexId embedded;
};
std::map<std::pair<int64_t, int64_t>, HybridMotion> HybridMotions(const Graph& graph) {
  std::map<std::pair<int64_t, int64_t>, HybridMotion> motions;
  for (const auto& [id, vertex] : graph.vertices) {
    const Label& label = vertex.label;
    if (label.role == Role::kHybridMotion) {
      motions[{label.object, label.frame}] = {vertex.pose(), label.embedded};
    }
  }
  return motions;
}

// The object poses a graph carries: L variables, or hybrid L_k = H^e_k · L_e.
std::map<std::pair<int64_t, int64_t>, Pose> CarriedObjectPoses(const Graph& graph) {
  std::map<std::pair<int64_t, int64_t>, Pose> poses = ByObjectAndFrame(graph, Role::kObjectPose);
  for (const auto& [key, h] : HybridMotions(graph)) {
    if (const Vertex* embedded = graph.Find(h.embedded)) {
      poses[key] = Compose(h.motion, embedded->pose());
    }
  }
  return poses;
}

// World-centric: L_{k0} = L^gt_{k0} at the start of each run of motions at consecutive frames,
// then L_k = H_k · L_{k−1} (SPEC §5, paper §V-E).
std::map<std::pair<int64_t, int64_t>, Pose> ComposeFromMotions(
    const std::map<std::pair<int64_t, int64_t>, Pose>& motions, const GroundTruth& gt,
    int64_t* segments_without_start) {
  std::map<std::pair<int64_t, int64_t>, Pose> poses;
  *segments_without_start = 0;
  bool skipping = false;
  for (auto it = motions.begin(); it != motions.end(); ++it) {
    const auto [object, frame] = it->first;
    const bool starts_segment = it == motions.begin() || std::prev(it)->first.first != object ||
                                std::prev(it)->first.second != frame - 1;
    if (starts_segment) {
      const Pose* start = gt.Object(object, frame - 1);
      skipping = start == nullptr;
      if (skipping) {
        ++*segments_without_start;
        continue;
      }
      poses[{object, frame - 1}] = *start;
    }
    if (skipping) continue;
    poses[{object, frame}] = Compose(it->second, poses.at({object, frame - 1}));
  }
  return poses;
}

}  // namespace

std::pair<double, double> PoseError(const Pose& estimate, const Pose& truth) {
  const Pose error = Compose(Inverse(estimate), truth);
  const Eigen::Quaterniond q = error.rotation();
  const double angle = 2.0 * std::atan2(q.vec().norm(), std::abs(q.w()));
  return {angle * kDegreesPerRadian, error.translation().norm()};
}

std::map<std::pair<int64_t, int64_t>, Pose> EstimatedObjectPoses(const Graph& solved,
                                                                 const GroundTruth& ground_truth) {
  if (CarriesObjectPoses(solved)) return CarriedObjectPoses(solved);
  int64_t skipped = 0;
  return ComposeFromMotions(EstimatedMotions(solved), ground_truth, &skipped);
}

std::map<std::pair<int64_t, int64_t>, Pose> EstimatedMotions(const Graph& solved) {
  std::map<std::pair<int64_t, int64_t>, Pose> motions = ByObjectAndFrame(solved, Role::kMotion);
  const auto hybrid = HybridMotions(solved);
  for (auto it = hybrid.begin(); it != hybrid.end(); ++it) {
    const auto [object, frame] = it->first;
    auto previous = hybrid.find({object, frame - 1});
    if (previous == hybrid.end() || previous->second.embedded != it->second.embedded) continue;
    motions[it->first] = Compose(it->second.motion, Inverse(previous->second.motion));
  }
  return motions;
}

Metrics ComputeMetrics(const Graph& solved, const GroundTruth& gt) {
  Metrics metrics;
  metrics.object_centric = CarriesObjectPoses(solved);

  std::map<int64_t, Pose> cameras;
  for (const auto& [id, vertex] : solved.vertices) {
    if (vertex.label.role == Role::kCamera) cameras[vertex.label.frame] = vertex.pose();
  }
  for (const auto& [frame, pose] : cameras) {
    auto previous = cameras.find(frame - 1);
    const Pose* truth = gt.Camera(frame);
    const Pose* truth_previous = gt.Camera(frame - 1);
    if (previous == cameras.end() || truth == nullptr || truth_previous == nullptr) continue;
    const auto [rot, trans] = PoseError(Compose(Inverse(previous->second), pose),
                                        Compose(Inverse(*truth_previous), *truth));
    metrics.per_frame.push_back({"camera", -1, frame, rot, trans});
    ++metrics.camera.count;
    metrics.camera.mean_rot_deg += rot;
    metrics.camera.mean_trans_m += trans;
  }
  if (metrics.camera.count > 0) {
    metrics.camera.mean_rot_deg /= metrics.camera.count;
    metrics.camera.mean_trans_m /= metrics.camera.count;
  }

  const auto motions = EstimatedMotions(solved);
  Accumulator motion_errors;
  for (const auto& [key, motion] : motions) {
    const auto [object, frame] = key;
    const Pose* truth = gt.Object(object, frame);
    const Pose* truth_previous = gt.Object(object, frame - 1);
    if (truth == nullptr || truth_previous == nullptr) continue;
    const auto [rot, trans] =
        motion_errors.Add(object, motion, Compose(*truth, Inverse(*truth_previous)));
    metrics.per_frame.push_back({"object_motion", object, frame, rot, trans});
  }
  metrics.object_motion = motion_errors.Finish();

  const auto poses =
      metrics.object_centric
          ? CarriedObjectPoses(solved)
          : ComposeFromMotions(motions, gt, &metrics.segments_without_ground_truth_start);
  Accumulator pose_errors;
  for (const auto& [key, motion] : motions) {
    const auto [object, frame] = key;
    auto current = poses.find({object, frame});
    auto previous = poses.find({object, frame - 1});
    const Pose* truth = gt.Object(object, frame);
    const Pose* truth_previous = gt.Object(object, frame - 1);
    if (current == poses.end() || previous == poses.end() || truth == nullptr ||
        truth_previous == nullptr) {
      continue;
    }
    const auto [rot, trans] = pose_errors.Add(object, Compose(Inverse(previous->second), current->second),
                                              Compose(Inverse(*truth_previous), *truth));
    metrics.per_frame.push_back({"object_pose", object, frame, rot, trans});
  }
  metrics.object_pose = pose_errors.Finish();
  return metrics;
}

std::string MetricsJson(const Metrics& metrics) { return DumpJson(MetricsToJson(metrics)); }

}  // namespace dynslam
