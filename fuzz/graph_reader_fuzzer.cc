// libFuzzer target: arbitrary bytes as a graph file. Reading must never crash; a graph that
// reads must write and read back to the same counts, and must build into every formulation or
// fail with an Error (never an exception or a crash). Build and run: scripts/fuzz [SECONDS].
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <sstream>
#include <string>

#include "dynslam/formulation.h"
#include "dynslam/graph_io.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  std::istringstream in(text);
  dynslam::ReadOptions options;
  options.skip_unknown_tags = size % 2 == 0;  // both modes, decided by the input
  dynslam::Expected<dynslam::Graph> graph = dynslam::ReadGraph(in, "fuzz", options);
  if (!graph.ok()) return 0;

  std::ostringstream out;
  dynslam::WriteGraph(*graph, out);
  std::istringstream again(out.str());
  dynslam::Expected<dynslam::Graph> reread = dynslam::ReadGraph(again, "written");
  // Internal invariants: what we wrote, we read back, with the same counts.
  if (!reread.ok() || reread->vertices.size() != graph->vertices.size() ||
      reread->NumEdges() != graph->NumEdges()) {
    std::abort();
  }
  for (const dynslam::Formulation f : dynslam::kAllFormulations) {
    dynslam::BuildOptions build_options;
    build_options.min_object_frames = 2;
    dynslam::Expected<dynslam::Graph> built =
        dynslam::BuildFormulation(*graph, f, build_options, nullptr, nullptr);
    (void)built;
  }
  return 0;
}
