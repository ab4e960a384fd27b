// A scene simulator that plays the role of a visual front end (docs/SIMULATOR.md).
//
// A `Scene` holds true trajectories: camera poses X_k and, per object, its poses L_k (SPEC §0:
// local → world; the world is the first camera of the range, SPEC §2). It comes from KITTI
// Tracking ground truth (`MakeKittiScene`, real camera and object motion) or from a small
// hand-made layout (`MakeSyntheticScene`). `Simulate` then makes what a front end would output:
//
// - static points on plausible surfaces (a ground plane and building façades beside the road,
//   the boxes of parked objects), dynamic points fixed on the boxes of moving objects (object
//   frame), each tracked while it is in the image, in range and facing the camera, with a
//   break probability per frame (a new detection is a new point, a new tracklet);
// - stereo-like point measurements: the covariance of each observation is propagated from pixel
//   and disparity noise (σ_x ≈ σ_px·z/f, σ_z ≈ σ_d·z²/(f·b)), the noise is drawn from it and the
//   edge's information is its inverse;
// - noisy odometry, camera initial values chained from it (they drift), a prior on the first
//   camera; point initial values = initial camera pose × measurement; motions
//   H^W_{k−1,k} = L_k·L_{k−1}⁻¹ with noisy initial values, ternary motion edges (z = 0) and
//   smoothing edges (Z = I) — SPEC §1.2 with the released code's extra fields, §1.4 labels;
// - optionally a fraction of gross point errors (outliers).
//
// Deterministic for a seed: std::mt19937_64 with our own uniform and Box–Muller transforms. The
// scene layout (detections, breaks) and the noise come from separate streams, so `noise = false`
// gives the same points and edges with exact measurements.
//
// Graph layer: no Ceres.
#ifndef DYNSLAM_SIMULATE_H_
#define DYNSLAM_SIMULATE_H_

#include <array>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "dynslam/graph.h"
#include "dynslam/ground_truth.h"
#include "dynslam/kitti.h"
#include "dynslam/options.h"
#include "dynslam/pose.h"
#include "dynslam/status.h"

namespace dynslam {

struct SimulateOptions {
  // Frames [first_frame, last_frame) of the sequence; last_frame < 0: to its end. Synthetic
  // scenes have `synthetic_frames` frames unless last_frame is given.
  int64_t first_frame = 0;
  int64_t last_frame = -1;
  uint64_t seed = 0;
  bool synthetic = false;
  int64_t synthetic_frames = 30;

  // Noise. `noise = false` draws none (informations are unchanged): measurements are exact and
  // initial values equal ground truth.
  bool noise = true;
  double pixel_sigma = 0.5;         // px, image coordinates u, v
  double disparity_sigma = 0.5;     // px
  double point_sigma_floor = 0.005; // m, added in quadrature on each axis
  double odometry_rotation_sigma = 0.002;     // rad per frame, each axis
  double odometry_translation_sigma = 0.02;   // m per frame, each axis
  double motion_init_rotation_sigma = 0.01;   // rad: initial H = H_true · Exp(ξ)
  double motion_init_translation_sigma = 0.1; // m
  double prior_sigma = 0.001;                 // rad and m: prior on the first camera
  double motion_sigma = 0.1;                  // m: ternary motion edge, isotropic
  double smoothing_rotation_sigma = 0.01;     // rad: smoothing edge
  double smoothing_translation_sigma = 0.1;   // m
  // Off: the prior, motion and smoothing edges carry their information but no noise (the prior
  // at the true first pose, z = 0, Z = I: models, not measurements). On (with `noise`): each of
  // them is a measurement of the truth drawn from its information — the prior Z = X_0·Exp(ξ),
  // the motion edge's z ~ N(0, σ²I), the smoothing Z = H_{k−1}⁻¹·H_k·Exp(ξ) — from a stream of
  // its own, so every other draw is the same as with it off (docs/SIMULATOR.md).
  bool noise_every_edge = false;
  // Outliers: this fraction of point observations gets a gross error, a random direction of
  // length uniform in [outlier_min, outlier_max] metres (the edge's information is unchanged).
  double outlier_fraction = 0.0;
  double outlier_min = 1.0;
  double outlier_max = 5.0;

  // Tracking.
  int64_t static_points_per_frame = 150;   // tracked static points kept per frame (target)
  int64_t dynamic_points_per_object = 20;  // tracked points kept per visible moving object
  double static_break_probability = 0.05;  // per frame and track
  double dynamic_break_probability = 0.05;
  double min_depth = 1.0;   // m, camera z
  double max_depth = 40.0;  // m, camera z (stereo range)
  int64_t image_width = 1242;
  int64_t image_height = 375;

  // Scenery (camera-local at detection time; camera y points down).
  double camera_height = 1.65;     // m above the ground (KITTI's camera height)
  double facade_distance = 9.0;    // m from the camera to each side's façade
  double facade_height = 12.0;     // m above the ground

