// The conventions before any solve (issue: core, SPEC §0, §1.2, §1.5): for every reference graph,
// the SPEC cost at the file's values equals GTSAM's `initial_cost` (tight profile) to 1e-9
// relative, in total and per edge kind. GTSAM's numbers are independent of this code.
#include <gtest/gtest.h>

#include "dynslam/graph_io.h"
#include "dynslam/json.h"
#include "dynslam/solver.h"
#include "reference_util.h"

namespace dynslam {
namespace {

using testing::ReferenceGraph;

class InitialCostTest : public ::testing::TestWithParam<ReferenceGraph> {};

TEST_P(InitialCostTest, MatchesGtsamInTotalAndPerKind) {
  const ReferenceGraph& reference = GetParam();
  Expected<Json> summary = Json::ReadFile(reference.ProfileDir("tight") + "/summary.json");
  ASSERT_TRUE(summary.ok()) << summary.error().ToString();
  Expected<Graph> graph = ReadGraph(reference.graph_path);
  ASSERT_TRUE(graph.ok()) << graph.error().ToString();
  Expected<CostByKind> cost = EvaluateCost(*graph);
  ASSERT_TRUE(cost.ok()) << cost.error().ToString();

  const double expected_total = summary->Find("initial_cost")->number();
  EXPECT_LE(testing::RelativeDifference(TotalCost(*cost), expected_total), 1e-9)
      << "total " << TotalCost(*cost) << " vs GTSAM " << expected_total;
  for (const EdgeKind kind : kAllEdgeKinds) {
    const Json* expected = summary->FindPath({"cost_by_kind", "initial", EdgeKindName(kind)});
    ASSERT_NE(expected, nullptr) << EdgeKindName(kind);
    const double ours = (*cost)[static_cast<int>(kind)];
    if (expected->number() == 0) {
      EXPECT_EQ(ours, 0) << EdgeKindName(kind);
    } else {
      EXPECT_LE(testing::RelativeDifference(ours, expected->number()), 1e-9)
          << EdgeKindName(kind) << ": " << ours << " vs GTSAM " << expected->number();
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Reference, InitialCostTest,
                         ::testing::ValuesIn(testing::ReferenceGraphs()),
                         [](const auto& info) { return info.param.TestName(); });
GTEST_ALLOW_UNINSTANTIATED_PARAMETERIZED_TEST(InitialCostTest);

}  // namespace
}  // namespace dynslam
