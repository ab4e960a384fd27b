// A change of variables for the object-frame point m_L of the object-centric residuals (SPEC §3.3;
// docs/CONVERGENCE.md): the solver carries the point as w, its world position at an anchor pose
// L_a of its segment, and each residual evaluates m_L = L_a⁻¹ · w before calling the residual of
// SPEC §1.3 unchanged. The cost is the same function of the graph's variables, so the optimum is
// the same; what changes is the chart the Gauss–Newton steps are taken in. In (L, m_L) the
// segment's gauge — every L_k · G with every m_L as G⁻¹ · m_L, fixed only by the weak object
// prior — is a curve (m_L turns about the object origin), and steps along its tangent raise the
// point residuals: LM crept along it for a hundred steps. In (L, w) it is the straight line
// L_k · Exp(t ξ) with w fixed.
//
// Inner is a residual functor whose last parameter block is m_L (3 doubles) and the others
// poses (7 doubles), e.g. ObjectPointMeasurementError (X, L, m_L) or ObjectPointMotionError
// (L_prev, L_curr, H, m_L).
#ifndef DYNSLAM_COST_FUNCTIONS_WORLD_ANCHORED_OBJECT_POINT_H_
#define DYNSLAM_COST_FUNCTIONS_WORLD_ANCHORED_OBJECT_POINT_H_

#include <utility>

#include <ceres/ceres.h>

#include "dynslam/se3.h"

namespace dynslam {

// The anchor is a further pose block after Inner's poses: blocks (poses…, L_a, w).
template <typename Inner>
class AnchoredAtFurtherPose {
 public:
  explicit AnchoredAtFurtherPose(Inner inner) : inner_(std::move(inner)) {}

  template <typename T>
  bool operator()(const T* const p0, const T* const p1, const T* const L_w_a, const T* const w,
                  T* residual) const {
    T m_o[3];
    PoseInverseTransformPoint(L_w_a, w, m_o);
    return inner_(p0, p1, m_o, residual);
  }
  template <typename T>
  bool operator()(const T* const p0, const T* const p1, const T* const p2, const T* const L_w_a,
                  const T* const w, T* residual) const {
    T m_o[3];
    PoseInverseTransformPoint(L_w_a, w, m_o);
    return inner_(p0, p1, p2, m_o, residual);
  }

 private:
  Inner inner_;
};

// The anchor is Inner's pose block number kAnchor: blocks (poses…, w).
template <typename Inner, int kAnchor>
class AnchoredAtOwnPose {
 public:
  explicit AnchoredAtOwnPose(Inner inner) : inner_(std::move(inner)) {}

  template <typename T>
  bool operator()(const T* const p0, const T* const p1, const T* const p2, const T* const w,
                  T* residual) const {
    const T* const poses[] = {p0, p1, p2};
    T m_o[3];
    PoseInverseTransformPoint(poses[kAnchor], w, m_o);
    return inner_(p0, p1, p2, m_o, residual);
  }

 private:
  Inner inner_;
};

// Cost functions for Inner with kResiduals residuals over kPoses poses then m_L.
template <typename Inner, int kResiduals, int kPoses>
struct WorldAnchored;

template <typename Inner, int kResiduals>
struct WorldAnchored<Inner, kResiduals, 2> {
  static ceres::CostFunction* AtFurtherPose(Inner inner) {
    return new ceres::AutoDiffCostFunction<AnchoredAtFurtherPose<Inner>, kResiduals, kPoseSize,
                                           kPoseSize, kPoseSize, kPointSize>(
        new AnchoredAtFurtherPose<Inner>(std::move(inner)));
  }
};

template <typename Inner, int kResiduals>
struct WorldAnchored<Inner, kResiduals, 3> {
  static ceres::CostFunction* AtFurtherPose(Inner inner) {
    return new ceres::AutoDiffCostFunction<AnchoredAtFurtherPose<Inner>, kResiduals, kPoseSize,
                                           kPoseSize, kPoseSize, kPoseSize, kPointSize>(
        new AnchoredAtFurtherPose<Inner>(std::move(inner)));
  }
  template <int kAnchor>
  static ceres::CostFunction* AtOwnPose(Inner inner) {
    return new ceres::AutoDiffCostFunction<AnchoredAtOwnPose<Inner, kAnchor>, kResiduals,
                                           kPoseSize, kPoseSize, kPoseSize, kPointSize>(
        new AnchoredAtOwnPose<Inner, kAnchor>(std::move(inner)));
  }
};

}  // namespace dynslam

#endif  // DYNSLAM_COST_FUNCTIONS_WORLD_ANCHORED_OBJECT_POINT_H_
