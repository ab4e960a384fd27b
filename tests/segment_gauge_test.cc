// The gauge of an object segment (src/segment_gauge.h, docs/CONVERGENCE.md §7) on the embedded
// synthetic front end: moving a segment's object poses by L → L·G and its object-frame points by
// m → G⁻¹·m changes only the object prior's cost in oc_a, and Snap zeroes that cost.
#include "src/segment_gauge.h"

#include <map>
#include <string>

#include <gtest/gtest.h>

#include "dynslam/formulation.h"
#include "dynslam/graph_io.h"
#include "dynslam/se3.h"
#include "dynslam/solver.h"
#include "convergence_rows.h"

namespace dynslam {
namespace {

Graph Build(Formulation formulation) {
  Expected<Graph> front_end =
      ReadGraph(std::string(DYNSLAM_SOURCE_DIR) + "/data/reference/synthetic/frontend.g2o");
  EXPECT_TRUE(front_end.ok()) << front_end.error().ToString();
  Expected<Graph> built =
      BuildFormulation(*front_end, formulation, BuildOptions(), nullptr, nullptr);
  EXPECT_TRUE(built.ok()) << built.error().ToString();
  return built.ok() ? std::move(*built) : Graph{};
}

// The blocks of a graph in vertex order, every vertex movable, object points in the object frame
// (the chart with object-frame point variables).
struct Blocks {
  explicit Blocks(const Graph& graph) {
    for (const auto& [id, vertex] : graph.vertices) {
      index.emplace(id, values.size());
      values.push_back(vertex.value);
    }
  }
  SegmentGauges::Layout Layout() const {
    return {[this](VertexId id) { return index.at(id); }, [](VertexId) { return true; },
            [](VertexId) { return false; }};
  }
  void WriteTo(Graph* graph) const {
    for (auto& [id, vertex] : graph->vertices) vertex.value = values[index.at(id)];
  }
  std::map<VertexId, size_t> index;
  SegmentGauges::Values values;
};

CostByKind Cost(const Graph& graph) {
  Expected<CostByKind> cost = EvaluateCost(graph);
  EXPECT_TRUE(cost.ok()) << cost.error().ToString();
  return cost.ok() ? *cost : CostByKind{};
}

// Every object pose right-multiplied by g, every object-frame point by g⁻¹: written out here,
// independently of SegmentGauges.
void MoveAllObjects(const Pose& g, Graph* graph) {
  for (auto& [id, vertex] : graph->vertices) {
    if (vertex.label.role == Role::kObjectPose) vertex.set_pose(Compose(vertex.pose(), g));
    if (vertex.label.role == Role::kObjectPoint) {
      vertex.point() = Transform(Inverse(g), vertex.point());
    }
  }
}

int Count(const Graph& graph, EdgeKind kind) {
  return static_cast<int>(CountEdgesByKind(graph)[static_cast<int>(kind)]);
}

TEST(SegmentGaugeTest, FindsOneSegmentPerObjectPriorInObjectCentricGraphs) {
  for (const Formulation formulation :
       {Formulation::kObjectCentricA, Formulation::kObjectCentricB,
        Formulation::kObjectCentricC}) {
    const Graph graph = Build(formulation);
    const Blocks blocks(graph);
    const int priors = Count(graph, EdgeKind::kObjectPrior);
    ASSERT_GT(priors, 0) << FormulationName(formulation);
    EXPECT_EQ(SegmentGauges::Find(graph, blocks.Layout()).size(), static_cast<size_t>(priors))
        << FormulationName(formulation);
  }
}

// wc and hy have no object poses (hy's object points hang off hybrid motions and a constant
// embedded frame), so nothing to move; nor is a segment with a vertex held constant moved.
TEST(SegmentGaugeTest, NoSegmentsInWcOrHyOrWhenAVertexIsHeld) {
  for (const Formulation formulation : {Formulation::kWorldCentric, Formulation::kHybrid}) {
    const Graph graph = Build(formulation);
    EXPECT_TRUE(SegmentGauges::Find(graph, Blocks(graph).Layout()).empty())
        << FormulationName(formulation);
  }
  const Graph oc_a = Build(Formulation::kObjectCentricA);
  const Blocks blocks(oc_a);
  SegmentGauges::Layout held = blocks.Layout();
  held.movable = [](VertexId) { return false; };
  EXPECT_TRUE(SegmentGauges::Find(oc_a, held).empty());
}

// The premise: in oc_a a segment's gauge changes no residual but the object prior's.
TEST(SegmentGaugeTest, GaugeChangesOnlyTheObjectPriorInOcA) {
  Graph graph = Build(Formulation::kObjectCentricA);
  const CostByKind before = Cost(graph);
  EXPECT_LT(before[static_cast<int>(EdgeKind::kObjectPrior)], 1e-20);  // priors at their start
  Vector6d xi;
  xi << 0.2, -0.1, 0.3, 1.5, -0.7, 0.4;
  MoveAllObjects(Exp(xi), &graph);
  const CostByKind after = Cost(graph);
  for (const EdgeKind kind : kAllEdgeKinds) {
    const int k = static_cast<int>(kind);
    if (kind == EdgeKind::kObjectPrior) {
      EXPECT_GT(after[k], 1.0);
    } else {
      EXPECT_NEAR(after[k], before[k], 1e-9 * std::max(1.0, before[k])) << EdgeKindName(kind);
    }
  }
}

TEST(SegmentGaugeTest, SnapZeroesThePriorsAndRestoresEveryOtherCostInOcA) {
  Graph graph = Build(Formulation::kObjectCentricA);
  const CostByKind start = Cost(graph);
  Vector6d xi;
  xi << -0.3, 0.25, 0.1, -2.0, 0.5, 1.0;
  MoveAllObjects(Exp(xi), &graph);
  Blocks blocks(graph);
  const SegmentGauges gauges = SegmentGauges::Find(graph, blocks.Layout());
  const double prior_cost = gauges.PriorCost(blocks.values);
  EXPECT_NEAR(prior_cost, Cost(graph)[static_cast<int>(EdgeKind::kObjectPrior)],
              1e-9 * prior_cost);
  gauges.Snap(&blocks.values);
  EXPECT_LT(gauges.PriorCost(blocks.values), 1e-20);
  blocks.WriteTo(&graph);
  const CostByKind snapped = Cost(graph);
  for (const EdgeKind kind : kAllEdgeKinds) {
    const int k = static_cast<int>(kind);
    EXPECT_NEAR(snapped[k], start[k], 1e-9 * std::max(1.0, start[k])) << EdgeKindName(kind);
  }
}

// From the optimum with every segment moved along its gauge (only the priors pay) and heavy
// damping, LM alone creeps back; with the option on the solve moves the gauges, records each
// move as a row of lambda 0 that lowers the cost, counted apart from the linear solves, takes
// fewer steps, and ends within remaining_chi2 of the tight rule's optimum.
TEST(SegmentGaugeTest, GaugeMovesCutTheCreepAlongTheGauge) {
  Graph optimum = Build(Formulation::kObjectCentricA);
  Expected<SolveReport> tight = Solve(TightRule(SolverOptions{}), &optimum);
  ASSERT_TRUE(tight.ok()) << tight.error().ToString();
  Vector6d xi;
  xi << 0.05, -0.02, 0.03, 0.4, -0.2, 0.1;
  Graph start = optimum;
  MoveAllObjects(Exp(xi), &start);
  auto solve = [&](bool moves) {
    SolverOptions options;
    options.gauge_moves = moves;
    options.initial_lambda = 1e-2;
    Graph graph = start;
    Expected<SolveReport> report = Solve(options, &graph);
    EXPECT_TRUE(report.ok()) << report.error().ToString();
    return *report;
  };
  const SolveReport without = solve(false), with = solve(true);
  EXPECT_EQ(without.gauge_moves, 0);
  EXPECT_GT(with.gauge_moves, 0);
  EXPECT_LT(with.steps, without.steps);
  for (const SolveReport& report : {without, with}) {
    testing::ExpectRowsFollowSpecSection4(report);  // moves: accepted rows of lambda 0, counted
    EXPECT_LE(2 * (report.final_cost - tight->final_cost), SolverOptions{}.remaining_chi2);
    EXPECT_GE(report.final_cost, tight->final_cost * (1 - 1e-9));
  }
}

}  // namespace
}  // namespace dynslam
