// SE(3) on the 7-double pose block of pose.h, templated so that Ceres's Jets flow through
// (SPEC §0). Tangent vectors are ξ = [ω; ρ]; Exp is the full SE(3) exponential
// (R = exp([ω]×), t = V(ω)·ρ) and Log its inverse — GTSAM's Pose3::Expmap/Logmap with
// GTSAM_POSE3_EXPMAP.
//
// Jet safety: near θ = 0 every coefficient is a Taylor series (no sqrt, acos or division by θ),
// so derivatives at exactly the identity are exact. Exp switches at θ² = 1e-2 (series to θ⁸: the
// first omitted term is below 1e-19 relative); Log at |v|²/w² = 1e-4, i.e. θ ≈ 0.02 (series to
// x⁸ and θ⁶: omitted terms below 1e-20). Beyond the switches the closed forms lose at most
// ~1e-11 relative on coefficients that multiply terms of size θ², i.e. ~1e-16 absolute.
// Near θ = π, Log uses atan2 and the half-angle form of V⁻¹ ((θ/2)·cot(θ/2) = f·w/2 below),
// which stay finite as sin θ → 0.
#ifndef DYNSLAM_SE3_H_
#define DYNSLAM_SE3_H_

#include <cmath>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "dynslam/pose.h"

namespace dynslam {

namespace se3_internal {

inline constexpr double kExpTaylorThetaSquared = 1e-2;  // θ² below which Exp uses series
inline constexpr double kLogTaylorX2 = 1e-4;             // |v|²/w² below which Log does

template <typename T>
using Vector3 = Eigen::Matrix<T, 3, 1>;

template <typename T>
Eigen::Quaternion<T> Rotation(const T* pose) {
  return Eigen::Quaternion<T>(pose[3], pose[0], pose[1], pose[2]);
}

template <typename T>
Vector3<T> Translation(const T* pose) {
  return Vector3<T>(pose[4], pose[5], pose[6]);
}

template <typename T>
void Store(const Eigen::Quaternion<T>& q, const Vector3<T>& t, T* pose) {
  pose[0] = q.x();
  pose[1] = q.y();
  pose[2] = q.z();
  pose[3] = q.w();
  pose[4] = t.x();
  pose[5] = t.y();
  pose[6] = t.z();
}

}  // namespace se3_internal

// inverse = pose⁻¹. `inverse` may alias `pose`.
template <typename T>
inline void PoseInverse(const T* pose, T* inverse) {
  using namespace se3_internal;
  const Eigen::Quaternion<T> q_inv = Rotation(pose).conjugate();
  const Vector3<T> t_inv = -(q_inv * Translation(pose));
  Store(q_inv, t_inv, inverse);
}

// ab = a · b. `ab` may alias `a` or `b`.
template <typename T>
void PoseCompose(const T* a, const T* b, T* ab) {
  using namespace se3_internal;
  const Eigen::Quaternion<T> q_a = Rotation(a);
  const Eigen::Quaternion<T> q = q_a * Rotation(b);
  const Vector3<T> t = q_a * Translation(b) + Translation(a);
  Store(q, t, ab);
}

// out = R·p + t. `out` may alias `p`.
template <typename T>
void PoseTransformPoint(const T* pose, const T* p, T* out) {
  using namespace se3_internal;
  const Vector3<T> result = Rotation(pose) * Vector3<T>(p[0], p[1], p[2]) + Translation(pose);
  out[0] = result.x();
  out[1] = result.y();
  out[2] = result.z();
}

// out = Rᵀ·(p − t): a world point seen in the pose's frame (pose⁻¹ · p). `out` may alias `p`.
template <typename T>
void PoseInverseTransformPoint(const T* pose, const T* p, T* out) {
  using namespace se3_internal;
  const Vector3<T> result =
      Rotation(pose).conjugate() * (Vector3<T>(p[0], p[1], p[2]) - Translation(pose));
  out[0] = result.x();
  out[1] = result.y();
  out[2] = result.z();
}

// ab = a · b for a constant pose a (doubles) and b of any scalar type: the products of
// PoseCompose in the same order, with double × T multiplications where PoseCompose would multiply
// constant Jets (faster under autodiff; the same values to rounding — Eigen may vectorise the
// double quaternion product differently).
template <typename T>
void PoseComposeConstant(const Pose& a, const T* b, T* ab) {
  using namespace se3_internal;
  const Eigen::Quaterniond qa = a.rotation();
  const Eigen::Quaternion<T> qb = Rotation(b);
  const Eigen::Quaternion<T> q(qa.w() * qb.w() - qa.x() * qb.x() - qa.y() * qb.y() - qa.z() * qb.z(),
                               qa.w() * qb.x() + qa.x() * qb.w() + qa.y() * qb.z() - qa.z() * qb.y(),
                               qa.w() * qb.y() + qa.y() * qb.w() + qa.z() * qb.x() - qa.x() * qb.z(),
                               qa.w() * qb.z() + qa.z() * qb.w() + qa.x() * qb.y() - qa.y() * qb.x());
  // Eigen's q * v: v + w·(2 u×v) + u×(2 u×v), u = q.vec().
  const Vector3<T> v = Translation(b);
  const Eigen::Vector3d u = qa.vec();
  Vector3<T> uv(u.y() * v.z() - u.z() * v.y(), u.z() * v.x() - u.x() * v.z(),
                u.x() * v.y() - u.y() * v.x());
  uv += uv;
  const Vector3<T> u_uv(u.y() * uv.z() - u.z() * uv.y(), u.z() * uv.x() - u.x() * uv.z(),
                        u.x() * uv.y() - u.y() * uv.x());
  const Vector3<T> t = v + qa.w() * uv + u_uv + a.translation();
  Store(q, t, ab);
}

// r = S · e for an upper-triangular S of doubles (SqrtInformation) and e of any scalar type:
// double × T products only, the zeros below the diagonal skipped (faster under autodiff).
template <int N, typename T>
void Whiten(const Eigen::Matrix<double, N, N>& S, const T* e, T* r) {
  for (int i = 0; i < N; ++i) {
    T sum = S(i, i) * e[i];
    for (int j = i + 1; j < N; ++j) sum += S(i, j) * e[j];
    r[i] = sum;
  }
}

// pose = Exp(ξ), ξ = [ω; ρ].
template <typename T>
void SE3Exp(const T* xi, T* pose) {
  using namespace se3_internal;
  using std::cos;
  using std::sin;
  using std::sqrt;
  const Vector3<T> omega(xi[0], xi[1], xi[2]);
  const Vector3<T> rho(xi[3], xi[4], xi[5]);
  const T theta2 = omega.squaredNorm();
  T a, c, b, d;  // q = (a·ω, c); t = ρ + b·ω×ρ + d·ω×(ω×ρ)
  if (theta2 < T(kExpTaylorThetaSquared)) {
    const T t2 = theta2, t4 = t2 * t2, t6 = t4 * t2, t8 = t4 * t4;
    a = T(0.5) - t2 / 48.0 + t4 / 3840.0 - t6 / 645120.0 + t8 / 185794560.0;  // sin(θ/2)/θ
    c = T(1.0) - t2 / 8.0 + t4 / 384.0 - t6 / 46080.0 + t8 / 10321920.0;    // cos(θ/2)
    b = T(0.5) - t2 / 24.0 + t4 / 720.0 - t6 / 40320.0 + t8 / 3628800.0;    // (1−cos θ)/θ²
    d = T(1.0 / 6.0) - t2 / 120.0 + t4 / 5040.0 - t6 / 362880.0 + t8 / 39916800.0;  // (θ−sin θ)/θ³
  } else {
    const T theta = sqrt(theta2);
    const T s = sin(theta / 2.0);
    a = s / theta;
    c = cos(theta / 2.0);
    b = T(2.0) * s * s / theta2;  // 1 − cos θ = 2 sin²(θ/2): no cancellation
    d = (theta - sin(theta)) / (theta2 * theta);
  }
  const Vector3<T> omega_cross_rho = omega.cross(rho);
  const Vector3<T> t = rho + b * omega_cross_rho + d * omega.cross(omega_cross_rho);
  const Eigen::Quaternion<T> q(c, a * omega.x(), a * omega.y(), a * omega.z());
  Store(q, t, pose);
}

// ξ = Log(pose) = [ω; ρ], θ = |ω| ∈ [0, π]. q and −q give the same ξ.
template <typename T>
void SE3Log(const T* pose, T* xi) {
  using namespace se3_internal;
  using std::atan2;
  using std::sqrt;
  Eigen::Quaternion<T> q = Rotation(pose);
  if (q.w() < T(0)) q.coeffs() = -q.coeffs();
  const Vector3<T> v = q.vec();
  const T w = q.w();
  const T s2 = v.squaredNorm();
  // ω = f·v with f = 2·atan2(|v|, w)/|v|; (θ/2)·cot(θ/2) = f·w/2.
  T f, d;  // ρ = t − ½ ω×t + d·ω×(ω×t), d = (1 − (θ/2)cot(θ/2))/θ²
  if (s2 < T(kLogTaylorX2) * w * w) {
    // θ = 2·atan(x), x = |v|/w < 0.01: f = (2/w)(1 − x²/3 + x⁴/5 − x⁶/7 + x⁸/9).
    const T x2 = s2 / (w * w), x4 = x2 * x2;
    f = T(2.0) / w * (T(1.0) - x2 / 3.0 + x4 / 5.0 - x4 * x2 / 7.0 + x4 * x4 / 9.0);
    const T t2 = f * f * s2, t4 = t2 * t2, t6 = t4 * t2;
    d = T(1.0 / 12.0) + t2 / 720.0 + t4 / 30240.0 + t6 / 1209600.0;
  } else {
    const T s = sqrt(s2);
    f = T(2.0) * atan2(s, w) / s;
    const T theta2 = f * f * s2;
    d = (T(1.0) - f * w / 2.0) / theta2;
  }
  const Vector3<T> omega = f * v;
  const Vector3<T> t = Translation(pose);
  const Vector3<T> omega_cross_t = omega.cross(t);
  const Vector3<T> rho = t - T(0.5) * omega_cross_t + d * omega.cross(omega_cross_t);
  for (int i = 0; i < 3; ++i) {
    xi[i] = omega[i];
    xi[3 + i] = rho[i];
  }
}

// --- double conveniences on Pose ---

inline Pose Compose(const Pose& a, const Pose& b) {
  Pose ab;
  PoseCompose(a.data.data(), b.data.data(), ab.data.data());
  return ab;
}

inline Pose Inverse(const Pose& pose) {
  Pose inverse;
  PoseInverse(pose.data.data(), inverse.data.data());
  return inverse;
}

inline Eigen::Vector3d Transform(const Pose& pose, const Eigen::Vector3d& p) {
  Eigen::Vector3d out;
  PoseTransformPoint(pose.data.data(), p.data(), out.data());
  return out;
}

inline Pose Exp(const Vector6d& xi) {
  Pose pose;
  SE3Exp(xi.data(), pose.data.data());
  return pose;
}

inline Vector6d Log(const Pose& pose) {
  Vector6d xi;
  SE3Log(pose.data.data(), xi.data());
  return xi;
}

// Ad(T) in tangent order [ω; ρ]: [R 0; [t]×R R], so that T · Exp(ξ) · T⁻¹ = Exp(Ad(T) · ξ).
inline Matrix6d Adjoint(const Pose& pose) {
  const Eigen::Matrix3d r = pose.rotation().toRotationMatrix();
  const Eigen::Vector3d t = pose.translation();
  Eigen::Matrix3d t_hat;
  t_hat << 0, -t.z(), t.y(), t.z(), 0, -t.x(), -t.y(), t.x(), 0;
  Matrix6d ad = Matrix6d::Zero();
  ad.block<3, 3>(0, 0) = r;
  ad.block<3, 3>(3, 0) = t_hat * r;
  ad.block<3, 3>(3, 3) = r;
  return ad;
}

// Rotation angle in [0, π], robust near 0 and π.
inline double RotationAngle(const Pose& pose) {
  const Eigen::Quaterniond q = pose.rotation();
  return 2.0 * std::atan2(q.vec().norm(), std::abs(q.w()));
}

// Upper-triangular S with Sᵀ·S = information (whitening: r ← S·r, SPEC §1.5). The information
// must be symmetric positive definite (graph_io checks it on reading).
template <int N>
Eigen::Matrix<double, N, N> SqrtInformation(const Eigen::Matrix<double, N, N>& information) {
  return information.llt().matrixU();
}

}  // namespace dynslam

#endif  // DYNSLAM_SE3_H_
