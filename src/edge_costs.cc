#include "src/edge_costs.h"

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
#include "cost_functions/world_anchored_object_point.h"

namespace dynslam {

ceres::CostFunction* MakeCost(const PriorEdge& e, const SolverOptions&) {
  return PosePriorError::Create(e.measurement, e.information);
}

ceres::CostFunction* MakeCost(const BetweenEdge& e, const SolverOptions&) {
  return PoseBetweenError::Create(e.measurement, e.information);
}

ceres::CostFunction* MakeCost(const PointEdge& e, const SolverOptions&) {
  return PointMeasurementError::Create(e.measurement, e.information);
}

ceres::CostFunction* MakeCost(const MotionEdge& e, const SolverOptions& options) {
  return options.dsc_motion_residual ? PointMotionErrorDsc::Create(options.dsc_motion_sigma)
                                     : PointMotionError::Create(e.measurement, e.information);
}

ceres::CostFunction* MakeCost(const ObjectPointEdge& e, const SolverOptions&) {
  return ObjectPointMeasurementError::Create(e.measurement, e.information);
}

ceres::CostFunction* MakeCost(const ObjectMotionEdge& e, const SolverOptions& options) {
  return options.dsc_object_motion_residual ? ObjectPointMotionErrorDsc::Create(e.information)
                                            : ObjectPointMotionError::Create(e.measurement, e.information);
}

ceres::CostFunction* MakeCost(const KinematicEdge& e, const SolverOptions& options) {
  return ObjectKinematicError::Create(e.information, (options.kinematic_residual_frame == Frame::kWorld));
}

ceres::CostFunction* MakeCost(const HybridPointEdge& e, const SolverOptions&) {
  return HybridPointError::Create(e.measurement, e.information);
}

ceres::CostFunction* MakeCost(const HybridSmoothingEdge& e, const SolverOptions&) {
  return HybridSmoothingError::Create(e.information);
}

AnchoredCost MakeAnchoredCost(const ObjectPointEdge& e, VertexId anchor) {
  if (anchor == e.object_pose) {  // X⁻¹ · L_a · L_a⁻¹ · w = X⁻¹ · w
    return {PointMeasurementError::Create(e.measurement, e.information), {e.camera, e.point}};
  }
  return {WorldAnchored<ObjectPointMeasurementError, 3, 2>::AtFurtherPose(
              ObjectPointMeasurementError(e.measurement, e.information)),
          {e.camera, e.object_pose, anchor, e.point}};
}

namespace {

template <typename Residual>
AnchoredCost MakeAnchoredMotionCost(const ObjectMotionEdge& e, Residual residual,
                                    VertexId anchor) {
  using Anchored = WorldAnchored<Residual, 3, 3>;
  const std::vector<VertexId> own = VertexIds(e, true);
  if (anchor == e.pose_prev) return {Anchored::template AtOwnPose<0>(residual), own};
  if (anchor == e.pose_curr) return {Anchored::template AtOwnPose<1>(residual), own};
  return {Anchored::AtFurtherPose(residual),
          {e.pose_prev, e.pose_curr, e.motion, anchor, e.point}};
}

}  // namespace

AnchoredCost MakeAnchoredCost(const ObjectMotionEdge& e, const SolverOptions& options,
                              VertexId anchor) {
  return options.dsc_object_motion_residual
             ? MakeAnchoredMotionCost(e, ObjectPointMotionErrorDsc(e.information), anchor)
             : MakeAnchoredMotionCost(e, ObjectPointMotionError(e.measurement, e.information), anchor);
}

}  // namespace dynslam
