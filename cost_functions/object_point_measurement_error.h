// r = S · (X⁻¹ · L · m_L − z)   (SPEC §1.3, EDGE_SE3_OBJ_TRACKXYZ; paper eq. object_point3d_factor)
// X = T_w_c: camera pose; L = L_w_o: object pose at the camera's frame (object to world);
// m_L = m_o: the point fixed in the object frame; z = p_c measured in the camera.
#ifndef DYNSLAM_COST_FUNCTIONS_OBJECT_POINT_MEASUREMENT_ERROR_H_
#define DYNSLAM_COST_FUNCTIONS_OBJECT_POINT_MEASUREMENT_ERROR_H_

#include <ceres/autodiff_cost_function.h>

#include "dynslam/pose.h"
#include "dynslam/se3.h"

namespace dynslam {

class ObjectPointMeasurementError {
 public:
  ObjectPointMeasurementError(const Eigen::Vector3d& p_c_measured,
                              const Eigen::Matrix3d& information)
      : p_c_measured_(p_c_measured), sqrt_information_(SqrtInformation(information)) {}

  template <typename T>
  bool operator()(const T* const T_w_c, const T* const L_w_o, const T* const m_o,
                  T* residual) const {
    T p_w[3];
    PoseTransformPoint(L_w_o, m_o, p_w);
    Eigen::Matrix<T, 3, 1> p_c;
    PoseInverseTransformPoint(T_w_c, p_w, p_c.data());
    const T error[3] = {p_c[0] - p_c_measured_[0], p_c[1] - p_c_measured_[1],
                        p_c[2] - p_c_measured_[2]};
    Whiten(sqrt_information_, error, residual);
    return true;
  }

  static ceres::CostFunction* Create(const Eigen::Vector3d& p_c_measured,
                                     const Eigen::Matrix3d& information) {
    return new ceres::AutoDiffCostFunction<ObjectPointMeasurementError, 3, kPoseSize, kPoseSize,
                                           kPointSize>(
        new ObjectPointMeasurementError(p_c_measured, information));
  }

 private:
  Eigen::Vector3d p_c_measured_;
  Eigen::Matrix3d sqrt_information_;
};

}  // namespace dynslam

#endif  // DYNSLAM_COST_FUNCTIONS_OBJECT_POINT_MEASUREMENT_ERROR_H_
