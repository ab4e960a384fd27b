// Where the tests find the GTSAM reference set (SPEC §6) and what is in it.
//
// The full set is `DYNSLAM_REFERENCE_DIR` (a CMake cache path, ../shared/reference by default);
// a fresh clone without it falls back to the embedded subset in data/reference/.
#ifndef DYNSLAM_TESTS_REFERENCE_UTIL_H_
#define DYNSLAM_TESTS_REFERENCE_UTIL_H_

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <ostream>
#include <string>
#include <vector>

#include "dynslam/graph.h"
#include "src/json_io.h"
#include "dynslam/se3.h"

namespace dynslam::testing {

// `shared` when it is a directory, else the embedded copy data/<embedded>.
inline std::string SharedOrEmbedded(const char* shared, const char* embedded) {
  if (std::filesystem::is_directory(shared)) return shared;
  return (std::filesystem::path(DYNSLAM_SOURCE_DIR) / "data" / embedded).string();
}

inline std::string ReferenceDir() { return SharedOrEmbedded(DYNSLAM_REFERENCE_DIR, "reference"); }

// The hybrid reference solves (SPEC §3.6), ../shared/reference_hybrid or data/reference_hybrid.
inline std::string ReferenceHybridDir() {
  return SharedOrEmbedded(DYNSLAM_REFERENCE_HYBRID_DIR, "reference_hybrid");
}

// One solved graph of the reference set: <scene>/graphs/<name>.g2o with its GTSAM solves in
// <scene>/gtsam/<formulation>/<profile>/.
struct ReferenceGraph {
  std::string scene;
  std::string formulation;  // wc, oc_a, …, or pose_graph
  std::string graph_path;

  std::string ProfileDir(const std::string& profile) const {
    return (std::filesystem::path(ReferenceDir()) / scene / "gtsam" / formulation / profile)
        .string();
  }
  // For gtest parameter names: letters, digits and underscores only.
  std::string TestName() const {
    std::string name = scene + "_" + formulation;
    std::replace_if(name.begin(), name.end(), [](char c) { return !std::isalnum(c); }, '_');
    return name;
  }
};

// gtest prints parameters with this (instead of their bytes).
inline void PrintTo(const ReferenceGraph& graph, std::ostream* out) { *out << graph.graph_path; }

inline std::vector<ReferenceGraph> ReferenceGraphs() {
  std::vector<ReferenceGraph> graphs;
  const std::filesystem::path root(ReferenceDir());
  std::error_code ec;
  for (const auto& scene : std::filesystem::directory_iterator(root, ec)) {
    const std::filesystem::path graph_dir = scene.path() / "graphs";
    if (!std::filesystem::is_directory(graph_dir)) continue;
    for (const auto& file : std::filesystem::directory_iterator(graph_dir)) {
      if (file.path().extension() != ".g2o") continue;
      graphs.push_back({scene.path().filename().string(), file.path().stem().string(),
                        file.path().string()});
    }
  }
  std::sort(graphs.begin(), graphs.end(), [](const ReferenceGraph& a, const ReferenceGraph& b) {
    return a.graph_path < b.graph_path;
  });
  return graphs;
}

// Pose residuals whose rotation lies in GTSAM's approximate near-π Logmap branch
// (trace(R) + 1 < 1e-3, i.e. θ > π − 0.0316): there GTSAM's cost differs from the exact SPEC cost
// by more than rounding (docs/SPEC_NOTES.md).
inline int ResidualsInGtsamNearPiBranch(const Graph& graph) {
  const double near_pi_angle = M_PI - std::acos(1 - 0.5e-3);
  auto near_pi = [&](const Pose& error) { return RotationAngle(error) > near_pi_angle; };
  int count = 0;
  for (const PriorEdge& e : graph.Edges<PriorEdge>()) {
    count += near_pi(Compose(Inverse(e.measurement), graph.Find(e.pose)->pose()));
  }
  for (const BetweenEdge& e : graph.Edges<BetweenEdge>()) {
    count += near_pi(Compose(Inverse(e.measurement),
                             Compose(Inverse(graph.Find(e.from)->pose()), graph.Find(e.to)->pose())));
  }
  for (const KinematicEdge& e : graph.Edges<KinematicEdge>()) {
    count += near_pi(Compose(Inverse(graph.Find(e.pose_curr)->pose()),
                             Compose(graph.Find(e.motion)->pose(), graph.Find(e.pose_prev)->pose())));
  }
  return count;
}

// What the remaining-χ² stopping rule bounds (docs/SOLVER.md): the χ² of a final cost above the
// optimum of the tight_exact solve in `tight_exact_dir`, twice the cost difference. NaN when its
// summary.json cannot be read (so a bound on it fails).
inline double Chi2AboveTightExact(double final_cost, const std::string& tight_exact_dir) {
  Expected<JsonValue> summary =
      ReadJsonFile((std::filesystem::path(tight_exact_dir) / "summary.json").string());
  return summary.ok() ? 2 * (final_cost - NumberAt(*summary, {"final_cost"})) : std::nan("");
}

inline double RelativeDifference(double value, double reference) {
  return std::abs(value - reference) / std::max(std::abs(reference), 1e-300);
}

}  // namespace dynslam::testing

#endif  // DYNSLAM_TESTS_REFERENCE_UTIL_H_
