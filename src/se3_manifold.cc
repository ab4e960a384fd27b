#include "dynslam/se3_manifold.h"

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "dynslam/se3.h"

namespace dynslam {
namespace {

using RowMajor7x6 = Eigen::Matrix<double, 7, 6, Eigen::RowMajor>;
using RowMajor6x7 = Eigen::Matrix<double, 6, 7, Eigen::RowMajor>;

Eigen::Matrix3d Skew(const Eigen::Vector3d& v) {
  Eigen::Matrix3d m;
  m << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
  return m;
}

}  // namespace

bool SE3Manifold::Plus(const double* x, const double* delta, double* x_plus_delta) const {
  double exp_delta[kPoseSize];
  SE3Exp(delta, exp_delta);
  PoseCompose(x, exp_delta, x_plus_delta);
  // Keep the quaternion on the unit sphere: rounding would otherwise drift it over iterations.
  Eigen::Map<Eigen::Quaterniond>(x_plus_delta).normalize();
  return true;
}

bool SE3Manifold::PlusJacobian(const double* x, double* jacobian) const {
  const Eigen::Map<const Eigen::Quaterniond> q(x);
  Eigen::Map<RowMajor7x6> j(jacobian);
  j.setZero();
  j.block<3, 3>(0, 0) = 0.5 * (q.w() * Eigen::Matrix3d::Identity() + Skew(q.vec()));
  j.block<1, 3>(3, 0) = -0.5 * q.vec().transpose();
  j.block<3, 3>(4, 3) = q.toRotationMatrix();
  return true;
}

bool SE3Manifold::Minus(const double* y, const double* x, double* y_minus_x) const {
  double x_inverse_y[kPoseSize];
  PoseInverse(x, x_inverse_y);
  PoseCompose(x_inverse_y, y, x_inverse_y);
  SE3Log(x_inverse_y, y_minus_x);
  return true;
}

bool SE3Manifold::MinusJacobian(const double* x, double* jacobian) const {
  const Eigen::Map<const Eigen::Quaterniond> q(x);
  Eigen::Map<RowMajor6x7> j(jacobian);
  j.setZero();
  j.block<3, 3>(0, 0) = 2.0 * (q.w() * Eigen::Matrix3d::Identity() - Skew(q.vec()));
  j.block<3, 1>(0, 3) = -2.0 * q.vec();
  j.block<3, 3>(3, 4) = q.toRotationMatrix().transpose();
  return true;
}

}  // namespace dynslam
