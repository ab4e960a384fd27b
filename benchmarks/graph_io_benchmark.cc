// Google Benchmark: reading and writing a graph file (issue 22 item 3, the process around a
// solve). Run: build/release/benchmarks/graph_io_benchmark [GRAPH] [--benchmark_...]
// GRAPH defaults to the reference parking-garage pose graph (DYNSLAM_REFERENCE_DIR).
#include <benchmark/benchmark.h>

#include <sstream>
#include <string>

#include "dynslam/graph_io.h"

namespace dynslam {
namespace {

std::string graph_path = DYNSLAM_REFERENCE_DIR "/posegraph_parking-garage/graphs/pose_graph.g2o";

void BM_ReadGraph(benchmark::State& state) {
  for (auto _ : state) {
    Expected<Graph> graph = ReadGraph(graph_path);
    if (!graph.ok()) {
      state.SkipWithError(graph.error().ToString().c_str());
      return;
    }
    benchmark::DoNotOptimize(graph->vertices.size());
  }
}
BENCHMARK(BM_ReadGraph)->Unit(benchmark::kMillisecond);

void BM_WriteGraph(benchmark::State& state) {
  Expected<Graph> graph = ReadGraph(graph_path);
  if (!graph.ok()) {
    state.SkipWithError(graph.error().ToString().c_str());
    return;
  }
  for (auto _ : state) {
    std::ostringstream out;
    WriteGraph(*graph, out);
    benchmark::DoNotOptimize(out.tellp());
  }
}
BENCHMARK(BM_WriteGraph)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace dynslam

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (argc > 1) dynslam::graph_path = argv[1];
  benchmark::RunSpecifiedBenchmarks();
  return 0;
}
