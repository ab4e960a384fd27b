// Trajectory metrics of a solved graph against ground truth (SPEC §5; paper Tables I–III).
//
// Pose error of an estimate M against M_gt: E = M⁻¹ · M_gt, E_t = ‖t(E)‖ in metres,
// E_r = angle(R(E)) in degrees. Means are arithmetic. Graph layer: no Ceres.
#ifndef DYNSLAM_METRICS_H_
#define DYNSLAM_METRICS_H_

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "dynslam/graph.h"
#include "dynslam/ground_truth.h"

namespace dynslam {

struct ErrorMean {
  int64_t count = 0;  // pairs or motions averaged
  double mean_rot_deg = 0;
  double mean_trans_m = 0;
};

struct ObjectErrors {
  int64_t count = 0;    // motions (object_motion) or pairs (object_pose), all objects
  int64_t objects = 0;  // objects with at least one
  double mean_rot_deg = 0;   // mean over objects of the per-object means
  double mean_trans_m = 0;
  std::map<int64_t, ErrorMean> per_object;
};

// One frame's error (errors.csv, SPEC §4): the camera's relative pose error from frame − 1 to
// `frame` (object −1), an object's motion error into `frame`, or its relative pose error there.
struct FrameError {
  const char* quantity = "camera";  // "camera", "object_motion" or "object_pose"
  int64_t object = -1;
  int64_t frame = 0;
  double rot_deg = 0;
  double trans_m = 0;
};

struct Metrics {
  bool object_centric = false;
  ErrorMean camera;            // relative pose error of consecutive cameras (Table I)
  ObjectErrors object_motion;  // H_k against L^gt_k · (L^gt_{k−1})⁻¹ (Table II)
  ObjectErrors object_pose;    // relative error of L_{k−1}⁻¹ · L_k (Table III)
  // World-centric: segments whose first pose has no ground truth (skipped, SPEC §5).
  int64_t segments_without_ground_truth_start = 0;
  std::vector<FrameError> per_frame;  // every error the means above average, by quantity
};

// E_r in degrees and E_t in metres of `estimate` against `truth` (SPEC §5).
std::pair<double, double> PoseError(const Pose& estimate, const Pose& truth);

// Needs a labelled graph (roles, objects and frames). World-centric object poses are composed
// from the motions, starting each segment at its ground-truth pose (paper §V-E).
Metrics ComputeMetrics(const Graph& solved, const GroundTruth& ground_truth);

// World-centric object poses as composed for the metrics, by (object, frame); object-centric
// graphs return their L variables, hybrid graphs H^e_k · L_e (SPEC §3.6). Used for
// object_poses.csv (SPEC §4).
std::map<std::pair<int64_t, int64_t>, Pose> EstimatedObjectPoses(const Graph& solved,
                                                                 const GroundTruth& ground_truth);

// Frame-to-frame object motions H^W_{k−1,k} by (object, frame k): the motion variables, or for
// a hybrid graph H^e_k · (H^e_{k−1})⁻¹ within each segment (SPEC §3.6). motions.csv (SPEC §4).
std::map<std::pair<int64_t, int64_t>, Pose> EstimatedMotions(const Graph& solved);

// The metrics as the reference set's metrics.json writes them (SPEC §5), as JSON text.
std::string MetricsJson(const Metrics& metrics);

}  // namespace dynslam

#endif  // DYNSLAM_METRICS_H_
