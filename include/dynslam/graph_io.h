// Reading and writing graph files (SPEC §1). No Ceres.
//
// Reading checks every bad input of SPEC §1.6 and returns an Error naming the file, the line
// and the problem; it never aborts. 6×6 information is permuted from the file's g2o order
// (translation first) to tangent order [ω; ρ] exactly once here, and back on writing (§1.2).
// Quaternions whose norm differs from 1 by more than 1e-12 are normalised (SPEC §0). Writing
// uses the shortest form that reads back exactly, so read → write → read is bit-exact. After
// reading, roles are assigned (graph.h, AssignRoles).
#ifndef DYNSLAM_GRAPH_IO_H_
#define DYNSLAM_GRAPH_IO_H_

#include <cstdint>
#include <iosfwd>
#include <map>
#include <string>
#include <vector>

#include "dynslam/graph.h"
#include "dynslam/status.h"

namespace dynslam {

struct ReadOptions {
  // SPEC §1.6: an unknown tag is an error unless this is set; then each skipped tag is counted.
  bool skip_unknown_tags = false;
  // SPEC §7 item 1 (the released code's reading, never a default): 6×6 information taken as
  // already in tangent order [ω; ρ], without the permutation of SPEC §1.2.
  bool information_in_tangent_order = false;
  // An information matrix that is not numerically positive definite (SPEC §1.1) is an error;
  // with this set it is replaced by the nearest symmetric matrix whose eigenvalues are at least
  // 1e-9 × the largest (eigenvalues clamped), and its line is reported. A matrix with no positive
  // eigenvalue or a non-finite entry stays an error. docs/SPEC_NOTES.md.
  bool repair_information = false;
};

struct ReadReport {
  std::map<std::string, int64_t> skipped_tags;  // tag → number of lines skipped
  std::vector<int64_t> repaired_information_lines;  // lines whose information was repaired
  int64_t lines = 0;
};

// Reads `path`. `report` (optional) receives what was skipped.
Expected<Graph> ReadGraph(const std::string& path, const ReadOptions& options = {},
                          ReadReport* report = nullptr);
// Reads from a stream; `name` is used in error messages in place of a file name.
Expected<Graph> ReadGraph(std::istream& in, const std::string& name,
                          const ReadOptions& options = {}, ReadReport* report = nullptr);

// Writes in the order of SPEC §3.4: LABEL_FORMULATION, vertices by ascending id, edges grouped
// by kind (§1.5 order) and sorted by their vertex ids in field order, labels by ascending id.
// Requires roles assigned.
Status WriteGraph(const Graph& graph, const std::string& path);
void WriteGraph(const Graph& graph, std::ostream& out);
std::string GraphText(const Graph& graph);  // what WriteGraph writes

}  // namespace dynslam

#endif  // DYNSLAM_GRAPH_IO_H_
