// Whether a solve's uncertainty is honest: the normalised estimation error squared
// (NEES) of each camera pose, world-frame motion and object pose against ground truth, weighted
// by its marginal covariance (covariance.h). docs/COVARIANCE.md.
//
// For a variable X with marginal Σ over the right perturbation X·Exp(δ) (SPEC §1.3), the error is
// δ = Log(X⁻¹ · X_gt) and NEES = δᵀ Σ⁻¹ δ. If the covariance is honest (the estimate's error has
// that distribution), a NEES has mean dim (6 for a pose): above, the solve is overconfident;
// below, underconfident.
#ifndef DYNSLAM_CONSISTENCY_H_
#define DYNSLAM_CONSISTENCY_H_

#include <cstdint>

#include "dynslam/covariance.h"
#include "dynslam/ground_truth.h"

namespace dynslam {

struct NeesMean {
  int64_t count = 0;  // variables with a covariance and ground truth
  int dim = 6;
  double mean = 0;    // mean NEES over them
  // The two-sided 95 % band of the mean of `count` independent χ²(dim) values:
  // χ²_{0.025}(dim·count) / count, χ²_{0.975}(dim·count) / count (Wilson–Hilferty). The
  // variables of one solve are correlated, so this is a guide there, exact across seeds.
  double band_low = 0;
  double band_high = 0;
};

struct Consistency {
  NeesMean camera;        // X_k against X^gt_k
  NeesMean object_motion; // world-frame motions H_k against L^gt_k · (L^gt_{k−1})⁻¹ (wc)
  NeesMean object_pose;   // object poses L_k against L^gt_k (oc_a, oc_b, oc_c)
};

// The NEES of every camera, motion and object pose of `solved` that has a marginal in
// `covariance` and ground truth in `ground_truth`.
Consistency ComputeConsistency(const Graph& solved, const CovarianceReport& covariance,
                               const GroundTruth& ground_truth);

// The p-quantile of χ²(k) by Wilson and Hilferty's cube-root approximation (relative error
// below 1e-3 for k ≥ 6 at p = 0.025 and 0.975).
double ChiSquaredQuantile(double p, double k);

}  // namespace dynslam

#endif  // DYNSLAM_CONSISTENCY_H_
