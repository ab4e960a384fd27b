// The solver's half of the edge table (graph_schema.h): the residual of each edge struct, over
// the edge's parameter vertices in field order (VertexIds(edge, true)). Adding an edge tag adds
// one MakeCost overload here and in edge_costs.cc.
//
// Every Ceres autodiff cost function the solver builds is instantiated in edge_costs.cc, and
// nowhere else in the library: CMakeLists.txt compiles that file for the speed of its Jacobians
// (docs/SOLVER.md "Cost of a residual").
#ifndef DYNSLAM_SRC_EDGE_COSTS_H_
#define DYNSLAM_SRC_EDGE_COSTS_H_

#include <vector>

#include <ceres/cost_function.h>

#include "dynslam/graph_schema.h"
#include "dynslam/solver.h"

namespace dynslam {

ceres::CostFunction* MakeCost(const PriorEdge& e, const SolverOptions& options);
ceres::CostFunction* MakeCost(const BetweenEdge& e, const SolverOptions& options);
ceres::CostFunction* MakeCost(const PointEdge& e, const SolverOptions& options);
// SPEC §7 item 2 replaces the residual.
ceres::CostFunction* MakeCost(const MotionEdge& e, const SolverOptions& options);
ceres::CostFunction* MakeCost(const ObjectPointEdge& e, const SolverOptions& options);
// SPEC §7 item 6 replaces the residual.
ceres::CostFunction* MakeCost(const ObjectMotionEdge& e, const SolverOptions& options);
ceres::CostFunction* MakeCost(const KinematicEdge& e, const SolverOptions& options);
ceres::CostFunction* MakeCost(const HybridPointEdge& e, const SolverOptions& options);
ceres::CostFunction* MakeCost(const HybridSmoothingEdge& e, const SolverOptions& options);

// SolverOptions::object_point_variables: the residual of an object-frame point edge whose
// point block holds w = L_a · m_L at the anchor pose `anchor`
// (cost_functions/world_anchored_object_point.h), and the vertices it is over.
struct AnchoredCost {
  ceres::CostFunction* cost;
  std::vector<VertexId> ids;
};
AnchoredCost MakeAnchoredCost(const ObjectPointEdge& e, VertexId anchor);
AnchoredCost MakeAnchoredCost(const ObjectMotionEdge& e, const SolverOptions& options,
                              VertexId anchor);

}  // namespace dynslam

#endif  // DYNSLAM_SRC_EDGE_COSTS_H_
