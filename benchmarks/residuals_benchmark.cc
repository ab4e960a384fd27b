// Google Benchmark micro-benchmarks: each residual the solver builds, evaluated alone and with
// its Jacobians, and the manifold's Plus and PlusJacobian. The cost functions come from the
// library's factories (src/edge_costs.h), so this times the code the solver runs, compiled as
// the library compiles it. Run: build/release/benchmarks/residuals_benchmark
#include <benchmark/benchmark.h>
#include <ceres/ceres.h>

#include <memory>
#include <vector>

#include "dynslam/se3.h"
#include "dynslam/se3_manifold.h"
#include "src/edge_costs.h"

namespace dynslam {
namespace {

Pose GenericPose(double seed) {
  Vector6d xi;
  xi << 0.3 * seed, -0.2, 0.5, 1.0 + seed, -2.0, 0.7;
  return Exp(xi);
}

// Evaluates `cost` at fixed generic values; with_jacobians adds the ambient Jacobians.
void Evaluate(benchmark::State& state, std::unique_ptr<ceres::CostFunction> cost,
              bool with_jacobians) {
  std::vector<std::vector<double>> blocks;
  for (size_t i = 0; i < cost->parameter_block_sizes().size(); ++i) {
    const int size = cost->parameter_block_sizes()[i];
    if (size == kPoseSize) {
      const Pose pose = GenericPose(static_cast<double>(i));
      blocks.emplace_back(pose.data.begin(), pose.data.end());
    } else {
      blocks.push_back({1.0 + i, -0.5, 8.0});
    }
  }
  std::vector<const double*> parameters;
  for (const auto& block : blocks) parameters.push_back(block.data());
  std::vector<double> residuals(cost->num_residuals());
  std::vector<std::vector<double>> jacobian_storage;
  std::vector<double*> jacobians;
  for (const int size : cost->parameter_block_sizes()) {
    jacobian_storage.emplace_back(static_cast<size_t>(size * cost->num_residuals()));
    jacobians.push_back(jacobian_storage.back().data());
  }
  for (auto _ : state) {
    cost->Evaluate(parameters.data(), residuals.data(),
                   with_jacobians ? jacobians.data() : nullptr);
    benchmark::DoNotOptimize(residuals.data());
  }
}

const Eigen::Vector3d kMeasurement(0.4, -0.3, 9.0);
const Eigen::Matrix3d kInformation3 = Eigen::Vector3d(4, 5, 0.5).asDiagonal();
const Matrix6d kInformation6 = Vector6d(100, 100, 100, 10, 10, 10).asDiagonal();
const SolverOptions kDefaults;

// An edge with measurement z and information `information`; vertex ids left at their defaults.
template <typename Edge, typename Z, typename Information>
Edge Measured(const Z& z, const Information& information) {
  Edge e;
  e.measurement = z;
  e.information = information;
  return e;
}

// Vertex ids 1 (camera), 2 (object pose), 3 (point): the anchored variants compare them.
ObjectPointEdge ObjectPoint() {
  ObjectPointEdge e = Measured<ObjectPointEdge>(kMeasurement, kInformation3);
  e.camera = 1;
  e.object_pose = 2;
  e.point = 3;
  return e;
}

// Vertex ids 1 (L_prev), 2 (L_curr), 3 (H), 4 (point).
ObjectMotionEdge ObjectMotion() {
  ObjectMotionEdge e;
  e.pose_prev = 1;
  e.pose_curr = 2;
  e.motion = 3;
  e.point = 4;
  e.information = kInformation3;
  return e;
}

KinematicEdge Kinematic() {
  KinematicEdge e;
  e.information = kInformation6;
  return e;
}

#define DYNSLAM_RESIDUAL_BENCHMARK(name, create)                          \
  void BM_##name##_Residual(benchmark::State& state) {                    \
    Evaluate(state, std::unique_ptr<ceres::CostFunction>(create), false); \
  }                                                                       \
  void BM_##name##_WithJacobians(benchmark::State& state) {               \
    Evaluate(state, std::unique_ptr<ceres::CostFunction>(create), true);  \
  }                                                                       \
  BENCHMARK(BM_##name##_Residual);                                        \
  BENCHMARK(BM_##name##_WithJacobians)

DYNSLAM_RESIDUAL_BENCHMARK(PosePrior,
                           MakeCost(Measured<PriorEdge>(GenericPose(5), kInformation6), kDefaults));
DYNSLAM_RESIDUAL_BENCHMARK(PoseBetween,
                           MakeCost(Measured<BetweenEdge>(GenericPose(6), kInformation6),
                                    kDefaults));
DYNSLAM_RESIDUAL_BENCHMARK(PointMeasurement,
                           MakeCost(Measured<PointEdge>(kMeasurement, kInformation3), kDefaults));
DYNSLAM_RESIDUAL_BENCHMARK(PointMotion,
                           MakeCost(Measured<MotionEdge>(kMeasurement, kInformation3), kDefaults));
DYNSLAM_RESIDUAL_BENCHMARK(ObjectPointMeasurement, MakeCost(ObjectPoint(), kDefaults));
DYNSLAM_RESIDUAL_BENCHMARK(ObjectPointMotion, MakeCost(ObjectMotion(), kDefaults));
DYNSLAM_RESIDUAL_BENCHMARK(ObjectKinematic, MakeCost(Kinematic(), kDefaults));
// The world-anchored forms the object-centric solves use by default (SolverOptions::
// world_anchored_object_points): anchored at a further pose, and at the edge's own pose.
DYNSLAM_RESIDUAL_BENCHMARK(AnchoredObjectPointMeasurement, MakeAnchoredCost(ObjectPoint(), 9).cost);
DYNSLAM_RESIDUAL_BENCHMARK(AnchoredObjectPointMotion,
                           MakeAnchoredCost(ObjectMotion(), kDefaults, 9).cost);
DYNSLAM_RESIDUAL_BENCHMARK(AnchoredObjectPointMotionAtOwnPose,
                           MakeAnchoredCost(ObjectMotion(), kDefaults, 1).cost);

void BM_ManifoldPlus(benchmark::State& state) {
  const SE3Manifold manifold;
  const Pose x = GenericPose(1);
  const double delta[6] = {1e-3, -2e-3, 5e-4, 0.01, 0.02, -0.03};
  double out[kPoseSize];
  for (auto _ : state) {
    manifold.Plus(x.data.data(), delta, out);
    benchmark::DoNotOptimize(out);
  }
}
BENCHMARK(BM_ManifoldPlus);

void BM_ManifoldPlusJacobian(benchmark::State& state) {
  const SE3Manifold manifold;
  const Pose x = GenericPose(1);
  double jacobian[kPoseSize * kTangentSize];
  for (auto _ : state) {
    manifold.PlusJacobian(x.data.data(), jacobian);
    benchmark::DoNotOptimize(jacobian);
  }
}
BENCHMARK(BM_ManifoldPlusJacobian);

}  // namespace
}  // namespace dynslam

BENCHMARK_MAIN();
