// libFuzzer target: arbitrary bytes as a front-end file, built into every formulation and solved
// for a few steps. Nothing may crash or hang, and a solve that reports a usable result must hold
// finite values and a finite cost (no NaN in an output that claims success). Links Ceres (not
// instrumented: coverage and sanitizers see dynslam's code). Build and run: scripts/fuzz.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <sstream>
#include <string>

#include "dynslam/formulation.h"
#include "dynslam/graph_io.h"
#include "dynslam/solver.h"

namespace {

void AbortUnlessFiniteSolution(const dynslam::SolveReport& report, const dynslam::Graph& graph) {
  if (!report.usable) return;
  if (!std::isfinite(report.final_cost)) std::abort();
  for (const auto& [id, vertex] : graph.vertices) {
    for (const double v : vertex.value) {
      if (!std::isfinite(v)) std::abort();
    }
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  std::istringstream in(std::string(reinterpret_cast<const char*>(data), size));
  const dynslam::Expected<dynslam::Graph> front_end = dynslam::ReadGraph(in, "fuzz");
  if (!front_end.ok()) return 0;
  dynslam::SolverOptions options;
  options.max_iterations = 3;
  options.fix_first = true;  // a front end without a prior still solves
  for (const dynslam::Formulation f : dynslam::kAllFormulations) {
    dynslam::BuildOptions build_options;
    build_options.min_object_frames = 2;
    dynslam::Expected<dynslam::Graph> built =
        dynslam::BuildFormulation(*front_end, f, build_options, nullptr, nullptr);
    if (!built.ok()) continue;
    const dynslam::Expected<dynslam::SolveReport> report = dynslam::Solve(options, &*built);
    if (report.ok()) AbortUnlessFiniteSolution(*report, *built);
  }
  // The front end itself, as a graph file handed to `dynslam solve`.
  dynslam::Graph as_given = *front_end;
  const dynslam::Expected<dynslam::SolveReport> report = dynslam::Solve(options, &as_given);
  if (report.ok()) AbortUnlessFiniteSolution(*report, as_given);
  return 0;
}
