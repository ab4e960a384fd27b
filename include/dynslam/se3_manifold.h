// The ceres::Manifold of a 7-double pose block (pose.h; SPEC §0).
//
// Plus(x, ξ) = x · Exp(ξ) — right perturbation, ξ = [ω; ρ], full SE(3) exponential — and
// Minus(y, x) = Log(x⁻¹ · y). The Jacobians at ξ = 0 are analytic:
//   ∂Plus/∂ξ   = [ ½(w·I + [v]×)  0 ;  −½·vᵀ  0 ;  0  R ]        (rows qx qy qz qw tx ty tz)
//   ∂Minus/∂y  = [ 2(w·I − [v]×)  −2v  0 ;  0  0  Rᵀ ]           (columns qx qy qz qw tx ty tz)
// for x = (q = (v, w), t), R = R(q); their product is the identity for unit q.
#ifndef DYNSLAM_SE3_MANIFOLD_H_
#define DYNSLAM_SE3_MANIFOLD_H_

#include <ceres/manifold.h>

namespace dynslam {

class SE3Manifold final : public ceres::Manifold {
 public:
  int AmbientSize() const override { return 7; }
  int TangentSize() const override { return 6; }
  bool Plus(const double* x, const double* delta, double* x_plus_delta) const override;
  bool PlusJacobian(const double* x, double* jacobian) const override;
  bool Minus(const double* y, const double* x, double* y_minus_x) const override;
  bool MinusJacobian(const double* x, double* jacobian) const override;
};

}  // namespace dynslam

#endif  // DYNSLAM_SE3_MANIFOLD_H_
