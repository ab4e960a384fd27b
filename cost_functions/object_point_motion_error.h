// r = S · (L_curr · m_L − H · L_prev · m_L − z)   (SPEC §1.3, EDGE_SE3_OBJ_MOTION; paper eq.
// object_landmark_motion_factor)
// L_prev = L_w_prev, L_curr = L_w_curr: object poses at frames k−1 and k (object to world);
// H = H_w: the object's motion H^W_{k−1,k}; m_L = m_o: a point fixed in the object frame; z: the
// front-end motion edge's (SPEC §3.3 oc_a), normally 0. With z = 0, zero when the kinematics
// hold (H = L_curr · L_prev⁻¹).
#ifndef DYNSLAM_COST_FUNCTIONS_OBJECT_POINT_MOTION_ERROR_H_
#define DYNSLAM_COST_FUNCTIONS_OBJECT_POINT_MOTION_ERROR_H_

#include <ceres/autodiff_cost_function.h>

#include "dynslam/pose.h"
#include "dynslam/se3.h"

namespace dynslam {

class ObjectPointMotionError {
 public:
  ObjectPointMotionError(const Eigen::Vector3d& measurement, const Eigen::Matrix3d& information)
      : measurement_(measurement), sqrt_information_(SqrtInformation(information)) {}

  template <typename T>
  bool operator()(const T* const L_w_prev, const T* const L_w_curr, const T* const H_w,
                  const T* const m_o, T* residual) const {
    Eigen::Matrix<T, 3, 1> p_w_curr;
    PoseTransformPoint(L_w_curr, m_o, p_w_curr.data());
    T p_w_prev[3];
    PoseTransformPoint(L_w_prev, m_o, p_w_prev);
    Eigen::Matrix<T, 3, 1> p_w_moved;
    PoseTransformPoint(H_w, p_w_prev, p_w_moved.data());
    const Eigen::Matrix<T, 3, 1> error = p_w_curr - p_w_moved - measurement_.cast<T>();
    Whiten(sqrt_information_, error.data(), residual);
    return true;
  }

  static ceres::CostFunction* Create(const Eigen::Vector3d& measurement,
                                     const Eigen::Matrix3d& information) {
    return new ceres::AutoDiffCostFunction<ObjectPointMotionError, 3, kPoseSize, kPoseSize,
                                           kPoseSize, kPointSize>(
        new ObjectPointMotionError(measurement, information));
  }

 private:
  Eigen::Vector3d measurement_;
  Eigen::Matrix3d sqrt_information_;
};

}  // namespace dynslam

#endif  // DYNSLAM_COST_FUNCTIONS_OBJECT_POINT_MOTION_ERROR_H_
