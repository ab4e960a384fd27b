// SE(3) Exp/Log against closed-form values, Jet derivatives at the singular points, and the
// manifold's invariants (SPEC §0).
#include "dynslam/se3.h"

#include <cmath>
#include <random>

#include <ceres/jet.h>
#include <ceres/manifold_test_utils.h>
#include <gtest/gtest.h>

#include "dynslam/se3_manifold.h"

namespace dynslam {
namespace {

Vector6d Xi(double wx, double wy, double wz, double rx, double ry, double rz) {
  Vector6d xi;
  xi << wx, wy, wz, rx, ry, rz;
  return xi;
}

// Rotation θ about z applied to ρ = (1, 0, 0): V·ρ = (sin θ/θ, (1 − cos θ)/θ, 0) by hand from
// V = I + (1−cos θ)/θ²·W + (θ−sin θ)/θ³·W², W·ρ = (0, θ, 0), W²·ρ = (−θ², 0, 0).
// (1 − cos θ) is written 2·sin²(θ/2) so that the expected value has no cancellation.
TEST(SE3Test, ExpMatchesClosedFormAboutZ) {
  for (const double theta : {M_PI / 2, 1e-3, 0.05, 0.2, 3.0}) {
    const Pose pose = Exp(Xi(0, 0, theta, 1, 0, 0));
    const Eigen::Matrix3d expected_rotation =
        Eigen::AngleAxisd(theta, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    EXPECT_LT((pose.rotation().toRotationMatrix() - expected_rotation).norm(), 1e-15) << theta;
    const double half_sine = std::sin(theta / 2);
    EXPECT_NEAR(pose.translation().x(), std::sin(theta) / theta, 3e-16) << theta;
    EXPECT_NEAR(pose.translation().y(), 2 * half_sine * half_sine / theta, 3e-16) << theta;
    EXPECT_EQ(pose.translation().z(), 0.0);
  }
  const Pose quarter = Exp(Xi(0, 0, M_PI / 2, 1, 0, 0));
  EXPECT_NEAR(quarter.translation().x(), 2 / M_PI, 3e-16);
  EXPECT_NEAR(quarter.translation().y(), 2 / M_PI, 3e-16);
}

TEST(SE3Test, ExpOfPureTranslationIsTheTranslation) {
  const Pose pose = Exp(Xi(0, 0, 0, 1, -2, 3));
  EXPECT_EQ(pose.rotation().coeffs(), Eigen::Quaterniond::Identity().coeffs());
  EXPECT_EQ(pose.translation(), Eigen::Vector3d(1, -2, 3));
}

TEST(SE3Test, LogInvertsExpAcrossAngles) {
  const Eigen::Vector3d axis = Eigen::Vector3d(0.3, -0.5, 0.8).normalized();
  const Eigen::Vector3d rho(0.7, -1.2, 2.5);
  for (const double theta : {0.0, 1e-12, 1e-9, 1e-5, 1e-3, 0.0199, 0.0201, 0.09, 0.11, 1.0, 2.5,
                             M_PI - 1e-3, M_PI - 1e-6}) {
    Vector6d xi;
    xi << theta * axis, rho;
    const Vector6d back = Log(Exp(xi));
    EXPECT_LT((back - xi).norm(), 1e-14 * std::max(1.0, xi.norm())) << "theta " << theta;
  }
}

TEST(SE3Test, LogAtExactlyPiGivesAnAngleOfPiAndTheSamePose) {
  Pose pose;  // rotation of π about x: q = (1, 0, 0, 0), with a translation
  pose.data = {1, 0, 0, 0, 0.5, 1.5, -2};
  const Vector6d xi = Log(pose);
  EXPECT_NEAR(xi.head<3>().norm(), M_PI, 1e-15);
  const Pose back = Exp(xi);
  EXPECT_LT((back.rotation().toRotationMatrix() - pose.rotation().toRotationMatrix()).norm(), 1e-14);
  EXPECT_LT((back.translation() - pose.translation()).norm(), 1e-14);
}

TEST(SE3Test, QuaternionSignDoesNotChangeLog) {
  const Pose pose = Exp(Xi(0.4, -0.2, 1.1, 1, 2, 3));
  Pose negated = pose;
  negated.rotation().coeffs() *= -1;
  EXPECT_LT((Log(pose) - Log(negated)).norm(), 1e-15);
}

TEST(SE3Test, ComposeInverseAndTransformAgreeWithIsometry) {
  const Pose a = Exp(Xi(0.4, -0.2, 1.1, 1, 2, 3));
  const Pose b = Exp(Xi(-1.0, 0.3, 0.2, -4, 0.5, 1));
  const Eigen::Isometry3d expected = a.ToIsometry() * b.ToIsometry().inverse();
  const Pose ab_inv = Compose(a, Inverse(b));
  EXPECT_LT((ab_inv.ToIsometry().matrix() - expected.matrix()).norm(), 1e-14);
  const Eigen::Vector3d p(0.3, -7, 2);
  EXPECT_LT((Transform(a, p) - a.ToIsometry() * p).norm(), 1e-14);
}

// The adjoint in [ω; ρ] order: T · Exp(ξ) · T⁻¹ = Exp(Ad(T) · ξ), checked on a generic pose
// and by the hand value of a pure translation (ω about z moves ρ by t × ω).
TEST(SE3Test, AdjointConjugatesTheTangent) {
  const Pose t = Exp(Xi(0.4, -0.2, 1.1, 1, 2, 3));
  const Vector6d xi = Xi(0.05, 0.3, -0.2, 0.7, -1.5, 0.4);
  EXPECT_LT((Log(Compose(Compose(t, Exp(xi)), Inverse(t))) - Adjoint(t) * xi).norm(), 1e-12);
  const Pose shift = Exp(Xi(0, 0, 0, 0, 5, 0));
  Matrix6d expected = Matrix6d::Identity();  // [t]× for t = (0, 5, 0): [[0 0 5] [0 0 0] [-5 0 0]]
  expected(3, 2) = 5;
  expected(5, 0) = -5;
  EXPECT_LT((Adjoint(shift) - expected).norm(), 1e-14);
}

// ∂Exp/∂ξ and ∂Log/∂pose through Jets at the singular point θ = 0 are finite and equal central
// differences.
TEST(SE3Test, JetDerivativesAtIdentityMatchCentralDifferences) {
  using Jet = ceres::Jet<double, 6>;
  Jet xi[6];
  for (int i = 0; i < 6; ++i) xi[i] = Jet(0.0, i);
  Jet pose[7];
  SE3Exp(xi, pose);
  const double h = 1e-6;
  for (int i = 0; i < 6; ++i) {
    Vector6d plus = Vector6d::Zero(), minus = Vector6d::Zero();
    plus[i] = h;
    minus[i] = -h;
    const Pose p = Exp(plus), m = Exp(minus);
    for (int k = 0; k < 7; ++k) {
      const double numeric = (p.data[k] - m.data[k]) / (2 * h);
      ASSERT_TRUE(std::isfinite(pose[k].v[i]));
      EXPECT_NEAR(pose[k].v[i], numeric, 1e-9) << "d pose[" << k << "] / d xi[" << i << "]";
    }
  }
  // Log at the identity, perturbed along the manifold: d Log(Exp(ξ)) / dξ = I.
  Jet logged[6];
  SE3Log(pose, logged);
  for (int k = 0; k < 6; ++k) {
    for (int i = 0; i < 6; ++i) EXPECT_NEAR(logged[k].v[i], k == i ? 1.0 : 0.0, 1e-15);
  }
}

TEST(SE3Test, SqrtInformationIsTheUpperCholeskyFactor) {
  Matrix6d a = Matrix6d::Random();
  const Matrix6d information = a * a.transpose() + Matrix6d::Identity();
  const Matrix6d s = SqrtInformation(information);
  EXPECT_LT((s.transpose() * s - information).norm(), 1e-12);
  EXPECT_LT(s.triangularView<Eigen::StrictlyLower>().toDenseMatrix().norm(), 0.0 + 1e-300);
}

// The autodiff shortcuts of the residuals: composing with a constant pose and whitening with an
// upper-triangular factor give, value and derivative, what the generic Jet code gives.
TEST(SE3Test, ComposeConstantAndWhitenEqualTheGenericJetCode) {
  using Jet = ceres::Jet<double, 7>;
  const Pose a = Exp(Xi(0.3, -1.2, 2.5, 1.0, -2.0, 0.5));
  const Pose b = Exp(Xi(-2.0, 0.4, 0.9, -3.0, 0.2, 7.0));
  Jet b_jet[7], a_jet[7], expected[7], ours[7];
  for (int i = 0; i < 7; ++i) {
    b_jet[i] = Jet(b.data[i], i);
    a_jet[i] = Jet(a.data[i]);
  }
  PoseCompose(a_jet, b_jet, expected);
  PoseComposeConstant(a, b_jet, ours);
  for (int k = 0; k < 7; ++k) {
    EXPECT_NEAR(ours[k].a, expected[k].a, 1e-15 * (1 + std::abs(expected[k].a))) << k;
    for (int i = 0; i < 7; ++i) EXPECT_NEAR(ours[k].v[i], expected[k].v[i], 1e-15) << k << i;
  }
  Matrix6d m = Matrix6d::Random();
  const Matrix6d s = SqrtInformation(Matrix6d(m * m.transpose() + Matrix6d::Identity()));
  Jet e[6], r[6];
  for (int i = 0; i < 6; ++i) e[i] = ours[i];
  Whiten(s, e, r);
  const Eigen::Matrix<Jet, 6, 1> generic =
      s.cast<Jet>() * Eigen::Map<const Eigen::Matrix<Jet, 6, 1>>(e);
  for (int k = 0; k < 6; ++k) {
    EXPECT_NEAR(r[k].a, generic[k].a, 1e-14 * (1 + std::abs(generic[k].a))) << k;
    for (int i = 0; i < 7; ++i) {
      EXPECT_NEAR(r[k].v[i], generic[k].v[i], 1e-14 * (1 + std::abs(generic[k].v[i]))) << k;
    }
  }
}

// Ceres's manifold invariants (Plus/Minus inverse of each other, Jacobians against numeric
// differences, MinusJacobian·PlusJacobian = I) at identity, generic poses, near π, and for
// small and generic steps (the invariant checks are relative to the step, so a 1e-9 step
// would measure only rounding; the 1e-9 rad case is covered by the pose at 1e-9 rad).
TEST(SE3ManifoldTest, InvariantsHold) {
  using namespace ceres;  // the invariant matchers live there
  const SE3Manifold manifold;
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> uniform(-1, 1);
  auto random_xi = [&](double scale) {
    Vector6d xi;
    for (int i = 0; i < 6; ++i) xi[i] = scale * uniform(rng);
    return xi;
  };
  const Eigen::Vector3d axis = Eigen::Vector3d(1, 2, -0.5).normalized();
  std::vector<Pose> points = {Pose::Identity(), Exp(Xi(1e-9, 0, 0, 0, 0, 0)), Exp(random_xi(1.0)),
                              Exp(random_xi(2.0))};
  Vector6d near_pi;
  near_pi << (M_PI - 1e-4) * axis, 1, -2, 0.5;
  points.push_back(Exp(near_pi));
  for (const Pose& pose : points) {
    for (const double scale : {1e-3, 0.1, 0.8}) {
      const Vector x = Eigen::Map<const Eigen::Matrix<double, 7, 1>>(pose.data.data());
      const Vector delta = random_xi(scale);
      const Pose y_pose = Compose(pose, Exp(random_xi(scale)));
      const Vector y = Eigen::Map<const Eigen::Matrix<double, 7, 1>>(y_pose.data.data());
      SCOPED_TRACE("pose " + std::to_string(&pose - points.data()) + " scale " + std::to_string(scale));
      EXPECT_THAT_MANIFOLD_INVARIANTS_HOLD(manifold, x, delta, y, 1e-9);
    }
  }
}

}  // namespace
}  // namespace dynslam
