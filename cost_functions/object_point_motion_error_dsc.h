// r = S · (L_curr⁻¹ · H · L_prev · m_L)   (SPEC §7 item 6: EDGE_SE3_OBJ_MOTION as coded in the
// released code). It lacks the paper's − m_L, so it is not zero when the kinematics hold
// (it is m_L then); offered behind --compat to show the effect, never a default.
// L_prev = L_w_prev, L_curr = L_w_curr: object poses at k−1 and k; H = H_w; m_L = m_o.
#ifndef DYNSLAM_COST_FUNCTIONS_OBJECT_POINT_MOTION_ERROR_DSC_H_
#define DYNSLAM_COST_FUNCTIONS_OBJECT_POINT_MOTION_ERROR_DSC_H_

#include <ceres/autodiff_cost_function.h>

#include "dynslam/pose.h"
#include "dynslam/se3.h"

namespace dynslam {

class ObjectPointMotionErrorDsc {
 public:
  explicit ObjectPointMotionErrorDsc(const Eigen::Matrix3d& information)
      : sqrt_information_(SqrtInformation(information)) {}

  template <typename T>
  bool operator()(const T* const L_w_prev, const T* const L_w_curr, const T* const H_w,
                  const T* const m_o, T* residual) const {
    T p_w_prev[3];
    PoseTransformPoint(L_w_prev, m_o, p_w_prev);
    T p_w_moved[3];
    PoseTransformPoint(H_w, p_w_prev, p_w_moved);
    Eigen::Matrix<T, 3, 1> p_o_curr;
    PoseInverseTransformPoint(L_w_curr, p_w_moved, p_o_curr.data());
    Whiten(sqrt_information_, p_o_curr.data(), residual);
    return true;
  }

  static ceres::CostFunction* Create(const Eigen::Matrix3d& information) {
    return new ceres::AutoDiffCostFunction<ObjectPointMotionErrorDsc, 3, kPoseSize, kPoseSize,
                                           kPoseSize, kPointSize>(
        new ObjectPointMotionErrorDsc(information));
  }

 private:
  Eigen::Matrix3d sqrt_information_;
};

}  // namespace dynslam

#endif  // DYNSLAM_COST_FUNCTIONS_OBJECT_POINT_MOTION_ERROR_DSC_H_
