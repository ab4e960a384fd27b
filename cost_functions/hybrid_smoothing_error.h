// r = S · Log((L_a⁻¹ · L_b)⁻¹ · (L_b⁻¹ · L_c)),  L_x = H_x · L_e   (SPEC §3.6,
// EDGE_SE3_HY_SMOOTHING)
// H_a, H_b, H_c = H^e_{k−2}, H^e_{k−1}, H^e_k: the object's motions from its embedded frame L_e
// (held constant by the solver). Zero when the body-frame motions L_{k−2}⁻¹ L_{k−1} and
// L_{k−1}⁻¹ L_k are equal (constant velocity in the object frame); no measurement.
// S: information in [ω; ρ] order.
#ifndef DYNSLAM_COST_FUNCTIONS_HYBRID_SMOOTHING_ERROR_H_
#define DYNSLAM_COST_FUNCTIONS_HYBRID_SMOOTHING_ERROR_H_

#include <ceres/autodiff_cost_function.h>

#include "dynslam/pose.h"
#include "dynslam/se3.h"

namespace dynslam {

class HybridSmoothingError {
 public:
  explicit HybridSmoothingError(const Matrix6d& information)
      : sqrt_information_(SqrtInformation(information)) {}

  template <typename T>
  bool operator()(const T* const H_a, const T* const H_b, const T* const H_c,
                  const T* const L_w_e, T* residual) const {
    T L_a[kPoseSize], L_b[kPoseSize], L_c[kPoseSize];
    PoseCompose(H_a, L_w_e, L_a);
    PoseCompose(H_b, L_w_e, L_b);
    PoseCompose(H_c, L_w_e, L_c);
    T L_b_inverse[kPoseSize];
    PoseInverse(L_b, L_b_inverse);
    T back[kPoseSize];  // (L_a⁻¹ · L_b)⁻¹ = L_b⁻¹ · L_a
    PoseCompose(L_b_inverse, L_a, back);
    T forward[kPoseSize];  // L_b⁻¹ · L_c
    PoseCompose(L_b_inverse, L_c, forward);
    T error_pose[kPoseSize];
    PoseCompose(back, forward, error_pose);
    T error[6];
    SE3Log(error_pose, error);
    Whiten(sqrt_information_, error, residual);
    return true;
  }

  static ceres::CostFunction* Create(const Matrix6d& information) {
    return new ceres::AutoDiffCostFunction<HybridSmoothingError, 6, kPoseSize, kPoseSize,
                                           kPoseSize, kPoseSize>(
        new HybridSmoothingError(information));
  }

 private:
  Matrix6d sqrt_information_;
};

}  // namespace dynslam

#endif  // DYNSLAM_COST_FUNCTIONS_HYBRID_SMOOTHING_ERROR_H_
