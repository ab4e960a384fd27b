// r = S · Log(Z⁻¹ · X)   (SPEC §1.2, EDGE_SE3_PRIOR; GTSAM PriorFactor<Pose3>)
// X = T_w_x: the pose variable (camera or object pose, 7 doubles, SPEC §0);
// Z = T_w_measured: the prior; S: upper Cholesky factor of the information in [ω; ρ] order.
#ifndef DYNSLAM_COST_FUNCTIONS_POSE_PRIOR_ERROR_H_
#define DYNSLAM_COST_FUNCTIONS_POSE_PRIOR_ERROR_H_

#include <ceres/autodiff_cost_function.h>

#include "dynslam/graph.h"
#include "dynslam/pose.h"
#include "dynslam/se3.h"

namespace dynslam {

class PosePriorError {
 public:
  PosePriorError(const Pose& T_w_measured, const Matrix6d& information)
      : T_measured_w_(Inverse(T_w_measured)), sqrt_information_(SqrtInformation(information)) {}

  template <typename T>
  bool operator()(const T* const T_w_x, T* residual) const {
    T T_measured_w[kPoseSize];
    for (int i = 0; i < kPoseSize; ++i) T_measured_w[i] = T(T_measured_w_.data[i]);
    T T_measured_x[kPoseSize];
    PoseCompose(T_measured_w, T_w_x, T_measured_x);
    Eigen::Matrix<T, 6, 1> error;
    SE3Log(T_measured_x, error.data());
    Eigen::Map<Eigen::Matrix<T, 6, 1>> r(residual);
    r = sqrt_information_.cast<T>() * error;
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
