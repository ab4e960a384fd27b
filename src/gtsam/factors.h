// GTSAM factors for the edges GTSAM has no factor of its own for (SPEC §1.2–§1.3, §3.6, §7).
//
// Each returns the SPEC residual r before whitening (the noise model whitens it) with analytic
// Jacobians in GTSAM's tangent convention (pose: X·Exp(ξ), ξ = [ω; ρ]; point: m + δ), built from
// GTSAM's own chain-rule Jacobians. tests/gtsam_backend_test.cc checks each against
// gtsam::numericalDerivative and against the Ceres cost function of the same edge.
#ifndef DYNSLAM_SRC_GTSAM_FACTORS_H_
#define DYNSLAM_SRC_GTSAM_FACTORS_H_

#include <gtsam/geometry/Point3.h>
#include <gtsam/geometry/Pose3.h>
#include <gtsam/nonlinear/NonlinearFactor.h>

namespace dynslam::gtsam_backend {

using gtsam::Key;
using gtsam::Matrix;
using gtsam::Point3;
using gtsam::Pose3;
using gtsam::SharedNoiseModel;
using gtsam::Vector;
using Jacobian = boost::optional<Matrix&>;

// `&m` when a Jacobian that needs m is wanted, else none: GTSAM's error() asks for none.
template <typename M>
M* When(bool wanted, M& m) {
  return wanted ? &m : nullptr;
}

// Writes `value` into an optional Jacobian when it was asked for.
template <typename Derived>
void Set(Jacobian& jacobian, const Eigen::MatrixBase<Derived>& value) {
  if (jacobian) *jacobian = value;
}

// EDGE_SE3_TRACKXYZ: r = X⁻¹·m − z.
class CameraPointFactor : public gtsam::NoiseModelFactorN<Pose3, Point3> {
 public:
  CameraPointFactor(Key camera, Key point, const Point3& z, const SharedNoiseModel& noise)
      : NoiseModelFactorN(noise, camera, point), z_(z) {}
  Vector evaluateError(const Pose3& X, const Point3& m, Jacobian dX = boost::none,
                       Jacobian dm = boost::none) const override {
    gtsam::Matrix36 p_X;
    gtsam::Matrix3 p_m;
    const Point3 p = X.transformTo(m, When(!!dX, p_X), When(!!dm, p_m));
    Set(dX, p_X);
    Set(dm, p_m);
    return p - z_;
  }

 private:
  Point3 z_;
};

// EDGE_SE3_MOTION: r = m_curr − H·m_prev − z; with `released` (SPEC §7 item 2) the released
// code's r = m_prev − H⁻¹·m_curr (z unused; the caller gives σ = 0.1 and Huber).
class PointMotionFactor : public gtsam::NoiseModelFactorN<Point3, Point3, Pose3> {
 public:
  PointMotionFactor(Key prev, Key curr, Key motion, const Point3& z, bool released,
                    const SharedNoiseModel& noise)
      : NoiseModelFactorN(noise, prev, curr, motion), z_(z), released_(released) {}
  Vector evaluateError(const Point3& prev, const Point3& curr, const Pose3& H,
                       Jacobian dprev = boost::none, Jacobian dcurr = boost::none,
                       Jacobian dH = boost::none) const override {
    gtsam::Matrix36 q_H;
    gtsam::Matrix3 q_m;
    if (released_) {
      const Point3 back = H.transformTo(curr, When(!!dH, q_H), When(!!dcurr, q_m));
      Set(dprev, gtsam::Matrix3::Identity());
      Set(dcurr, -q_m);
      Set(dH, -q_H);
      return prev - back;
    }
    const Point3 moved = H.transformFrom(prev, When(!!dH, q_H), When(!!dprev, q_m));
    Set(dprev, -q_m);
    Set(dcurr, gtsam::Matrix3::Identity());
    Set(dH, -q_H);
    return curr - moved - z_;
  }

 private:
  Point3 z_;
  bool released_;
};

// EDGE_SE3_OBJ_TRACKXYZ: r = X⁻¹·L·m_L − z.
class ObjectPointFactor : public gtsam::NoiseModelFactorN<Pose3, Pose3, Point3> {
 public:
  ObjectPointFactor(Key camera, Key object_pose, Key point, const Point3& z,
                    const SharedNoiseModel& noise)
      : NoiseModelFactorN(noise, camera, object_pose, point), z_(z) {}
  Vector evaluateError(const Pose3& X, const Pose3& L, const Point3& m, Jacobian dX = boost::none,
                       Jacobian dL = boost::none, Jacobian dm = boost::none) const override {
    gtsam::Matrix36 w_L, p_X;
    gtsam::Matrix3 w_m, p_w;
    const Point3 w = L.transformFrom(m, When(!!dL, w_L), When(!!dm, w_m));
    const Point3 p = X.transformTo(w, When(!!dX, p_X), When(dL || dm, p_w));
    Set(dX, p_X);
    Set(dL, p_w * w_L);
    Set(dm, p_w * w_m);
    return p - z_;
  }

