// r = S · Log(Z⁻¹ · A⁻¹ · B)   (SPEC §1.2, EDGE_SE3:QUAT; GTSAM BetweenFactor<Pose3>)
// A = T_w_a, B = T_w_b: two poses (cameras: odometry; motions of one object: smoothing);
// Z = T_a_b_measured: B seen from A; S: upper Cholesky factor of the information, [ω; ρ] order.
#ifndef DYNSLAM_COST_FUNCTIONS_POSE_BETWEEN_ERROR_H_
#define DYNSLAM_COST_FUNCTIONS_POSE_BETWEEN_ERROR_H_

#include <ceres/autodiff_cost_function.h>

#include "dynslam/pose.h"
#include "dynslam/se3.h"

namespace dynslam {

class PoseBetweenError {
 public:
  PoseBetweenError(const Pose& T_a_b_measured, const Matrix6d& information)
      : T_measured_a_(Inverse(T_a_b_measured)), sqrt_information_(SqrtInformation(information)) {}

  template <typename T>
  bool operator()(const T* const T_w_a, const T* const T_w_b, T* residual) const {
    T T_a_w[kPoseSize];
    PoseInverse(T_w_a, T_a_w);
    T T_a_b[kPoseSize];
    PoseCompose(T_a_w, T_w_b, T_a_b);
    T T_measured_b[kPoseSize];
    PoseComposeConstant(T_measured_a_, T_a_b, T_measured_b);
    T error[6];
    SE3Log(T_measured_b, error);
    Whiten(sqrt_information_, error, residual);
    return true;
  }

  static ceres::CostFunction* Create(const Pose& T_a_b_measured, const Matrix6d& information) {
    return new ceres::AutoDiffCostFunction<PoseBetweenError, 6, kPoseSize, kPoseSize>(
        new PoseBetweenError(T_a_b_measured, information));
  }

 private:
  Pose T_measured_a_;  // Z⁻¹, precomputed
  Matrix6d sqrt_information_;
};

}  // namespace dynslam

#endif  // DYNSLAM_COST_FUNCTIONS_POSE_BETWEEN_ERROR_H_
