// Use one of dynslam's residuals in your own ceres::Problem: a point seen from two camera poses
// (SPEC §1.2 EDGE_SE3_TRACKXYZ), the first pose held fixed, poses on dynslam's SE(3) manifold.
#include <cstdio>

#include <ceres/ceres.h>

#include "cost_functions/point_measurement_error.h"
#include "dynslam/pose.h"
#include "dynslam/se3.h"
#include "dynslam/se3_manifold.h"

int main() {
  using dynslam::Pose;
  // Truth: camera 1 one metre right of camera 0; a point 10 m ahead.
  const Pose T_w_c0 = Pose::Identity();
  const Pose T_w_c1 = Pose::FromRotationTranslation(Eigen::Quaterniond::Identity(), {1, 0, 0});
  const Eigen::Vector3d p_w(0.5, 0.2, 10);
  const Eigen::Matrix3d information = Eigen::Matrix3d::Identity() * 100;  // σ = 0.1 m

  // Estimates: camera 1 and the point start off.
  Pose c0 = T_w_c0, c1 = Pose::FromRotationTranslation(Eigen::Quaterniond::Identity(), {0.7, 0.1, 0});
  Eigen::Vector3d point(0, 0, 8);

  dynslam::SE3Manifold manifold;  // shared by all pose blocks; outlives the problem
  ceres::Problem::Options problem_options;
  problem_options.manifold_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  ceres::Problem problem(problem_options);
  problem.AddParameterBlock(c0.data.data(), dynslam::kPoseSize, &manifold);
  problem.AddParameterBlock(c1.data.data(), dynslam::kPoseSize, &manifold);
  problem.SetParameterBlockConstant(c0.data.data());
  for (const Pose* truth : {&T_w_c0, &T_w_c1}) {
    Pose* estimate = truth == &T_w_c0 ? &c0 : &c1;
    const Eigen::Vector3d p_c = dynslam::Transform(dynslam::Inverse(*truth), p_w);
    problem.AddResidualBlock(dynslam::PointMeasurementError::Create(p_c, information), nullptr,
                             estimate->data.data(), point.data());
  }
  // Two observations leave camera 1 free to turn about the point: anchor it with a second point.
  const Eigen::Vector3d q_w(-2, 1, 15);
  Eigen::Vector3d q(-1.5, 0.8, 12);
  for (const Pose* truth : {&T_w_c0, &T_w_c1}) {
    Pose* estimate = truth == &T_w_c0 ? &c0 : &c1;
    const Eigen::Vector3d q_c = dynslam::Transform(dynslam::Inverse(*truth), q_w);
    problem.AddResidualBlock(dynslam::PointMeasurementError::Create(q_c, information), nullptr,
                             estimate->data.data(), q.data());
  }
  ceres::Solver::Options options;
  ceres::Solver::Summary summary;
  ceres::Solve(options, &problem, &summary);
  std::printf("cost %.3g -> %.3g; point (%.4f %.4f %.4f), truth (0.5 0.2 10)\n",
              summary.initial_cost, summary.final_cost, point.x(), point.y(), point.z());
  return summary.IsSolutionUsable() ? 0 : 1;
}
