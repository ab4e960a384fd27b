// Simulated front ends through the formulation builder (SPEC §3) and the solver's cost
// (SPEC §1.5): without noise, the initial values of a simulated front end are the truth, and the
// cost of every formulation built from it is 0 for every edge kind but smoothing (whose Z = I
// is the constant-motion assumption: at the truth its residual is the true change of motion).
#include <cmath>

#include <gtest/gtest.h>

#include "dynslam/formulation.h"
#include "dynslam/kitti.h"
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
      if (kind == EdgeKind::kSmoothing) continue;
      EXPECT_LT((*cost)[i], 1e-12 * std::max<int64_t>(counts[i], 1)) << EdgeKindName(kind);
    }
    EXPECT_GT(counts[static_cast<int>(EdgeKind::kMotion)] +
                  counts[static_cast<int>(EdgeKind::kObjectMotion)] +
                  counts[static_cast<int>(EdgeKind::kKinematic)],
              0);
    // Identical data in every formulation: the same smoothing edges, the same cost.
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

}  // namespace
}  // namespace dynslam
