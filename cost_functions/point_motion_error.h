// r = S · (m_curr − H · m_prev − z)   (SPEC §1.2, EDGE_SE3_MOTION; paper eq.
// world_landmark_motion_tenary_factor)
// m_prev = p_w_prev, m_curr = p_w_curr: one tracked point of object j in the world at frames k−1
// and k; H = H_w: the object's motion H^W_{k−1,k} (7 doubles, SPEC §0); z: normally 0.
#ifndef DYNSLAM_COST_FUNCTIONS_POINT_MOTION_ERROR_H_
#define DYNSLAM_COST_FUNCTIONS_POINT_MOTION_ERROR_H_

#include <ceres/autodiff_cost_function.h>

#include "dynslam/pose.h"
#include "dynslam/se3.h"

namespace dynslam {

class PointMotionError {
 public:
  PointMotionError(const Eigen::Vector3d& measurement, const Eigen::Matrix3d& information)
      : measurement_(measurement), sqrt_information_(SqrtInformation(information)) {}

  template <typename T>
  bool operator()(const T* const p_w_prev, const T* const p_w_curr, const T* const H_w,
                  T* residual) const {
    Eigen::Matrix<T, 3, 1> p_w_moved;
    PoseTransformPoint(H_w, p_w_prev, p_w_moved.data());
    const Eigen::Map<const Eigen::Matrix<T, 3, 1>> p_curr(p_w_curr);
    const T error[3] = {p_curr[0] - p_w_moved[0] - measurement_[0],
                        p_curr[1] - p_w_moved[1] - measurement_[1],
                        p_curr[2] - p_w_moved[2] - measurement_[2]};
    Whiten(sqrt_information_, error, residual);
    return true;
  }

  static ceres::CostFunction* Create(const Eigen::Vector3d& measurement,
                                     const Eigen::Matrix3d& information) {
    return new ceres::AutoDiffCostFunction<PointMotionError, 3, kPointSize, kPointSize,
                                           kPoseSize>(
        new PointMotionError(measurement, information));
  }

 private:
  Eigen::Vector3d measurement_;
  Eigen::Matrix3d sqrt_information_;
};

}  // namespace dynslam

#endif  // DYNSLAM_COST_FUNCTIONS_POINT_MOTION_ERROR_H_
