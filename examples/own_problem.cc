// Use dynslam's residuals in your own ceres::Problem: a square loop of four camera poses with a
// prior on the first (SPEC §1.2 EDGE_SE3_PRIOR) and relative-pose measurements between
// neighbours (EDGE_SE3:QUAT), every pose block on dynslam's SE(3) manifold (x·Exp(ξ), ξ = [ω; ρ]).
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>

#include <ceres/ceres.h>

#include "cost_functions/pose_between_error.h"
#include "cost_functions/pose_prior_error.h"
#include "dynslam/pose.h"
#include "dynslam/se3.h"
#include "dynslam/se3_manifold.h"

int main() {
  using dynslam::Pose;
  using dynslam::Vector6d;
  constexpr int kPoses = 4;
  // Truth T_w_ci: one metre forward, then a quarter turn about z, four times: back at the start.
  std::array<Pose, kPoses> truth;
  Vector6d step;
  step << 0, 0, M_PI / 2, 1, 0, 0;  // [ω; ρ]
  truth[0] = Pose::Identity();
  for (int i = 1; i < kPoses; ++i) truth[i] = dynslam::Compose(truth[i - 1], dynslam::Exp(step));

  // Estimates: the truth pushed off by a different tangent vector per pose.
  std::array<Pose, kPoses> estimate;
  for (int i = 0; i < kPoses; ++i) {
    Vector6d noise;
    noise << 0.05 * i, -0.03, 0.1, 0.2, -0.1 * i, 0.05;
    estimate[i] = dynslam::Compose(truth[i], dynslam::Exp(noise));
  }

  const dynslam::Matrix6d information = dynslam::Matrix6d::Identity() * 100;  // σ = 0.1
  dynslam::SE3Manifold manifold;  // shared by all pose blocks; outlives the problem
  ceres::Problem::Options problem_options;
  problem_options.manifold_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  ceres::Problem problem(problem_options);
  for (Pose& pose : estimate) {
    problem.AddParameterBlock(pose.data.data(), dynslam::kPoseSize, &manifold);
  }
  // The prior fixes the gauge (without it the whole loop could move freely).
  problem.AddResidualBlock(dynslam::PosePriorError::Create(truth[0], information), nullptr,
                           estimate[0].data.data());
  for (int i = 0; i < kPoses; ++i) {  // odometry 0→1→2→3 and the loop closure 3→0
    const int j = (i + 1) % kPoses;
    const Pose T_ci_cj = dynslam::Compose(dynslam::Inverse(truth[i]), truth[j]);
    problem.AddResidualBlock(dynslam::PoseBetweenError::Create(T_ci_cj, information), nullptr,
                             estimate[i].data.data(), estimate[j].data.data());
  }

  ceres::Solver::Options options;
  options.function_tolerance = 1e-12;
  ceres::Solver::Summary summary;
  ceres::Solve(options, &problem, &summary);
  double worst_angle = 0, worst_translation = 0;
  for (int i = 0; i < kPoses; ++i) {
    const Pose error = dynslam::Compose(dynslam::Inverse(truth[i]), estimate[i]);
    worst_angle = std::max(worst_angle, dynslam::RotationAngle(error));
    worst_translation = std::max(worst_translation, error.translation().norm());
  }
  std::printf("cost %.3g -> %.3g in %d iterations; worst pose error %.2e rad, %.2e m\n",
              summary.initial_cost, summary.final_cost,
              static_cast<int>(summary.iterations.size()), worst_angle, worst_translation);
  return summary.IsSolutionUsable() && worst_angle < 1e-6 && worst_translation < 1e-6 ? 0 : 1;
}
