// r = S · Log(L_curr⁻¹ · H · L_prev)   (SPEC §1.3, EDGE_SE3_OBJ_KINEMATIC; paper eq.
// object_kinematic_factor)
// L_prev = L_w_prev, L_curr = L_w_curr: object poses at frames k−1 and k; H = H_w: the object's
// motion H^W_{k−1,k}. Zero when H = L_curr · L_prev⁻¹. S: information in [ω; ρ] order.
// `world_frame`: both 3-vectors of r turned by L_curr's rotation — the same norm, so the same
// cost, but unchanged when every object pose of a segment turns by the same rotation (its gauge,
// docs/CONVERGENCE.md); the solver's default (SolverOptions::world_frame_kinematic_residual).
#ifndef DYNSLAM_COST_FUNCTIONS_OBJECT_KINEMATIC_ERROR_H_
#define DYNSLAM_COST_FUNCTIONS_OBJECT_KINEMATIC_ERROR_H_

#include <ceres/autodiff_cost_function.h>

#include "dynslam/pose.h"
#include "dynslam/se3.h"

namespace dynslam {

class ObjectKinematicError {
 public:
  ObjectKinematicError(const Matrix6d& information, bool world_frame)
      : sqrt_information_(SqrtInformation(information)), world_frame_(world_frame) {}

  template <typename T>
  bool operator()(const T* const L_w_prev, const T* const L_w_curr, const T* const H_w,
                  T* residual) const {
    T L_curr_w[kPoseSize];
    PoseInverse(L_w_curr, L_curr_w);
    T L_curr_w_moved[kPoseSize];
    PoseCompose(L_curr_w, H_w, L_curr_w_moved);
    T error_pose[kPoseSize];
    PoseCompose(L_curr_w_moved, L_w_prev, error_pose);
    T error[6];
    SE3Log(error_pose, error);
    Whiten(sqrt_information_, error, residual);
    if (world_frame_) {
      Eigen::Map<Eigen::Matrix<T, 6, 1>> r(residual);
      const Eigen::Matrix<T, 3, 3> rotation = se3_internal::Rotation(L_w_curr).toRotationMatrix();
      r.template head<3>() = (rotation * r.template head<3>()).eval();
      r.template tail<3>() = (rotation * r.template tail<3>()).eval();
    }
    return true;
  }

  static ceres::CostFunction* Create(const Matrix6d& information, bool world_frame = false) {
    return new ceres::AutoDiffCostFunction<ObjectKinematicError, 6, kPoseSize, kPoseSize,
                                           kPoseSize>(
        new ObjectKinematicError(information, world_frame));
  }

 private:
  Matrix6d sqrt_information_;
  bool world_frame_;
};

}  // namespace dynslam

#endif  // DYNSLAM_COST_FUNCTIONS_OBJECT_KINEMATIC_ERROR_H_