  // Moving vs parked (KITTI): moving when the object's world-frame centre spans at least
  // `moving_min_extent` metres over its track in the range AND its speed over
  // `speed_window_frames` frames reaches `moving_min_speed` somewhere. Both are robust to
  // label jitter (a few decimetres). Others are parked: static scenery.
  double moving_min_extent = 2.0;   // m
  double moving_min_speed = 1.0;    // m/s
  int64_t speed_window_frames = 10;
  // Label types simulated as rigid boxes; others (Pedestrian, Person_sitting: not rigid;
  // DontCare) are ignored. Cyclist and Misc are in because the paper's tables include them
  // (sequence 00 object 1 is a cyclist, 20 object 32 a Misc).
  std::vector<std::string> object_types = {"Car", "Van", "Truck", "Tram", "Cyclist", "Misc"};
};

// The option table of SimulateOptions (options.h): `dynslam simulate`'s flags and
// `dynslam.simulate`'s keywords. Groups "scene", "noise", "density and visibility". `frames`
// ("A:B", B exclusive; "A:" and ":B" too) sets first_frame and last_frame.
const OptionTable<SimulateOptions>& SimulateOptionTable();

// Pinhole of the image the front end sees (KITTI: P2, colour camera 2) and the stereo baseline.
struct CameraModel {
  Eigen::Matrix<double, 3, 4> projection;  // rectified camera 0 point → image (P2)
  double baseline = 0.54;                  // m
  double focal() const { return projection(0, 0); }
};

struct SceneObject {
  int64_t id = 0;  // KITTI track id
  std::string type;
  Eigen::Vector3d size = Eigen::Vector3d::Ones();  // box extent along object x, y, z: l, h, w
  bool moving = false;
  std::map<int64_t, Pose> poses;  // frame → L^W_k (moving objects: every labelled frame)
  Pose parked_pose;               // parked objects: one pose for the whole range
  double extent = 0;              // m, moving/parked evidence (see SimulateOptions)
  double max_speed = 0;           // m/s
};

struct Scene {
  std::vector<std::string> header;  // provenance lines (without '#')
  int64_t first_source_frame = 0;   // frame k of the scene is source frame k + this
  std::vector<Pose> cameras;        // X^W_k, X_0 = I
  std::vector<SceneObject> objects; // ascending id
  CameraModel camera;
};

// The scene of frames [first_frame, last_frame) of a KITTI sequence.
Expected<Scene> MakeKittiScene(const KittiSequence& sequence, const SimulateOptions& options);
// A small scene with no data: a camera on a gently curving road, a lead car, an oncoming car that
// leaves view, a car that turns across, a parked car.
Scene MakeSyntheticScene(const SimulateOptions& options);

struct SimulateStatistics {
  int64_t frames = 0;
  double camera_path_length = 0;  // m
  int64_t static_points = 0;
  int64_t static_observations = 0;
  int64_t static_obs_per_frame_min = 0;
  int64_t static_obs_per_frame_max = 0;
  int64_t parked_objects = 0;
  int64_t moving_objects = 0;
  int64_t moving_objects_observed = 0;
  int64_t dynamic_observations = 0;
  int64_t dynamic_tracklets = 0;
  int64_t dynamic_tracklets_of_length_one = 0;
  int64_t motions = 0;
  int64_t motion_edges = 0;
  int64_t smoothing_edges = 0;
  int64_t odometry_edges = 0;
  int64_t static_breaks = 0;
  int64_t dynamic_breaks = 0;
  int64_t outliers = 0;
  int64_t vertices = 0;
  int64_t edges = 0;
};

struct SimulatedScene {
  Graph graph;              // the front-end file: initial values, edges, labels (roles assigned)
  GroundTruth ground_truth; // cameras of every frame; moving objects at every labelled frame
  // The true value of every vertex (same layout as Vertex::value): the point where every
  // measurement edge's residual is pure noise and every motion edge's residual is 0.
  std::map<VertexId, std::array<double, kPoseSize>> true_values;
  SimulateStatistics statistics;
  std::vector<std::string> header;  // the scene's provenance lines plus object lists
};

Expected<SimulatedScene> Simulate(const Scene& scene, const SimulateOptions& options);
// The checks of `Simulate` that need no scene: sigmas positive, probabilities in [0, 1], …
Status CheckSimulateOptions(const SimulateOptions& options);

// `--density paper`: the tracked points per frame and per moving object that make each of the
// paper's nine sequences, simulated whole, as large as its Table I (object-centric and
// world-centric variables within 2 %, docs/SIMULATOR.md). Calibrated per sequence, because
// VDO-SLAM's dense flow tracked more points where the images have more texture and larger
// objects. False (options unchanged) for a sequence the paper did not use.
bool UsePaperDensity(const std::string& sequence, SimulateOptions* options);

// "  frames   144\n  static_points   …" — one `name value` line per statistic.
std::string FormatStatistics(const SimulateStatistics& statistics);

}  // namespace dynslam

#endif  // DYNSLAM_SIMULATE_H_
