// Simulated front ends through the formulation builder (SPEC §3) and the solver's cost
// (SPEC §1.5): without noise, the initial values of a simulated front end are the truth, and the
// cost of every formulation built from it is 0 for every edge kind but smoothing (whose Z = I
// is the constant-motion assumption: at the truth its residual is the true change of motion;
// likewise hy's smoothing edge, which has no measurement, SPEC §3.6).
#include <cmath>

#include <gtest/gtest.h>

#include "dynslam/formulation.h"
#include "dynslam/kitti.h"
#include "dynslam/metrics.h"
#include "dynslam/simulate.h"
#include "dynslam/solver.h"

namespace dynslam {
namespace {

void CheckFormulationsExactAtTruth(const Scene& scene) {
  SimulateOptions options;
  options.noise = false;
  Expected<SimulatedScene> sim = Simulate(scene, options);
  ASSERT_TRUE(sim.ok()) << sim.error().ToString();
  double smoothing_cost = -1;
  int64_t smoothing_edges = -1;
  for (const Formulation formulation : kAllFormulations) {
    SCOPED_TRACE(FormulationName(formulation));
    BuildReport report;
    Expected<Graph> built =
        BuildFormulation(sim->graph, formulation, BuildOptions(), &sim->ground_truth, &report);
    ASSERT_TRUE(built.ok()) << built.error().ToString();
    Expected<CostByKind> cost = EvaluateCost(*built);
    ASSERT_TRUE(cost.ok()) << cost.error().ToString();
    const auto counts = CountEdgesByKind(*built);
    for (const EdgeKind kind : kAllEdgeKinds) {
      const int i = static_cast<int>(kind);
      if (kind == EdgeKind::kSmoothing || kind == EdgeKind::kHybridSmoothing) continue;
      EXPECT_LT((*cost)[i], 1e-12 * std::max<int64_t>(counts[i], 1)) << EdgeKindName(kind);
    }
    EXPECT_GT(counts[static_cast<int>(EdgeKind::kMotion)] +
                  counts[static_cast<int>(EdgeKind::kObjectMotion)] +
                  counts[static_cast<int>(EdgeKind::kKinematic)] +
                  counts[static_cast<int>(EdgeKind::kHybridPoint)],
              0);
    if (formulation == Formulation::kHybrid) {  // one re-expressed edge per front-end edge kept
      EXPECT_EQ(counts[static_cast<int>(EdgeKind::kHybridSmoothing)], smoothing_edges);
      EXPECT_EQ(counts[static_cast<int>(EdgeKind::kSmoothing)], 0);
      continue;
    }
    // Identical data in every formulation: the same smoothing edges, the same cost.
    smoothing_edges = counts[static_cast<int>(EdgeKind::kSmoothing)];
    const double smoothing = (*cost)[static_cast<int>(EdgeKind::kSmoothing)];
    if (smoothing_cost < 0) smoothing_cost = smoothing;
    EXPECT_NEAR(smoothing, smoothing_cost, 1e-9 * smoothing_cost);
  }
  EXPECT_GT(smoothing_cost, 0);
}

TEST(SimulateFormulations, SyntheticCostIsZeroAtTruth) {
  CheckFormulationsExactAtTruth(MakeSyntheticScene(SimulateOptions()));
}

TEST(SimulateFormulations, Kitti0003CostIsZeroAtTruth) {
  Expected<KittiSequence> seq =
      ReadKittiSequence(std::string(DYNSLAM_SOURCE_DIR) + "/data/kitti_tracking", "0003");
  ASSERT_TRUE(seq.ok()) << seq.error().ToString();
  SimulateOptions options;
  options.last_frame = 60;
  Expected<Scene> scene = MakeKittiScene(*seq, options);
  ASSERT_TRUE(scene.ok()) << scene.error().ToString();
  CheckFormulationsExactAtTruth(*scene);
}

// Issue 20: the default object start (SPEC §3.3 `motion`) lands where the ground-truth start does.
// KITTI 0004 frames 0:60, seed 1, oc_b: the scene where the former default (`align`) stopped at
// cost 40 718 after 500 steps, 2.3× the optimum, with 1.10° object motion error against 0.48°.
TEST(SimulateFormulations, Kitti0004DefaultObjectStartReachesTheTruthStartsOptimum) {
  Expected<KittiSequence> seq =
      ReadKittiSequence(std::string(DYNSLAM_SOURCE_DIR) + "/data/kitti_tracking", "0004");
  ASSERT_TRUE(seq.ok()) << seq.error().ToString();
  SimulateOptions options;
  options.last_frame = 60;
  options.seed = 1;
  Expected<Scene> scene = MakeKittiScene(*seq, options);
  ASSERT_TRUE(scene.ok()) << scene.error().ToString();
  Expected<SimulatedScene> sim = Simulate(*scene, options);
  ASSERT_TRUE(sim.ok()) << sim.error().ToString();
  auto solve = [&](ObjectInit rule) {
    BuildOptions build;
    build.object_init = rule;
    Expected<Graph> graph = BuildFormulation(sim->graph, Formulation::kObjectCentricB, build,
                                             &sim->ground_truth, nullptr);
    EXPECT_TRUE(graph.ok());
    Expected<SolveReport> report = Solve(SolverOptions{}, &*graph);
    EXPECT_TRUE(report.ok());
    EXPECT_EQ(report->termination, "convergence") << ObjectInitName(rule);
    return std::make_pair(report->final_cost, ComputeMetrics(*graph, sim->ground_truth));
  };
  const auto [default_cost, default_metrics] = solve(BuildOptions{}.object_init);
  const auto [truth_cost, truth_metrics] = solve(ObjectInit::kTruth);
  EXPECT_LE(default_cost, truth_cost * (1 + 1e-6));
  EXPECT_NEAR(default_metrics.object_motion.mean_rot_deg, truth_metrics.object_motion.mean_rot_deg,
              0.05 * truth_metrics.object_motion.mean_rot_deg);
  EXPECT_NEAR(default_metrics.object_motion.mean_trans_m, truth_metrics.object_motion.mean_trans_m,
              0.05 * truth_metrics.object_motion.mean_trans_m);
}

// Issue 21: `--density paper` builds whole sequences to the paper's Table I size. Sequence 0002,
// the smallest: the paper's graphs have 19 034 (object-centric) and 38 450 (world-centric)
// variables; ours must be within 25 % (measured: 18 874 and 38 370).
TEST(SimulateFormulations, PaperDensityBuildsTheTableIVariableCounts) {
  Expected<KittiSequence> seq =
      ReadKittiSequence(std::string(DYNSLAM_SOURCE_DIR) + "/data/kitti_tracking", "0002");
  ASSERT_TRUE(seq.ok()) << seq.error().ToString();
  SimulateOptions options;
  options.seed = 1;
  ASSERT_TRUE(UsePaperDensity("0002", &options));
  EXPECT_FALSE(UsePaperDensity("0007", &options));
  Expected<Scene> scene = MakeKittiScene(*seq, options);
  ASSERT_TRUE(scene.ok()) << scene.error().ToString();
  Expected<SimulatedScene> sim = Simulate(*scene, options);
  ASSERT_TRUE(sim.ok()) << sim.error().ToString();
  for (const auto& [formulation, paper] :
       {std::pair{Formulation::kObjectCentricB, 19034.0}, {Formulation::kWorldCentric, 38450.0}}) {
    Expected<Graph> graph =
        BuildFormulation(sim->graph, formulation, BuildOptions{}, &sim->ground_truth, nullptr);
    ASSERT_TRUE(graph.ok()) << graph.error().ToString();
    EXPECT_NEAR(static_cast<double>(graph->vertices.size()), paper, 0.25 * paper)
        << FormulationName(formulation);
  }
}

}  // namespace
}  // namespace dynslam