 private:
  Point3 z_;
};

// EDGE_SE3_OBJ_MOTION: r = L_curr·m_L − H·L_prev·m_L − z; with `released` (SPEC §7 item 6) the
// released code's r = L_curr⁻¹·H·L_prev·m_L (z unused).
class ObjectMotionFactor : public gtsam::NoiseModelFactorN<Pose3, Pose3, Pose3, Point3> {
 public:
  ObjectMotionFactor(Key pose_prev, Key pose_curr, Key motion, Key point, const Point3& z,
                     bool released, const SharedNoiseModel& noise)
      : NoiseModelFactorN(noise, pose_prev, pose_curr, motion, point), z_(z), released_(released) {}
  Vector evaluateError(const Pose3& Lp, const Pose3& Lc, const Pose3& H, const Point3& m,
                       Jacobian dLp = boost::none, Jacobian dLc = boost::none,
                       Jacobian dH = boost::none, Jacobian dm = boost::none) const override {
    gtsam::Matrix36 a_Lp, b_H, c_Lc, d_Lc;
    gtsam::Matrix3 a_m, b_a, c_b, d_m;
    const bool through_a = dLp || dm;
    const Point3 a = Lp.transformFrom(m, When(!!dLp, a_Lp), When(!!dm, a_m));  // L_prev·m
    const Point3 b = H.transformFrom(a, When(!!dH, b_H), When(through_a, b_a));  // H·L_prev·m
    if (released_) {
      const Point3 c = Lc.transformTo(b, When(!!dLc, c_Lc), When(through_a || dH, c_b));
      Set(dLp, c_b * b_a * a_Lp);
      Set(dLc, c_Lc);
      Set(dH, c_b * b_H);
      Set(dm, c_b * b_a * a_m);
      return c;
    }
    const Point3 d = Lc.transformFrom(m, When(!!dLc, d_Lc), When(!!dm, d_m));  // L_curr·m
    Set(dLp, -b_a * a_Lp);
    Set(dLc, d_Lc);
    Set(dH, -b_H);
    Set(dm, d_m - b_a * a_m);
    return d - b - z_;
  }

 private:
  Point3 z_;
  bool released_;
};

// EDGE_SE3_OBJ_KINEMATIC: r = Log(L_curr⁻¹·H·L_prev), Log's derivative included.
class KinematicFactor : public gtsam::NoiseModelFactorN<Pose3, Pose3, Pose3> {
 public:
  KinematicFactor(Key pose_prev, Key pose_curr, Key motion, const SharedNoiseModel& noise)
      : NoiseModelFactorN(noise, pose_prev, pose_curr, motion) {}
  Vector evaluateError(const Pose3& Lp, const Pose3& Lc, const Pose3& H, Jacobian dLp = boost::none,
                       Jacobian dLc = boost::none, Jacobian dH = boost::none) const override {
    gtsam::Matrix6 M_H, M_Lp, E_Lc, E_M, r_E;
    const bool any = dLp || dLc || dH;
    const Pose3 M = H.compose(Lp, When(!!dH, M_H), When(!!dLp, M_Lp));
    const Pose3 E = Lc.between(M, When(!!dLc, E_Lc), When(dLp || dH, E_M));
    const gtsam::Vector6 r = Pose3::Logmap(E, When(any, r_E));
    Set(dLp, r_E * E_M * M_Lp);
    Set(dLc, r_E * E_Lc);
    Set(dH, r_E * E_M * M_H);
    return r;
  }
};

// EDGE_SE3_PRIOR with Log's derivative (SPEC §6 tight_exact): r = Log(Z⁻¹·X).
class ExactPriorFactor : public gtsam::NoiseModelFactorN<Pose3> {
 public:
  ExactPriorFactor(Key pose, const Pose3& Z, const SharedNoiseModel& noise)
      : NoiseModelFactorN(noise, pose), Z_inverse_(Z.inverse()) {}
  Vector evaluateError(const Pose3& X, Jacobian dX = boost::none) const override {
    gtsam::Matrix6 r_E;
    const gtsam::Vector6 r = Pose3::Logmap(Z_inverse_ * X, When(!!dX, r_E));
    Set(dX, r_E);  // d(Z⁻¹X)/dX = I for the right perturbation
    return r;
  }

