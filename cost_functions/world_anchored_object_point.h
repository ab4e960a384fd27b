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
// Both halves are Ceres autodiff: ObjectFramePoint (L_a, w) ↦ m_L and the residual over
// (poses…, m_L); the Jacobians with respect to L_a and w are joined by the chain rule through m_L.
// One autodiff pass over all blocks at once would carry Jets as wide as every block together
// (31 for a motion edge) where the halves need 10 and 17–24: with the chain rule these residuals
// with Jacobians take 1.7–3× less time (benchmarks/residuals_benchmark, docs/SOLVER.md) for the
// same derivatives to rounding (tests/cost_functions_test.cc).
#ifndef DYNSLAM_COST_FUNCTIONS_WORLD_ANCHORED_OBJECT_POINT_H_
#define DYNSLAM_COST_FUNCTIONS_WORLD_ANCHORED_OBJECT_POINT_H_

#include <array>
#include <memory>
#include <utility>

#include <Eigen/Core>
#include <ceres/autodiff_cost_function.h>
#include <ceres/cost_function.h>

#include "dynslam/se3.h"

namespace dynslam {

// m_L = L_a⁻¹ · w.
struct ObjectFramePoint {
  template <typename T>
  bool operator()(const T* const L_w_a, const T* const w, T* m_o) const {
    PoseInverseTransformPoint(L_w_a, w, m_o);
    return true;
  }
};

// ObjectFramePoint as an autodiff cost function. Stateless, so one instance serves every
// anchored residual (and every thread: Evaluate is const).
inline const ceres::CostFunction& ObjectFramePointCost() {
  static const ceres::AutoDiffCostFunction<ObjectFramePoint, kPointSize, kPoseSize, kPointSize>
      cost(new ObjectFramePoint);
  return cost;
}

// The residual of `inner` (an autodiff cost function over kPoses poses, then m_L) at
// m_L = L_a⁻¹ · w. The anchor L_a is one of inner's poses (blocks: poses…, w) or a further pose
// block after them (blocks: poses…, L_a, w).
template <int kResiduals, int kPoses>
class WorldAnchoredCost final : public ceres::CostFunction {
 public:
  static constexpr int kFurtherPose = kPoses;

  // `anchor`: the index of the anchor among inner's poses, or kFurtherPose. Takes `inner`.
  WorldAnchoredCost(ceres::CostFunction* inner, int anchor) : inner_(inner), anchor_(anchor) {
    set_num_residuals(kResiduals);
    for (int i = 0; i < kPoses; ++i) mutable_parameter_block_sizes()->push_back(kPoseSize);
    if (anchor_ == kFurtherPose) mutable_parameter_block_sizes()->push_back(kPoseSize);
    mutable_parameter_block_sizes()->push_back(kPointSize);
  }

  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override {
    const int w_block = anchor_ == kFurtherPose ? kPoses + 1 : kPoses;
    const bool chain = jacobians != nullptr && (jacobians[anchor_] || jacobians[w_block]);
    const std::array<const double*, 2> anchor_blocks = {parameters[anchor_], parameters[w_block]};
    double m_o[kPointSize];
    double dm_danchor[kPointSize * kPoseSize], dm_dw[kPointSize * kPointSize];
    std::array<double*, 2> m_jacobians = {dm_danchor, dm_dw};
    if (!ObjectFramePointCost().Evaluate(anchor_blocks.data(), m_o,
                                         chain ? m_jacobians.data() : nullptr)) {
      return false;
    }
    std::array<const double*, kPoses + 1> inner_blocks;
    std::array<double*, kPoses + 1> inner_jacobians;
    double dr_dm[kResiduals * kPointSize];
    for (int i = 0; i < kPoses; ++i) {
      inner_blocks[i] = parameters[i];
      inner_jacobians[i] = jacobians != nullptr ? jacobians[i] : nullptr;
    }
    inner_blocks[kPoses] = m_o;
    inner_jacobians[kPoses] = chain ? dr_dm : nullptr;
    if (!inner_->Evaluate(inner_blocks.data(), residuals,
                          jacobians != nullptr ? inner_jacobians.data() : nullptr)) {
      return false;
    }
    if (chain) Chain(dr_dm, dm_danchor, dm_dw, jacobians[anchor_], jacobians[w_block]);
    return true;
  }

 private:
  template <int kCols>
  using RowMajor = Eigen::Matrix<double, kResiduals, kCols, Eigen::RowMajor>;
  template <int kCols>
  using MRowMajor = Eigen::Matrix<double, kPointSize, kCols, Eigen::RowMajor>;

  // ∂r/∂L_a (added to inner's own Jacobian when the anchor is one of its poses) and ∂r/∂w.
  void Chain(const double* dr_dm, const double* dm_danchor, const double* dm_dw,
             double* dr_danchor, double* dr_dw) const {
    const Eigen::Map<const RowMajor<kPointSize>> j_m(dr_dm);
    if (dr_danchor != nullptr) {
      Eigen::Map<RowMajor<kPoseSize>> j_anchor(dr_danchor);
      const Eigen::Map<const MRowMajor<kPoseSize>> m_anchor(dm_danchor);
      if (anchor_ == kFurtherPose) {
        j_anchor.noalias() = j_m * m_anchor;
      } else {
        j_anchor.noalias() += j_m * m_anchor;
      }
    }
    if (dr_dw != nullptr) {
      Eigen::Map<RowMajor<kPointSize>>(dr_dw).noalias() =
          j_m * Eigen::Map<const MRowMajor<kPointSize>>(dm_dw);
    }
  }

  std::unique_ptr<ceres::CostFunction> inner_;
  const int anchor_;
};

// Cost functions for the residual functor Inner (kResiduals residuals over kPoses poses, then m_L).
template <typename Inner, int kResiduals, int kPoses>
struct WorldAnchored;

template <typename Inner, int kResiduals>
struct WorldAnchored<Inner, kResiduals, 2> {
  static ceres::CostFunction* AtFurtherPose(Inner inner) {
    return new WorldAnchoredCost<kResiduals, 2>(ObjectFrame(std::move(inner)),
                                                WorldAnchoredCost<kResiduals, 2>::kFurtherPose);
  }

 private:
  static ceres::CostFunction* ObjectFrame(Inner inner) {
    return new ceres::AutoDiffCostFunction<Inner, kResiduals, kPoseSize, kPoseSize, kPointSize>(
        new Inner(std::move(inner)));
  }
};

template <typename Inner, int kResiduals>
struct WorldAnchored<Inner, kResiduals, 3> {
  static ceres::CostFunction* AtFurtherPose(Inner inner) {
    return new WorldAnchoredCost<kResiduals, 3>(ObjectFrame(std::move(inner)),
                                                WorldAnchoredCost<kResiduals, 3>::kFurtherPose);
  }
  template <int kAnchor>
  static ceres::CostFunction* AtOwnPose(Inner inner) {
    static_assert(kAnchor >= 0 && kAnchor < 3, "the anchor is one of the three poses");
    return new WorldAnchoredCost<kResiduals, 3>(ObjectFrame(std::move(inner)), kAnchor);
  }

 private:
  static ceres::CostFunction* ObjectFrame(Inner inner) {
    return new ceres::AutoDiffCostFunction<Inner, kResiduals, kPoseSize, kPoseSize, kPoseSize,
                                           kPointSize>(new Inner(std::move(inner)));
  }
};

}  // namespace dynslam

#endif  // DYNSLAM_COST_FUNCTIONS_WORLD_ANCHORED_OBJECT_POINT_H_
