// A dynslam Graph as a GTSAM factor graph: one factor per edge (src/gtsam/factors.h and GTSAM's
// own prior/between factors), the variables as gtsam::Values.
#ifndef DYNSLAM_SRC_GTSAM_PROBLEM_H_
#define DYNSLAM_SRC_GTSAM_PROBLEM_H_

#include <string>
#include <vector>

#include <gtsam/geometry/Pose3.h>
#include <gtsam/nonlinear/NonlinearFactorGraph.h>
#include <gtsam/nonlinear/Values.h>

#include "dynslam/graph.h"
#include "dynslam/gtsam_backend.h"
#include "dynslam/solver.h"
#include "dynslam/solver_options.h"
#include "dynslam/status.h"

namespace dynslam::gtsam_backend {

gtsam::Pose3 ToGtsam(const Pose& pose);
Pose FromGtsam(const gtsam::Pose3& pose);

struct Problem {
  gtsam::NonlinearFactorGraph factors;
  std::vector<EdgeKind> kinds;  // of each factor; the --fix-first constraint has none (last)
  gtsam::Values values;         // the variables: vertices in an edge, not constant by role
  std::vector<VertexId> held_constant;  // unused vertices, then the --fix-first pose
  std::vector<std::string> warnings;
};

// The factor graph of `graph` with `profile`'s pose-edge Jacobians and `options`' kernels and
// SPEC §7 residuals; an Error for a graph without a prior unless options.fix_first (SPEC §1.7).
Expected<Problem> BuildProblem(const Graph& graph, const GtsamProfile& profile,
                               const SolverOptions& options);

// The SPEC §1.5 cost of each kind at `values`.
CostByKind CostsByKind(const Problem& problem, const gtsam::Values& values);

// Writes the variables of `values` back into `graph`'s vertices.
void WriteBack(const gtsam::Values& values, Graph* graph);

}  // namespace dynslam::gtsam_backend

#endif  // DYNSLAM_SRC_GTSAM_PROBLEM_H_
