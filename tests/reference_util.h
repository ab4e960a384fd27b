// Where the tests find the GTSAM reference set (SPEC §6) and what is in it.
//
// The full set is `DYNSLAM_REFERENCE_DIR` (a CMake cache path, ../shared/reference by default);
// a fresh clone without it falls back to the embedded subset in data/reference/.
#ifndef DYNSLAM_TESTS_REFERENCE_UTIL_H_
#define DYNSLAM_TESTS_REFERENCE_UTIL_H_

#include <algorithm>
#include <filesystem>
#include <ostream>
#include <string>
#include <vector>

#include "dynslam/json.h"

namespace dynslam::testing {

inline std::string ReferenceDir() {
  const std::filesystem::path shared(DYNSLAM_REFERENCE_DIR);
  if (std::filesystem::is_directory(shared)) return shared.string();
  return (std::filesystem::path(DYNSLAM_SOURCE_DIR) / "data" / "reference").string();
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

inline double RelativeDifference(double value, double reference) {
  return std::abs(value - reference) / std::max(std::abs(reference), 1e-300);
}

}  // namespace dynslam::testing

#endif  // DYNSLAM_TESTS_REFERENCE_UTIL_H_
