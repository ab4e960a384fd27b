// r = S · (X⁻¹ · m − z)   (SPEC §1.2, EDGE_SE3_TRACKXYZ; paper eq. world_point3d_factor up to sign)
// X = T_w_c: camera pose (7 doubles, SPEC §0); m = p_w: point in world (static, or a dynamic
// point at one frame); z = p_c measured in the camera; S: upper Cholesky factor of the information.
#ifndef DYNSLAM_COST_FUNCTIONS_POINT_MEASUREMENT_ERROR_H_
#define DYNSLAM_COST_FUNCTIONS_POINT_MEASUREMENT_ERROR_H_

#include <ceres/autodiff_cost_function.h>

#include "dynslam/pose.h"
#include "dynslam/se3.h"

namespace dynslam {

class PointMeasurementError {
 public:
  PointMeasurementError(const Eigen::Vector3d& p_c_measured, const Eigen::Matrix3d& information)
      : p_c_measured_(p_c_measured), sqrt_information_(SqrtInformation(information)) {}

  template <typename T>
  bool operator()(const T* const T_w_c, const T* const p_w, T* residual) const {
    Eigen::Matrix<T, 3, 1> p_c;
    PoseInverseTransformPoint(T_w_c, p_w, p_c.data());
    const T error[3] = {p_c[0] - p_c_measured_[0], p_c[1] - p_c_measured_[1],
                        p_c[2] - p_c_measured_[2]};
    Whiten(sqrt_information_, error, residual);
    return true;
  }

  static ceres::CostFunction* Create(const Eigen::Vector3d& p_c_measured,
                                     const Eigen::Matrix3d& information) {
    return new ceres::AutoDiffCostFunction<PointMeasurementError, 3, kPoseSize, kPointSize>(
        new PointMeasurementError(p_c_measured, information));
  }

 private:
  Eigen::Vector3d p_c_measured_;
  Eigen::Matrix3d sqrt_information_;  // upper Cholesky factor: Sᵀ S = information
};

}  // namespace dynslam

#endif  // DYNSLAM_COST_FUNCTIONS_POINT_MEASUREMENT_ERROR_H_
