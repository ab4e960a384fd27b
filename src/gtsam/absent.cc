// The GTSAM backend's entry points in a build without GTSAM (DYNSLAM_WITH_GTSAM off): each says
// how to get it.
#include "dynslam/gtsam_backend.h"

namespace dynslam {

bool GtsamBackendBuilt() { return false; }

Expected<SolveReport> SolveWithGtsam(const GtsamProfile&, const SolverOptions&, Graph*) {
  return Error{"", 0, GtsamBackendMissingMessage()};
}

Expected<CovarianceReport> GtsamCovariances(const Graph&, const GtsamProfile&,
                                            const SolverOptions&, const std::vector<VertexId>&) {
  return Error{"", 0, GtsamBackendMissingMessage()};
}

}  // namespace dynslam
