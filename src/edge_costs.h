// The solver's half of the edge table (graph_schema.h): the residual of each edge struct, over
// the edge's parameter vertices in field order (VertexIds(edge, true)). Adding an edge tag adds
// one MakeCost overload here.
#ifndef DYNSLAM_SRC_EDGE_COSTS_H_
#define DYNSLAM_SRC_EDGE_COSTS_H_

#include <ceres/cost_function.h>

#include "cost_functions/hybrid_point_error.h"
#include "cost_functions/hybrid_smoothing_error.h"
#include "cost_functions/object_kinematic_error.h"
#include "cost_functions/object_point_measurement_error.h"
#include "cost_functions/object_point_motion_error.h"
#include "cost_functions/object_point_motion_error_dsc.h"
#include "cost_functions/point_measurement_error.h"
#include "cost_functions/point_motion_error.h"
#include "cost_functions/point_motion_error_dsc.h"
#include "cost_functions/pose_between_error.h"
#include "cost_functions/pose_prior_error.h"
#include "dynslam/graph_schema.h"
#include "dynslam/solver.h"

namespace dynslam {

inline ceres::CostFunction* MakeCost(const PriorEdge& e, const SolverOptions&) {
  return PosePriorError::Create(e.measurement, e.information);
}

inline ceres::CostFunction* MakeCost(const BetweenEdge& e, const SolverOptions&) {
  return PoseBetweenError::Create(e.measurement, e.information);
}

inline ceres::CostFunction* MakeCost(const PointEdge& e, const SolverOptions&) {
  return PointMeasurementError::Create(e.measurement, e.information);
}

// SPEC §7 item 2 replaces the residual.
inline ceres::CostFunction* MakeCost(const MotionEdge& e, const SolverOptions& options) {
  return options.dsc_motion_residual ? PointMotionErrorDsc::Create(options.dsc_motion_sigma)
                                     : PointMotionError::Create(e.measurement, e.information);
}

inline ceres::CostFunction* MakeCost(const ObjectPointEdge& e, const SolverOptions&) {
  return ObjectPointMeasurementError::Create(e.measurement, e.information);
}

// SPEC §7 item 6 replaces the residual.
inline ceres::CostFunction* MakeCost(const ObjectMotionEdge& e, const SolverOptions& options) {
  return options.dsc_object_motion_residual ? ObjectPointMotionErrorDsc::Create(e.information)
                                            : ObjectPointMotionError::Create(e.information);
}

inline ceres::CostFunction* MakeCost(const KinematicEdge& e, const SolverOptions& options) {
  return ObjectKinematicError::Create(e.information, options.world_frame_kinematic_residual);
}

inline ceres::CostFunction* MakeCost(const HybridPointEdge& e, const SolverOptions&) {
  return HybridPointError::Create(e.measurement, e.information);
}

inline ceres::CostFunction* MakeCost(const HybridSmoothingEdge& e, const SolverOptions&) {
  return HybridSmoothingError::Create(e.information);
}

}  // namespace dynslam

#endif  // DYNSLAM_SRC_EDGE_COSTS_H_
