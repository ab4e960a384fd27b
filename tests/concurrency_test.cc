// Solves run at the same time in one process give bit-identical results to the same solves run
// one after another (issue 44): eight different graphs (the synthetic scene, two seeds, the four
// formulations whose default solve uses CHOLMOD's supernodal factorisation and so the BLAS),
// solved serially, then all eight at once on eight std::threads, three times over. A BLAS that
// is not safe for concurrent callers (Debian's serial OpenBLAS) makes some of them end at other
// costs or step counts.
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "dynslam/formulation.h"
#include "dynslam/simulate.h"
#include "dynslam/solver.h"

namespace dynslam {
namespace {

struct Outcome {
  double final_cost = 0;
  int steps = 0;
  std::vector<std::array<double, kPoseSize>> values;
};

std::vector<Graph> EightGraphs() {
  std::vector<Graph> graphs;
  for (const uint64_t seed : {1, 2}) {
    SimulateOptions options;
    options.synthetic = true;
    options.seed = seed;
    Expected<SimulatedScene> scene = Simulate(MakeSyntheticScene(options), options);
    EXPECT_TRUE(scene.ok());
    for (const char* name : {"wc", "oc_a", "oc_b", "oc_c"}) {
      Formulation formulation;
      EXPECT_TRUE(ParseFormulation(name, &formulation));
      BuildReport report;
      Expected<Graph> graph = BuildFormulation(scene->graph, formulation, BuildOptions{},
                                               &scene->ground_truth, &report);
      EXPECT_TRUE(graph.ok());
      graphs.push_back(*graph);
    }
  }
  return graphs;
}

Outcome SolveCopy(Graph graph) {
  Outcome outcome;
  Expected<SolveReport> report = Solve(SolverOptions{}, &graph);
  if (!report.ok()) return outcome;
  outcome.final_cost = report->final_cost;
  outcome.steps = report->steps;
  for (const auto& [id, vertex] : graph.vertices) outcome.values.push_back(vertex.value);
  return outcome;
}

void ExpectIdentical(const Outcome& serial, const Outcome& concurrent, size_t graph, int round) {
  EXPECT_EQ(serial.final_cost, concurrent.final_cost) << "graph " << graph << ", round " << round;
  EXPECT_EQ(serial.steps, concurrent.steps) << "graph " << graph << ", round " << round;
  EXPECT_TRUE(serial.values == concurrent.values) << "graph " << graph << ", round " << round;
}

TEST(ConcurrencyTest, EightConcurrentSolvesEqualTheSerialOnes) {
  const std::vector<Graph> graphs = EightGraphs();
  ASSERT_EQ(graphs.size(), 8u);
  std::vector<Outcome> serial;
  for (const Graph& graph : graphs) serial.push_back(SolveCopy(graph));
  for (const Outcome& outcome : serial) ASSERT_GT(outcome.steps, 0);

  for (int round = 0; round < 3; ++round) {
    std::vector<Outcome> concurrent(graphs.size());
    std::vector<std::thread> threads;
    for (size_t i = 0; i < graphs.size(); ++i) {
      threads.emplace_back([&, i] { concurrent[i] = SolveCopy(graphs[i]); });
    }
    for (std::thread& thread : threads) thread.join();
    for (size_t i = 0; i < graphs.size(); ++i) ExpectIdentical(serial[i], concurrent[i], i, round);
  }
}

}  // namespace
}  // namespace dynslam
