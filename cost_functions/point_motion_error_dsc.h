// r = (m_prev − H⁻¹ · m_curr) / σ   (SPEC §7 item 2: the released code's EDGE_SE3_MOTION)
// m_prev = p_w_prev, m_curr = p_w_curr: a tracked point in the world at frames k−1 and k;
// H = H_w: the object's motion H^W_{k−1,k}. The file's information and measurement are ignored;
// σ is isotropic (0.1 in the release). Offered behind --compat, never a default.
#ifndef DYNSLAM_COST_FUNCTIONS_POINT_MOTION_ERROR_DSC_H_
#define DYNSLAM_COST_FUNCTIONS_POINT_MOTION_ERROR_DSC_H_

#include <ceres/autodiff_cost_function.h>

#include "dynslam/pose.h"
#include "dynslam/se3.h"

namespace dynslam {

class PointMotionErrorDsc {
 public:
  explicit PointMotionErrorDsc(double sigma) : inverse_sigma_(1.0 / sigma) {}

  template <typename T>
  bool operator()(const T* const p_w_prev, const T* const p_w_curr, const T* const H_w,
                  T* residual) const {
    T p_w_moved_back[3];
    PoseInverseTransformPoint(H_w, p_w_curr, p_w_moved_back);
    for (int i = 0; i < 3; ++i) residual[i] = (p_w_prev[i] - p_w_moved_back[i]) * inverse_sigma_;
    return true;
  }

  static ceres::CostFunction* Create(double sigma) {
    return new ceres::AutoDiffCostFunction<PointMotionErrorDsc, 3, kPointSize, kPointSize,
                                           kPoseSize>(new PointMotionErrorDsc(sigma));
  }

 private:
  double inverse_sigma_;
};

}  // namespace dynslam

#endif  // DYNSLAM_COST_FUNCTIONS_POINT_MOTION_ERROR_DSC_H_
