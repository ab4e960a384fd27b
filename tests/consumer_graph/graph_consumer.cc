// Reads a graph file and builds a formulation with the graph layer alone (no Ceres). Exit 0 on
// success.
#include <cstdio>

#include "dynslam/formulation.h"
#include "dynslam/graph_io.h"

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: graph_consumer FRONTEND.g2o\n");
    return 2;
  }
  dynslam::Expected<dynslam::Graph> front_end = dynslam::ReadGraph(argv[1]);
  if (!front_end.ok()) {
    std::fprintf(stderr, "%s\n", front_end.error().ToString().c_str());
    return 2;
  }
  dynslam::BuildReport report;
  dynslam::Expected<dynslam::Graph> built = dynslam::BuildFormulation(
      *front_end, dynslam::Formulation::kObjectCentricB, dynslam::BuildOptions{}, nullptr, &report);
  if (!built.ok()) {
    std::fprintf(stderr, "%s\n", built.error().ToString().c_str());
    return 1;
  }
  std::printf("oc_b: %zu vertices, %lld edges\n", built->vertices.size(),
              static_cast<long long>(built->NumEdges()));
  return 0;
}