 private:
  Pose3 Z_inverse_;
};

// EDGE_SE3:QUAT with Log's derivative (SPEC §6 tight_exact): r = Log(Z⁻¹·A⁻¹·B).
class ExactBetweenFactor : public gtsam::NoiseModelFactorN<Pose3, Pose3> {
 public:
  ExactBetweenFactor(Key a, Key b, const Pose3& Z, const SharedNoiseModel& noise)
      : NoiseModelFactorN(noise, a, b), Z_inverse_(Z.inverse()) {}
  Vector evaluateError(const Pose3& A, const Pose3& B, Jacobian dA = boost::none,
                       Jacobian dB = boost::none) const override {
    gtsam::Matrix6 D_A, D_B, E_D, r_E;
    const bool any = dA || dB;
    const Pose3 D = A.between(B, When(!!dA, D_A), When(!!dB, D_B));
    const Pose3 E = Z_inverse_.compose(D, boost::none, When(any, E_D));
    const gtsam::Vector6 r = Pose3::Logmap(E, When(any, r_E));
    Set(dA, r_E * E_D * D_A);
    Set(dB, r_E * E_D * D_B);
    return r;
  }

 private:
  Pose3 Z_inverse_;
};

// EDGE_SE3_HY_TRACKXYZ: r = X⁻¹·H·L_e·m − z, L_e a constant (SPEC §3.6).
class HybridPointFactor : public gtsam::NoiseModelFactorN<Pose3, Pose3, Point3> {
 public:
  HybridPointFactor(Key camera, Key motion, Key point, const Pose3& embedded, const Point3& z,
                    const SharedNoiseModel& noise)
      : NoiseModelFactorN(noise, camera, motion, point), embedded_(embedded), z_(z) {}
  Vector evaluateError(const Pose3& X, const Pose3& H, const Point3& m, Jacobian dX = boost::none,
                       Jacobian dH = boost::none, Jacobian dm = boost::none) const override {
    gtsam::Matrix6 L_H;
    gtsam::Matrix36 w_L, p_X;
    gtsam::Matrix3 w_m, p_w;
    const Pose3 L = H.compose(embedded_, When(!!dH, L_H), boost::none);
    const Point3 w = L.transformFrom(m, When(!!dH, w_L), When(!!dm, w_m));
    const Point3 p = X.transformTo(w, When(!!dX, p_X), When(dH || dm, p_w));
    Set(dX, p_X);
    Set(dH, p_w * w_L * L_H);
    Set(dm, p_w * w_m);
    return p - z_;
  }

 private:
  Pose3 embedded_;
  Point3 z_;
};

// EDGE_SE3_HY_SMOOTHING: r = Log((L_a⁻¹·L_b)⁻¹·(L_b⁻¹·L_c)), L_x = H_x·L_e (SPEC §3.6).
class HybridSmoothingFactor : public gtsam::NoiseModelFactorN<Pose3, Pose3, Pose3> {
 public:
  HybridSmoothingFactor(Key a, Key b, Key c, const Pose3& embedded, const SharedNoiseModel& noise)
      : NoiseModelFactorN(noise, a, b, c), embedded_(embedded) {}
  Vector evaluateError(const Pose3& Ha, const Pose3& Hb, const Pose3& Hc,
                       Jacobian dHa = boost::none, Jacobian dHb = boost::none,
                       Jacobian dHc = boost::none) const override {
    gtsam::Matrix6 La_Ha, Lb_Hb, Lc_Hc, U_La, U_Lb1, V_Lb, V_Lc, E_U, E_V, r_E;
    const Pose3 La = Ha.compose(embedded_, When(!!dHa, La_Ha), boost::none);
    const Pose3 Lb = Hb.compose(embedded_, When(!!dHb, Lb_Hb), boost::none);
    const Pose3 Lc = Hc.compose(embedded_, When(!!dHc, Lc_Hc), boost::none);
    const Pose3 U = La.between(Lb, When(!!dHa, U_La), When(!!dHb, U_Lb1));  // L_a⁻¹L_b
    const Pose3 V = Lb.between(Lc, When(!!dHb, V_Lb), When(!!dHc, V_Lc));   // L_b⁻¹L_c
    const Pose3 E = U.between(V, When(dHa || dHb, E_U), When(dHb || dHc, E_V));
    const gtsam::Vector6 r = Pose3::Logmap(E, When(dHa || dHb || dHc, r_E));
    Set(dHa, r_E * E_U * U_La * La_Ha);
    Set(dHb, r_E * (E_U * U_Lb1 + E_V * V_Lb) * Lb_Hb);
    Set(dHc, r_E * E_V * V_Lc * Lc_Hc);
    return r;
  }

 private:
  Pose3 embedded_;
};

}  // namespace dynslam::gtsam_backend

#endif  // DYNSLAM_SRC_GTSAM_FACTORS_H_
