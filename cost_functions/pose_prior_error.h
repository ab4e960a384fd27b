// r = S · Log(Z⁻¹ · X)   (SPEC §1.2, EDGE_SE3_PRIOR; GTSAM PriorFactor<Pose3>)
// X = T_w_x: the pose variable (camera or object pose, 7 doubles, SPEC §0);
// Z = T_w_measured: the prior; S: upper Cholesky factor of the information in [ω; ρ] order.
#ifndef DYNSLAM_COST_FUNCTIONS_POSE_PRIOR_ERROR_H_
#define DYNSLAM_COST_FUNCTIONS_POSE_PRIOR_ERROR_H_

#include <ceres/autodiff_cost_function.h>

#include "dynslam/pose.h"
#include "dynslam/se3.h"

namespace dynslam {

class PosePriorError {
 public:
  PosePriorError(const Pose& T_w_measured, const Matrix6d& information)
      : T_measured_w_(Inverse(T_w_measured)), sqrt_information_(SqrtInformation(information)) {}

  template <typename T>
  bool operator()(const T* const T_w_x, T* residual) const {
    T T_measured_x[kPoseSize];
    PoseComposeConstant(T_measured_w_, T_w_x, T_measured_x);
    T error[6];
    SE3Log(T_measured_x, error);
    Whiten(sqrt_information_, error, residual);
    return true;
  }

  static ceres::CostFunction* Create(const Pose& T_w_measured, const Matrix6d& information) {
    return new ceres::AutoDiffCostFunction<PosePriorError, 6, kPoseSize>(
        new PosePriorError(T_w_measured, information));
  }

 private:
  Pose T_measured_w_;  // Z⁻¹, precomputed
  Matrix6d sqrt_information_;
};

}  // namespace dynslam

#endif  // DYNSLAM_COST_FUNCTIONS_POSE_PRIOR_ERROR_H_
