// The gauge of an object segment (docs/CONVERGENCE.md §6–7). An object-centric segment's object
// poses L_k and object-frame points m_L can all be moved by one pose G — L_k → L_k·G,
// m_L → G⁻¹·m_L — without changing any object-point or object-motion residual (L_k·m_L is
// unchanged); only the prior on the segment's first pose sees it, and the kinematic residual
// (oc_b, oc_c) changes with G's translation. Along that direction the only curvature is the weak
// object prior's, which LM's damping dwarfs, so a solver creeps along it for hundreds of steps.
// SegmentGauges finds the segments and moves each by the G that zeroes its prior residual,
// G = L_{k0}⁻¹·Z: in oc_a exactly the prior's cost comes off, in oc_b/oc_c the caller keeps the
// move only if the total cost falls.
#ifndef DYNSLAM_SRC_SEGMENT_GAUGE_H_
#define DYNSLAM_SRC_SEGMENT_GAUGE_H_

#include <array>
#include <cstddef>
#include <functional>
#include <vector>

#include "cost_functions/pose_prior_error.h"
#include "dynslam/graph.h"
#include "dynslam/pose.h"

namespace dynslam {

class SegmentGauges {
 public:
  // One 7-double block per vertex (a point uses the first three), as the solver holds them.
  using Values = std::vector<std::array<double, kPoseSize>>;
  // What the solver tells about a vertex of the graph.
  struct Layout {
    std::function<size_t(VertexId)> index;  // its block in Values
    std::function<bool(VertexId)> movable;  // a variable of the problem (not held constant)
    // An object-frame point the solver carries as its world position w = L_a·m_L, which the
    // gauge leaves unchanged.
    std::function<bool(VertexId)> world_anchored;
  };

  // The segments of `graph`: object poses and object-frame points joined by object-point,
  // object-motion and kinematic edges, with exactly one object prior, touched by no other edge,
  // and every vertex movable. None for graphs without object poses.
  static SegmentGauges Find(const Graph& graph, const Layout& layout);

  bool empty() const { return segments_.empty(); }
  size_t size() const { return segments_.size(); }
  // Σ ½·‖r‖² of the segments' prior residuals at `values` (no robust kernel): what the move
  // removes.
  double PriorCost(const Values& values) const;
  // Moves every segment so that its prior residual is zero.
  void Snap(Values* values) const;

 private:
  struct Segment {
    size_t prior_pose;      // block of the pose the prior is on
    Pose measurement;       // the prior's Z
    PosePriorError error;   // the prior's whitened residual, as the solver evaluates it
    std::vector<size_t> poses;   // L → L·G
    std::vector<size_t> points;  // m → G⁻¹·m (object-frame points not world-anchored)
  };
  std::vector<Segment> segments_;
};

}  // namespace dynslam

#endif  // DYNSLAM_SRC_SEGMENT_GAUGE_H_
