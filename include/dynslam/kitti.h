// KITTI Tracking ground truth: readers for oxts, label_02 and calib files and the devkit's
// conversions to camera and object poses (conventions in docs/SIMULATOR.md).
//
// Frames. KITTI's 3D labels live in the *rectified camera 0* frame (x right, y down, z forward).
// A camera pose here is the pose of that frame in a world frame: oxts give the IMU pose in a
// Mercator world (devkit convertOxtsToPose), and the calib file's Tr_imu_velo, Tr_velo_cam and
// R_rect map IMU → velodyne → camera 0 → rectified camera 0. `CameraPoses` returns the poses
// relative to the first frame of a range (that camera is the world, SPEC §2).
//
// An object pose (SPEC §0: object to world) has its origin at the centre of the 3D box (the
// label's bottom centre raised by h/2 along camera −y) and the label's axes: x along the length,
// y down (height), z along the width, rotated by rotation_y about camera y.
//
// Graph layer: no Ceres. Readers never abort: errors name the file and line.
#ifndef DYNSLAM_KITTI_H_
#define DYNSLAM_KITTI_H_

#include <array>
#include <cstdint>
#include <istream>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "dynslam/pose.h"
#include "dynslam/status.h"

namespace dynslam {

inline constexpr double kEarthRadius = 6378137.0;  // devkit latlonToMercator, metres
inline constexpr double kKittiFrameRate = 10.0;    // Hz

// One line of oxts/NNNN.txt: the first six of its 30 fields (devkit dataformat.txt); the
// rest (velocities, accelerations, accuracies, status) is not needed.
struct OxtsRecord {
  double lat = 0;    // degrees
  double lon = 0;    // degrees
  double alt = 0;    // metres
  double roll = 0;   // rad, 0 = level, positive = left side up
  double pitch = 0;  // rad, 0 = level, positive = front down
  double yaw = 0;    // rad, 0 = east, positive = counter-clockwise
  int64_t line = 0;
};

// One line of label_02/NNNN.txt (17 fields; an 18th, score, is accepted and ignored).
struct LabelRecord {
  int64_t frame = 0;
  int64_t track_id = -1;  // -1 for DontCare
  std::string type;       // Car, Van, Truck, Pedestrian, Person_sitting, Cyclist, Tram, Misc, DontCare
  int truncated = 0;
  int occluded = 0;
  double alpha = 0;
  std::array<double, 4> bbox{};  // left top right bottom, pixels (image 2)
  double height = 0;             // h, w, l in metres
  double width = 0;
  double length = 0;
  Eigen::Vector3d location = Eigen::Vector3d::Zero();  // bottom centre, rectified camera 0
  double rotation_y = 0;                               // about camera y, [−π, π]
  int64_t line = 0;
};

// calib/NNNN.txt. Tracking keys (P0: … R_rect Tr_velo_cam Tr_imu_velo) or the object-benchmark
// spellings (R0_rect, Tr_velo_to_cam, Tr_imu_to_velo), with or without a colon.
struct KittiCalib {
  std::array<Eigen::Matrix<double, 3, 4>, 4> P;  // projection of rectified camera 0 points
  Eigen::Matrix3d R_rect = Eigen::Matrix3d::Identity();
  Eigen::Matrix<double, 3, 4> Tr_velo_cam = Eigen::Matrix<double, 3, 4>::Zero();
  Eigen::Matrix<double, 3, 4> Tr_imu_velo = Eigen::Matrix<double, 3, 4>::Zero();
};

struct KittiSequence {
  std::string name;  // e.g. "0003"
  std::vector<OxtsRecord> oxts;  // one per frame
  std::vector<LabelRecord> labels;
  KittiCalib calib;
};

Expected<std::vector<OxtsRecord>> ReadOxts(const std::string& path);
Expected<std::vector<LabelRecord>> ReadLabels(const std::string& path);
Expected<KittiCalib> ReadCalib(const std::string& path);
// The same from a stream; `name` is the file name errors give.
Expected<std::vector<OxtsRecord>> ReadOxts(std::istream& in, const std::string& name);
Expected<std::vector<LabelRecord>> ReadLabels(std::istream& in, const std::string& name);
Expected<KittiCalib> ReadCalib(std::istream& in, const std::string& name);
// DIR/oxts/SEQ.txt, DIR/label_02/SEQ.txt, DIR/calib/SEQ.txt. Labels must name frames of the
// oxts file.
Expected<KittiSequence> ReadKittiSequence(const std::string& dir, const std::string& sequence);

// devkit: scale = cos(lat0 · π/180), lat0 of the sequence's first frame.
double MercatorScale(double lat0_deg);
// devkit convertOxtsToPose for one record: the IMU pose in the Mercator world,
// t = (s·er·lon·π/180, s·er·ln(tan((90+lat)·π/360)), alt), R = Rz(yaw)·Ry(pitch)·Rx(roll).
Pose OxtsToImuPose(const OxtsRecord& oxts, double scale);
// The rigid map from IMU to rectified camera 0 coordinates, R_rect·Tr_velo_cam·Tr_imu_velo, with
// its rotation projected onto SO(3) (the file's 7-digit matrices are not exactly orthonormal).
Pose ImuToCamera(const KittiCalib& calib);
// Camera poses X_k (rectified camera 0 → world) of frames [first, last), relative to frame
// `first`: X_k = (W_first · C⁻¹)⁻¹ · W_k · C⁻¹ with W the IMU poses and C = ImuToCamera.
std::vector<Pose> CameraPoses(const KittiSequence& sequence, int64_t first, int64_t last);
// The object pose in rectified camera 0 coordinates: t = (x, y − h/2, z), R = Ry(rotation_y).
Pose ObjectInCamera(const LabelRecord& label);

}  // namespace dynslam

#endif  // DYNSLAM_KITTI_H_
