// r = S · Log(L_curr⁻¹ · H · L_prev)   (SPEC §1.3, EDGE_SE3_OBJ_KINEMATIC; paper eq.
// object_kinematic_factor)
// L_prev = L_w_prev, L_curr = L_w_curr: object poses at frames k−1 and k; H = H_w: the object's
// motion H^W_{k−1,k}. Zero when H = L_curr · L_prev⁻¹. S: information in [ω; ρ] order.
#ifndef DYNSLAM_COST_FUNCTIONS_OBJECT_KINEMATIC_ERROR_H_
#define DYNSLAM_COST_FUNCTIONS_OBJECT_KINEMATIC_ERROR_H_

#include <ceres/autodiff_cost_function.h>

#include "dynslam/graph.h"
#include "dynslam/pose.h"
#include "dynslam/se3.h"

namespace dynslam {

class ObjectKinematicError {
 public:
  explicit ObjectKinematicError(const Matrix6d& information)
      : sqrt_information_(SqrtInformation(information)) {}

  template <typename T>
  bool operator()(const T* const L_w_prev, const T* const L_w_curr, const T* const H_w,
                  T* residual) const {
    T L_curr_w[kPoseSize];
    PoseInverse(L_w_curr, L_curr_w);
    T L_curr_w_moved[kPoseSize];
    PoseCompose(L_curr_w, H_w, L_curr_w_moved);
    T error_pose[kPoseSize];
    PoseCompose(L_curr_w_moved, L_w_prev, error_pose);
    Eigen::Matrix<T, 6, 1> error;
    SE3Log(error_pose, error.data());
    Eigen::Map<Eigen::Matrix<T, 6, 1>> r(residual);
    r = sqrt_information_.cast<T>() * error;
    if (rotate_) {
      const Eigen::Matrix<T, 3, 3> rotation = se3_internal::Rotation(L_w_curr).toRotationMatrix();
      r.template head<3>() = (rotation * r.template head<3>()).eval();
      r.template tail<3>() = (rotation * r.template tail<3>()).eval();
    }
    return true;
  }

  static ceres::CostFunction* Create(const Matrix6d& information, bool rotate = false) {
    auto* f = new ObjectKinematicError(information);
    f->rotate_ = rotate;
    return new ceres::AutoDiffCostFunction<ObjectKinematicError, 6, kPoseSize, kPoseSize,
                                           kPoseSize>(f);
  }

 private:
  bool rotate_ = false;
  Matrix6d sqrt_information_;
};

}  // namespace dynslam

#endif  // DYNSLAM_COST_FUNCTIONS_OBJECT_KINEMATIC_ERROR_H_
