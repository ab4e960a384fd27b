// NEES (include/dynslam/consistency.h): χ² quantiles against printed tables, and the check
// itself shown to work on simulated scenes whose noise is exactly the edges' information.
#include "dynslam/consistency.h"

#include <gtest/gtest.h>

#include "dynslam/formulation.h"
#include "dynslam/simulate.h"

namespace dynslam {
namespace {

TEST(ConsistencyTest, ChiSquaredQuantilesMatchTheTables) {
  // Abramowitz and Stegun, Table 26.8.
  EXPECT_NEAR(ChiSquaredQuantile(0.975, 60), 83.2976, 83.2976 * 1e-3);
  EXPECT_NEAR(ChiSquaredQuantile(0.025, 60), 40.4817, 40.4817 * 1e-3);
  EXPECT_NEAR(ChiSquaredQuantile(0.975, 100), 129.561, 129.561 * 1e-3);
  EXPECT_NEAR(ChiSquaredQuantile(0.025, 100), 74.2219, 74.2219 * 1e-3);
}

struct SolvedScene {
  Graph graph;
  SolveReport report;
  GroundTruth truth;
};

// How the edges' information is made the noise they have. By default the simulator puts the
// prior on the first camera at its true pose (no noise drawn) with information σ = prior_sigma,
// so σ → 0 (with the default 1e-3 the mean NEES below is 2.70, the covariance counting a prior
// uncertainty the errors do not have; docs/COVARIANCE.md). Or noise_every_edge draws it.
enum class Honest { kPriorSigmaToZero, kNoiseOnEveryEdge };

SolvedScene SolveSynthetic(uint64_t seed, bool noise,
                           Honest honest = Honest::kPriorSigmaToZero) {
  SimulateOptions options;
  options.synthetic = true;
  options.seed = seed;
  options.noise = noise;
  if (honest == Honest::kPriorSigmaToZero) options.prior_sigma = 1e-9;
  options.noise_every_edge = honest == Honest::kNoiseOnEveryEdge;
  Expected<SimulatedScene> scene = Simulate(MakeSyntheticScene(options), options);
  EXPECT_TRUE(scene.ok());
  BuildReport build;
  Expected<Graph> graph = BuildFormulation(scene->graph, Formulation::kWorldCentric,
                                           BuildOptions{}, &scene->ground_truth, &build);
  EXPECT_TRUE(graph.ok());
  Expected<SolveReport> report = Solve(TightRule(SolverOptions{}), &*graph);
  EXPECT_TRUE(report.ok());
  return {*graph, *report, scene->ground_truth};
}

VertexId LastCamera(const Graph& graph) {
  VertexId last = -1;
  int64_t frame = -1;
  for (const auto& [id, vertex] : graph.vertices) {
    if (vertex.label.role == Role::kCamera && vertex.label.frame > frame) {
      frame = vertex.label.frame;
      last = id;
    }
  }
  return last;
}

TEST(ConsistencyTest, WithoutNoiseTheSolveIsTheTruth) {
  SolvedScene s = SolveSynthetic(1, false);
  Expected<CovarianceReport> covariance =
      ComputeCovariances(s.graph, s.report, VerticesOfKinds(s.graph, {CovarianceKind::kCameras}));
  ASSERT_TRUE(covariance.ok());
  const Consistency c = ComputeConsistency(s.graph, *covariance, s.truth);
  EXPECT_EQ(c.camera.count, 30);
  EXPECT_LT(c.camera.mean, 1e-6);
}

// One camera per seed (the last, whose error is the accumulated drift), so that the NEES values
// are independent and their mean has the χ² band exactly: 30 seeds, χ²(180) / 30.
void ExpectCameraNeesOverSeedsWithinItsBand(Honest honest) {
  double sum = 0;
  const int seeds = 30;
  NeesMean last;
  for (int seed = 1; seed <= seeds; ++seed) {
    SolvedScene s = SolveSynthetic(seed, true, honest);
    Expected<CovarianceReport> covariance =
        ComputeCovariances(s.graph, s.report, {LastCamera(s.graph)});
    ASSERT_TRUE(covariance.ok());
    last = ComputeConsistency(s.graph, *covariance, s.truth).camera;
    ASSERT_EQ(last.count, 1);
    sum += last.mean;
  }
  const double mean = sum / seeds;
  EXPECT_GT(mean, ChiSquaredQuantile(0.025, 6.0 * seeds) / seeds);
  EXPECT_LT(mean, ChiSquaredQuantile(0.975, 6.0 * seeds) / seeds);
  ::testing::Test::RecordProperty("mean_camera_nees", std::to_string(mean));
  std::printf("mean NEES of the last camera over %d seeds: %.3f (band %.3f-%.3f)\n", seeds, mean,
              ChiSquaredQuantile(0.025, 6.0 * seeds) / seeds,
              ChiSquaredQuantile(0.975, 6.0 * seeds) / seeds);
}

TEST(ConsistencyTest, CameraNeesOverSeedsIsWithinItsBand) {
  ExpectCameraNeesOverSeedsWithinItsBand(Honest::kPriorSigmaToZero);
}

// The default prior σ with its noise drawn (simulate --noise-every-edge): honest too.
TEST(ConsistencyTest, CameraNeesWithNoiseOnEveryEdgeIsWithinItsBand) {
  ExpectCameraNeesOverSeedsWithinItsBand(Honest::kNoiseOnEveryEdge);
}

}  // namespace
}  // namespace dynslam
