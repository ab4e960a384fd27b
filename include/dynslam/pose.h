// The pose block: one SE(3) element stored as 7 doubles (SPEC §0).
//
// Layout: [qx qy qz qw tx ty tz] — a unit Hamilton quaternion (Eigen's storage order, so
// `Eigen::Map<Eigen::Quaterniond>(data)` views it) followed by the translation. The pose maps
// local coordinates to world: p_w = R · p_local + t. The same 7 doubles are a Ceres parameter
// block with `SE3Manifold` (se3_manifold.h). Graph files write `tx ty tz qx qy qz qw`
// (SPEC §1.1); only graph_io converts between the two orders.
#ifndef DYNSLAM_POSE_H_
#define DYNSLAM_POSE_H_

#include <array>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace dynslam {

inline constexpr int kPoseSize = 7;     // ambient size of a pose block
inline constexpr int kTangentSize = 6;  // ξ = [ω; ρ]
inline constexpr int kPointSize = 3;

using Vector6d = Eigen::Matrix<double, kTangentSize, 1>;
using Matrix6d = Eigen::Matrix<double, kTangentSize, kTangentSize>;  // e.g. information, [ω; ρ]

struct Pose {
  std::array<double, kPoseSize> data{0, 0, 0, 1, 0, 0, 0};

  static Pose Identity() { return Pose(); }
  static Pose FromRotationTranslation(const Eigen::Quaterniond& q, const Eigen::Vector3d& t) {
    Pose pose;
    pose.rotation() = q;
    pose.translation() = t;
    return pose;
  }
  static Pose FromIsometry(const Eigen::Isometry3d& T) {
    return FromRotationTranslation(Eigen::Quaterniond(T.linear()), T.translation());
  }

  Eigen::Map<Eigen::Quaterniond> rotation() { return Eigen::Map<Eigen::Quaterniond>(data.data()); }
  Eigen::Map<const Eigen::Quaterniond> rotation() const {
    return Eigen::Map<const Eigen::Quaterniond>(data.data());
  }
  Eigen::Map<Eigen::Vector3d> translation() { return Eigen::Map<Eigen::Vector3d>(data.data() + 4); }
  Eigen::Map<const Eigen::Vector3d> translation() const {
    return Eigen::Map<const Eigen::Vector3d>(data.data() + 4);
  }

  Eigen::Isometry3d ToIsometry() const {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear() = rotation().normalized().toRotationMatrix();
    T.translation() = translation();
    return T;
  }

  bool operator==(const Pose& other) const { return data == other.data; }
  bool operator!=(const Pose& other) const { return data != other.data; }
};

}  // namespace dynslam

#endif  // DYNSLAM_POSE_H_
