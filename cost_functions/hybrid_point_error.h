// r = S · (X⁻¹ · H · L_e · m − z)   (SPEC §3.6, EDGE_SE3_HY_TRACKXYZ)
// X = T_w_c: camera pose at frame k; H = H^e_k: the world-frame motion of the object from its
// embedded frame's time e to k; L_e = L_w_e: the segment's embedded frame (held constant by the
// solver); m = m_e: the point fixed in the object frame; z = p_c measured in the camera.
#ifndef DYNSLAM_COST_FUNCTIONS_HYBRID_POINT_ERROR_H_
#define DYNSLAM_COST_FUNCTIONS_HYBRID_POINT_ERROR_H_

#include <ceres/autodiff_cost_function.h>

#include "dynslam/pose.h"
#include "dynslam/se3.h"

namespace dynslam {

class HybridPointError {
 public:
  HybridPointError(const Eigen::Vector3d& p_c_measured, const Eigen::Matrix3d& information)
      : p_c_measured_(p_c_measured), sqrt_information_(SqrtInformation(information)) {}

  template <typename T>
  bool operator()(const T* const T_w_c, const T* const H_w, const T* const L_w_e,
                  const T* const m_e, T* residual) const {
    T p_e_in_w[3];
    PoseTransformPoint(L_w_e, m_e, p_e_in_w);
    T p_w[3];
    PoseTransformPoint(H_w, p_e_in_w, p_w);
    Eigen::Matrix<T, 3, 1> p_c;
    PoseInverseTransformPoint(T_w_c, p_w, p_c.data());
    const T error[3] = {p_c[0] - p_c_measured_[0], p_c[1] - p_c_measured_[1],
                        p_c[2] - p_c_measured_[2]};
    Whiten(sqrt_information_, error, residual);
    return true;
  }

  static ceres::CostFunction* Create(const Eigen::Vector3d& p_c_measured,
                                     const Eigen::Matrix3d& information) {
    return new ceres::AutoDiffCostFunction<HybridPointError, 3, kPoseSize, kPoseSize, kPoseSize,
                                           kPointSize>(
        new HybridPointError(p_c_measured, information));
  }

 private:
  Eigen::Vector3d p_c_measured_;
  Eigen::Matrix3d sqrt_information_;
};

}  // namespace dynslam

#endif  // DYNSLAM_COST_FUNCTIONS_HYBRID_POINT_ERROR_H_
