// Each residual of SPEC §1.2–§1.3: zero at a consistent configuration, one value computed by
// hand, and its Jacobian through the manifold's Plus against central differences at the
// identity, at 1e-9 rad, at a generic pose and near π (docs/STYLE.md).
#include <cmath>
#include <memory>
#include <random>
#include <vector>

#include <ceres/autodiff_cost_function.h>
#include <ceres/cost_function.h>
#include <gtest/gtest.h>

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
#include "dynslam/se3.h"
#include "dynslam/se3_manifold.h"

namespace dynslam {
namespace {

using Block = std::vector<double>;

Block PoseBlock(const Pose& pose) { return Block(pose.data.begin(), pose.data.end()); }
Pose Translation(double x, double y, double z) {
  Pose pose;
  pose.translation() = Eigen::Vector3d(x, y, z);
  return pose;
}
Pose RotationZ(double angle) {
  return Pose::FromRotationTranslation(
      Eigen::Quaterniond(Eigen::AngleAxisd(angle, Eigen::Vector3d::UnitZ())), Eigen::Vector3d::Zero());
}

Eigen::VectorXd Residual(const ceres::CostFunction& cost, const std::vector<Block>& blocks) {
  std::vector<const double*> parameters;
  for (const Block& block : blocks) parameters.push_back(block.data());
  Eigen::VectorXd residual(cost.num_residuals());
  EXPECT_TRUE(cost.Evaluate(parameters.data(), residual.data(), nullptr));
  return residual;
}

// Local Jacobians (ambient Jacobian × PlusJacobian for poses) against central differences of the
// residual at Plus(x, ±h·e_i). Returns the largest relative difference.
double JacobianError(const ceres::CostFunction& cost, const std::vector<Block>& blocks) {
  const SE3Manifold manifold;
  const int m = cost.num_residuals();
  std::vector<const double*> parameters;
  std::vector<Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>> ambient;
  std::vector<double*> jacobians;
  for (const Block& block : blocks) {
    parameters.push_back(block.data());
    ambient.emplace_back(m, static_cast<int>(block.size()));
  }
  for (auto& j : ambient) jacobians.push_back(j.data());
  Eigen::VectorXd residual(m);
  EXPECT_TRUE(cost.Evaluate(parameters.data(), residual.data(), jacobians.data()));

  double worst = 0;
  const double h = 1e-6;
  for (size_t b = 0; b < blocks.size(); ++b) {
    const bool is_pose = blocks[b].size() == kPoseSize;
    Eigen::MatrixXd analytic = ambient[b];
    if (is_pose) {
      Eigen::Matrix<double, 7, 6, Eigen::RowMajor> plus_jacobian;
      manifold.PlusJacobian(blocks[b].data(), plus_jacobian.data());
      analytic = ambient[b] * plus_jacobian;
    }
    for (int i = 0; i < analytic.cols(); ++i) {
      std::vector<Block> plus = blocks, minus = blocks;
      if (is_pose) {
        double delta[6] = {0, 0, 0, 0, 0, 0};
        delta[i] = h;
        manifold.Plus(blocks[b].data(), delta, plus[b].data());
        delta[i] = -h;
        manifold.Plus(blocks[b].data(), delta, minus[b].data());
      } else {
        plus[b][i] += h;
        minus[b][i] -= h;
      }
      const Eigen::VectorXd numeric = (Residual(cost, plus) - Residual(cost, minus)) / (2 * h);
      const double scale = std::max(1.0, numeric.norm());
      worst = std::max(worst, (analytic.col(i) - numeric).norm() / scale);
    }
  }
  return worst;
}

// The poses a Jacobian is checked at (docs/STYLE.md): identity, 1e-9 rad, generic, near π.
std::vector<Pose> CheckPoses() {
  Vector6d tiny, generic, near_pi;
  tiny << 1e-9, 0, 0, 0.1, 0.2, 0.3;
  generic << 0.4, -0.7, 0.2, 1.5, -2.0, 0.7;
  near_pi << (M_PI - 1e-4) * Eigen::Vector3d(0.6, 0.8, 0).normalized(), -1, 3, 2;
  return {Pose::Identity(), Exp(tiny), Exp(generic), Exp(near_pi)};
}

Matrix6d Information6() {
  Matrix6d a;
  a.setZero();
  a.diagonal() << 9, 4, 1, 25, 16, 0.25;
  a(0, 4) = a(4, 0) = 0.5;  // a non-diagonal term exercises the full S
  return a;
}
const Eigen::Vector3d kZero3 = Eigen::Vector3d::Zero();

Eigen::Matrix3d Information3() {
  Eigen::Matrix3d a;
  a << 4, 0.5, 0, 0.5, 9, 0.2, 0, 0.2, 1;
  return a;
}

const Pose kOffset = Exp((Vector6d() << 0.1, 0.2, -0.3, 0.5, -1.0, 2.0).finished());

TEST(PosePriorErrorTest, ZeroHandValueAndJacobian) {
  const Pose z = kOffset;
  std::unique_ptr<ceres::CostFunction> cost(PosePriorError::Create(z, Information6()));
  EXPECT_LT(Residual(*cost, {PoseBlock(z)}).norm(), 1e-14);
  // X = translation (1, 2, 3), Z = I, information diag(1,1,1,4,4,4): r = [0 0 0 2 4 6].
  Matrix6d info = Matrix6d::Identity();
  info.diagonal().tail<3>().setConstant(4);
  std::unique_ptr<ceres::CostFunction> hand(PosePriorError::Create(Pose::Identity(), info));
  Eigen::VectorXd expected(6);
  expected << 0, 0, 0, 2, 4, 6;
  EXPECT_LT((Residual(*hand, {PoseBlock(Translation(1, 2, 3))}) - expected).norm(), 1e-15);
  for (const Pose& x : CheckPoses()) {
    EXPECT_LT(JacobianError(*cost, {PoseBlock(x)}), 1e-7);
    EXPECT_LT(JacobianError(*hand, {PoseBlock(x)}), 1e-7);
  }
}

TEST(PoseBetweenErrorTest, ZeroHandValueAndJacobian) {
  std::unique_ptr<ceres::CostFunction> cost(PoseBetweenError::Create(kOffset, Information6()));
  const Pose a = Exp((Vector6d() << -0.5, 1.0, 0.3, 4, 5, 6).finished());
  EXPECT_LT(Residual(*cost, {PoseBlock(a), PoseBlock(Compose(a, kOffset))}).norm(), 1e-13);
  // A = I, B = rotation 0.3 rad about z, Z = I, information I: r = [0 0 0.3 0 0 0].
  std::unique_ptr<ceres::CostFunction> hand(
      PoseBetweenError::Create(Pose::Identity(), Matrix6d::Identity()));
  Eigen::VectorXd expected(6);
  expected << 0, 0, 0.3, 0, 0, 0;
  EXPECT_LT((Residual(*hand, {PoseBlock(Pose::Identity()), PoseBlock(RotationZ(0.3))}) - expected)
                .norm(),
            1e-15);
  for (const Pose& x : CheckPoses()) {
    EXPECT_LT(JacobianError(*cost, {PoseBlock(x), PoseBlock(Compose(x, kOffset))}), 1e-7);
    EXPECT_LT(JacobianError(*cost, {PoseBlock(kOffset), PoseBlock(x)}), 1e-7);
  }
}

TEST(PointMeasurementErrorTest, ZeroHandValueAndJacobian) {
  const Eigen::Vector3d p_w(1, -2, 8);
  const Eigen::Vector3d p_c = Transform(Inverse(kOffset), p_w);
  std::unique_ptr<ceres::CostFunction> cost(PointMeasurementError::Create(p_c, Information3()));
  EXPECT_LT(Residual(*cost, {PoseBlock(kOffset), Block{1, -2, 8}}).norm(), 1e-13);
  // X = translation (1,0,0), m = (1,2,3), z = 0, information diag(1,4,9): r = (0, 4, 9).
  std::unique_ptr<ceres::CostFunction> hand(PointMeasurementError::Create(
      Eigen::Vector3d::Zero(), Eigen::Vector3d(1, 4, 9).asDiagonal()));
  EXPECT_LT((Residual(*hand, {PoseBlock(Translation(1, 0, 0)), Block{1, 2, 3}}) -
             Eigen::Vector3d(0, 4, 9))
                .norm(),
            1e-15);
  for (const Pose& x : CheckPoses()) {
    EXPECT_LT(JacobianError(*cost, {PoseBlock(x), Block{1, -2, 8}}), 1e-7);
  }
}

TEST(PointMotionErrorTest, ZeroHandValueAndJacobian) {
  const Eigen::Vector3d p_prev(1, -2, 8);
  std::unique_ptr<ceres::CostFunction> cost(
      PointMotionError::Create(Eigen::Vector3d::Zero(), Information3()));
  const Eigen::Vector3d p_curr = Transform(kOffset, p_prev);
  EXPECT_LT(Residual(*cost, {Block{1, -2, 8}, Block{p_curr.x(), p_curr.y(), p_curr.z()},
                             PoseBlock(kOffset)})
                .norm(),
            1e-13);
  // H = translation (1,0,0), m_prev = 0, m_curr = (2,0,0), z = 0, I: r = (1, 0, 0).
  std::unique_ptr<ceres::CostFunction> hand(
      PointMotionError::Create(Eigen::Vector3d::Zero(), Eigen::Matrix3d::Identity()));
  EXPECT_LT((Residual(*hand, {Block{0, 0, 0}, Block{2, 0, 0}, PoseBlock(Translation(1, 0, 0))}) -
             Eigen::Vector3d(1, 0, 0))
                .norm(),
            1e-15);
  for (const Pose& h : CheckPoses()) {
    EXPECT_LT(JacobianError(*cost, {Block{1, -2, 8}, Block{0.5, 0.5, 7}, PoseBlock(h)}), 1e-7);
  }
}

TEST(ObjectPointMeasurementErrorTest, ZeroHandValueAndJacobian) {
  const Pose camera = Exp((Vector6d() << 0.1, -0.1, 0.05, 0.3, 0.1, -2).finished());
  const Eigen::Vector3d m_o(0.5, 0.2, -1);
  const Eigen::Vector3d p_c = Transform(Inverse(camera), Transform(kOffset, m_o));
  std::unique_ptr<ceres::CostFunction> cost(
      ObjectPointMeasurementError::Create(p_c, Information3()));
  EXPECT_LT(Residual(*cost, {PoseBlock(camera), PoseBlock(kOffset), Block{0.5, 0.2, -1}}).norm(),
            1e-13);
  // X = I, L = 90° about z, m = (1,0,0), z = 0, I: r = L·m = (0, 1, 0).
  std::unique_ptr<ceres::CostFunction> hand(ObjectPointMeasurementError::Create(
      Eigen::Vector3d::Zero(), Eigen::Matrix3d::Identity()));
  EXPECT_LT((Residual(*hand, {PoseBlock(Pose::Identity()), PoseBlock(RotationZ(M_PI / 2)),
                              Block{1, 0, 0}}) -
             Eigen::Vector3d(0, 1, 0))
                .norm(),
            1e-15);
  for (const Pose& x : CheckPoses()) {
    EXPECT_LT(JacobianError(*cost, {PoseBlock(x), PoseBlock(kOffset), Block{0.5, 0.2, -1}}), 1e-7);
    EXPECT_LT(JacobianError(*cost, {PoseBlock(camera), PoseBlock(x), Block{0.5, 0.2, -1}}), 1e-7);
  }
}

TEST(ObjectPointMotionErrorTest, ZeroHandValueAndJacobian) {
  const Pose l_prev = Exp((Vector6d() << 0.2, 0.1, -0.4, 3, 1, 10).finished());
  const Pose h = kOffset;
  const Pose l_curr = Compose(h, l_prev);  // kinematics hold: H = L_curr · L_prev⁻¹
  std::unique_ptr<ceres::CostFunction> cost(ObjectPointMotionError::Create(kZero3, Information3()));
  const Block m_o{0.5, 0.2, -1};
  EXPECT_LT(Residual(*cost, {PoseBlock(l_prev), PoseBlock(l_curr), PoseBlock(h), m_o}).norm(),
            1e-13);
  // L_prev = I, L_curr = translation (0,0,1), H = I, m = (1,0,0), I: r = (0, 0, 1).
  std::unique_ptr<ceres::CostFunction> hand(
      ObjectPointMotionError::Create(kZero3, Eigen::Matrix3d::Identity()));
  EXPECT_LT((Residual(*hand, {PoseBlock(Pose::Identity()), PoseBlock(Translation(0, 0, 1)),
                              PoseBlock(Pose::Identity()), Block{1, 0, 0}}) -
             Eigen::Vector3d(0, 0, 1))
                .norm(),
            1e-15);
  for (const Pose& x : CheckPoses()) {
    EXPECT_LT(JacobianError(*cost, {PoseBlock(x), PoseBlock(l_curr), PoseBlock(h), m_o}), 1e-7);
    EXPECT_LT(JacobianError(*cost, {PoseBlock(l_prev), PoseBlock(l_curr), PoseBlock(x), m_o}), 1e-7);
  }
}

// SPEC §3.3: oc_a's edge carries the front-end motion edge's z with the same sign, so at points
// p = L·m both residuals are equal: m_curr − H·m_prev − z.
TEST(ObjectPointMotionErrorTest, MeasurementAsTheWorldCentricMotionEdge) {
  const Pose l_prev = Exp((Vector6d() << 0.2, 0.1, -0.4, 3, 1, 10).finished());
  const Pose l_curr = Exp((Vector6d() << 0.25, 0.05, -0.3, 3.5, 1, 11).finished());
  const Pose h = kOffset;
  const Eigen::Vector3d z(0.03, -0.07, 0.11), m_o(0.5, 0.2, -1);
  std::unique_ptr<ceres::CostFunction> object(ObjectPointMotionError::Create(z, Information3()));
  std::unique_ptr<ceres::CostFunction> world(PointMotionError::Create(z, Information3()));
  const Eigen::Vector3d p_prev = Transform(l_prev, m_o), p_curr = Transform(l_curr, m_o);
  const Eigen::Vector3d r_object = Residual(
      *object, {PoseBlock(l_prev), PoseBlock(l_curr), PoseBlock(h), Block{m_o[0], m_o[1], m_o[2]}});
  const Eigen::Vector3d r_world =
      Residual(*world, {Block{p_prev[0], p_prev[1], p_prev[2]},
                        Block{p_curr[0], p_curr[1], p_curr[2]}, PoseBlock(h)});
  EXPECT_LT((r_object - r_world).norm(), 1e-12);
  std::unique_ptr<ceres::CostFunction> without(
      ObjectPointMotionError::Create(kZero3, Information3()));
  const Eigen::Vector3d r_without = Residual(
      *without, {PoseBlock(l_prev), PoseBlock(l_curr), PoseBlock(h), Block{m_o[0], m_o[1], m_o[2]}});
  EXPECT_LT((r_without - r_object - SqrtInformation(Information3()) * z).norm(), 1e-12);
}

TEST(ObjectKinematicErrorTest, ZeroHandValueAndJacobian) {
  const Pose l_prev = Exp((Vector6d() << 0.2, 0.1, -0.4, 3, 1, 10).finished());
  const Pose h = kOffset;
  const Pose l_curr = Compose(h, l_prev);
  std::unique_ptr<ceres::CostFunction> cost(ObjectKinematicError::Create(Information6()));
  EXPECT_LT(Residual(*cost, {PoseBlock(l_prev), PoseBlock(l_curr), PoseBlock(h)}).norm(), 1e-13);
  // L_prev = L_curr = I, H = translation (1,0,0), I: r = Log(H) = [0 0 0 1 0 0].
  std::unique_ptr<ceres::CostFunction> hand(ObjectKinematicError::Create(Matrix6d::Identity()));
  Eigen::VectorXd expected(6);
  expected << 0, 0, 0, 1, 0, 0;
  EXPECT_LT((Residual(*hand, {PoseBlock(Pose::Identity()), PoseBlock(Pose::Identity()),
                              PoseBlock(Translation(1, 0, 0))}) -
             expected)
                .norm(),
            1e-15);
  for (const Pose& x : CheckPoses()) {
    EXPECT_LT(JacobianError(*cost, {PoseBlock(l_prev), PoseBlock(l_curr), PoseBlock(x)}), 1e-7);
    EXPECT_LT(JacobianError(*cost, {PoseBlock(x), PoseBlock(Compose(h, x)), PoseBlock(h)}), 1e-7);
  }
}

// SPEC §3.6: X⁻¹ · H · L_e · m − z, zero where the point is seen; the hand value with X = L_e = I,
// H a translation; Jacobians (L_e included, though the solver holds it constant) on every check
// pose.
TEST(HybridPointErrorTest, ZeroHandValueAndJacobian) {
  const Pose x = Exp((Vector6d() << 0.1, -0.3, 0.2, 4, -1, 2).finished());
  const Pose h = kOffset;
  const Pose l_e = Exp((Vector6d() << 0.2, 0.1, -0.4, 3, 1, 10).finished());
  const Eigen::Vector3d m(0.5, -1.0, 0.3);
  const Eigen::Vector3d z = Transform(Inverse(x), Transform(Compose(h, l_e), m));
  std::unique_ptr<ceres::CostFunction> cost(HybridPointError::Create(z, Information3()));
  const Block point(m.data(), m.data() + 3);
  EXPECT_LT(Residual(*cost, {PoseBlock(x), PoseBlock(h), PoseBlock(l_e), point}).norm(), 1e-13);
  std::unique_ptr<ceres::CostFunction> hand(
      HybridPointError::Create(Eigen::Vector3d(1, 1, 1), Eigen::Matrix3d::Identity()));
  // I⁻¹ · (m + (1, 0, 0)) − (1, 1, 1) with m = (0.5, −1, 0.3) = (0.5, −2, −0.7).
  EXPECT_LT((Residual(*hand, {PoseBlock(Pose::Identity()), PoseBlock(Translation(1, 0, 0)),
                              PoseBlock(Pose::Identity()), point}) -
             Eigen::Vector3d(0.5, -2, -0.7))
                .norm(),
            1e-15);
  for (const Pose& p : CheckPoses()) {
    EXPECT_LT(JacobianError(*cost, {PoseBlock(p), PoseBlock(h), PoseBlock(l_e), point}), 1e-7);
    EXPECT_LT(JacobianError(*cost, {PoseBlock(x), PoseBlock(p), PoseBlock(l_e), point}), 1e-7);
    EXPECT_LT(JacobianError(*cost, {PoseBlock(x), PoseBlock(h), PoseBlock(p), point}), 1e-7);
  }
}

// SPEC §3.6: Log((L_a⁻¹ L_b)⁻¹ (L_b⁻¹ L_c)), L_x = H_x · L_e, equals the stated equivalent form
// Ad(L_e⁻¹) · Log(H_b⁻¹ H_a H_b⁻¹ H_c); zero at a constant body-frame velocity; Jacobians.
TEST(HybridSmoothingErrorTest, EquivalentFormZeroAndJacobian) {
  const Pose l_e = Exp((Vector6d() << 0.2, 0.1, -0.4, 3, 1, 10).finished());
  const Pose h_a = Exp((Vector6d() << 0.05, -0.1, 0.3, 0.4, 0.2, -1).finished());
  const Pose h_b = Exp((Vector6d() << -0.2, 0.3, 0.1, 1, -0.5, 0.3).finished());
  const Pose h_c = Exp((Vector6d() << 0.4, 0.2, -0.3, -2, 1, 0.5).finished());
  std::unique_ptr<ceres::CostFunction> cost(HybridSmoothingError::Create(Information6()));
  const Vector6d expected = SqrtInformation(Information6()) * Adjoint(Inverse(l_e)) *
                            Log(Compose(Compose(Inverse(h_b), h_a), Compose(Inverse(h_b), h_c)));
  EXPECT_LT((Residual(*cost, {PoseBlock(h_a), PoseBlock(h_b), PoseBlock(h_c), PoseBlock(l_e)}) -
             expected)
                .norm(),
            1e-12);
  // Constant body-frame velocity V: L_b = L_a · V, L_c = L_b · V ⇒ H_x = L_x · L_e⁻¹.
  const Pose v = kOffset;
  const Pose l_a = Compose(h_a, l_e);
  const Pose l_b = Compose(l_a, v), l_c = Compose(l_b, v);
  EXPECT_LT(Residual(*cost, {PoseBlock(h_a), PoseBlock(Compose(l_b, Inverse(l_e))),
                             PoseBlock(Compose(l_c, Inverse(l_e))), PoseBlock(l_e)})
                .norm(),
            1e-12);
  for (const Pose& p : CheckPoses()) {
    EXPECT_LT(JacobianError(*cost, {PoseBlock(p), PoseBlock(h_b), PoseBlock(h_c), PoseBlock(l_e)}),
              1e-7);
    EXPECT_LT(JacobianError(*cost, {PoseBlock(h_a), PoseBlock(p), PoseBlock(h_c), PoseBlock(l_e)}),
              1e-7);
    EXPECT_LT(JacobianError(*cost, {PoseBlock(h_a), PoseBlock(h_b), PoseBlock(p), PoseBlock(l_e)}),
              1e-7);
    EXPECT_LT(JacobianError(*cost, {PoseBlock(h_a), PoseBlock(h_b), PoseBlock(h_c), PoseBlock(p)}),
              1e-7);
  }
}

// The world-frame kinematic residual (SolverOptions::kinematic_residual_frame): the object
// frame's residual turned by L_curr's rotation, so the same norm (the same cost) for any
// information; with the SPEC's isotropic information, unchanged when a rotation G turns every
// object pose (L → L·G: the segment's gauge), where the object-frame residual turns with G.
TEST(ObjectKinematicErrorTest, WorldFrameHasTheSameNormAndIgnoresTheGaugeRotation) {
  const Pose l_prev = Exp((Vector6d() << 0.2, 0.1, -0.4, 3, 1, 10).finished());
  const Pose l_curr = Compose(Exp((Vector6d() << 0.05, -0.02, 0.1, 0.3, 0.1, 1).finished()),
                              Compose(kOffset, l_prev));
  std::unique_ptr<ceres::CostFunction> object(ObjectKinematicError::Create(Information6()));
  std::unique_ptr<ceres::CostFunction> world(ObjectKinematicError::Create(Information6(), true));
  const std::vector<Block> blocks = {PoseBlock(l_prev), PoseBlock(l_curr), PoseBlock(kOffset)};
  EXPECT_GT(Residual(*object, blocks).norm(), 1.0);
  EXPECT_NEAR(Residual(*world, blocks).norm(), Residual(*object, blocks).norm(), 1e-12);
  EXPECT_GT((Residual(*world, blocks) - Residual(*object, blocks)).norm(), 1e-2);

  const Matrix6d isotropic = 10000 * Matrix6d::Identity();
  std::unique_ptr<ceres::CostFunction> object_iso(ObjectKinematicError::Create(isotropic));
  std::unique_ptr<ceres::CostFunction> world_iso(ObjectKinematicError::Create(isotropic, true));
  const Pose gauge = Pose::FromRotationTranslation(
      Eigen::Quaterniond(Eigen::AngleAxisd(0.3, Eigen::Vector3d(1, 2, 3).normalized())),
      Eigen::Vector3d::Zero());
  const std::vector<Block> turned = {PoseBlock(Compose(l_prev, gauge)),
                                     PoseBlock(Compose(l_curr, gauge)), PoseBlock(kOffset)};
  EXPECT_LT((Residual(*world_iso, turned) - Residual(*world_iso, blocks)).norm(), 1e-9);
  EXPECT_GT((Residual(*object_iso, turned) - Residual(*object_iso, blocks)).norm(), 1.0);
  for (const Pose& x : CheckPoses()) {
    EXPECT_LT(JacobianError(*world, {PoseBlock(l_prev), PoseBlock(x), PoseBlock(kOffset)}), 1e-7);
    EXPECT_LT(JacobianError(*world, {PoseBlock(x), PoseBlock(l_curr), PoseBlock(kOffset)}), 1e-7);
  }
}

// The change of variables m_L = L_a⁻¹ · w: each anchored cost function equals the residual of
// SPEC §1.3 at that m_L, whichever pose is the anchor, and its Jacobian matches differences.
TEST(WorldAnchoredObjectPointTest, EqualsTheResidualAtTheObjectFramePoint) {
  const Pose x = Exp((Vector6d() << 0.1, -0.2, 0.05, 1, 2, -3).finished());
  const Pose l_prev = Exp((Vector6d() << 0.2, 0.1, -0.4, 3, 1, 10).finished());
  const Pose l_curr = Compose(Exp((Vector6d() << 0.01, 0.02, 0, 0.1, 0, 0).finished()),
                              Compose(kOffset, l_prev));
  const Pose l_a = Exp((Vector6d() << -0.3, 0.2, 0.1, 2, 0, 9).finished());
  const Block w{4, -1, 12};
  auto m_from = [&](const Pose& anchor) {
    const Eigen::Vector3d m = Transform(Inverse(anchor), Eigen::Vector3d(w[0], w[1], w[2]));
    return Block{m.x(), m.y(), m.z()};
  };
  const ObjectPointMeasurementError measurement(Eigen::Vector3d(0.5, -0.3, 8), Information3());
  std::unique_ptr<ceres::CostFunction> plain(
      ObjectPointMeasurementError::Create(Eigen::Vector3d(0.5, -0.3, 8), Information3()));
  std::unique_ptr<ceres::CostFunction> anchored(
      WorldAnchored<ObjectPointMeasurementError, 3, 2>::AtFurtherPose(measurement));
  const std::vector<Block> anchored_blocks = {PoseBlock(x), PoseBlock(l_curr), PoseBlock(l_a), w};
  EXPECT_LT((Residual(*anchored, anchored_blocks) -
             Residual(*plain, {PoseBlock(x), PoseBlock(l_curr), m_from(l_a)}))
                .norm(),
            1e-10);
  EXPECT_LT(JacobianError(*anchored, anchored_blocks), 1e-7);

  const ObjectPointMotionError motion(kZero3, Information3());
  std::unique_ptr<ceres::CostFunction> motion_plain(ObjectPointMotionError::Create(kZero3, Information3()));
  using Motion = WorldAnchored<ObjectPointMotionError, 3, 3>;
  const std::vector<std::pair<std::unique_ptr<ceres::CostFunction>, Pose>> cases = [&] {
    std::vector<std::pair<std::unique_ptr<ceres::CostFunction>, Pose>> c;
    c.emplace_back(Motion::AtOwnPose<0>(motion), l_prev);
    c.emplace_back(Motion::AtOwnPose<1>(motion), l_curr);
    return c;
  }();
  const std::vector<Block> own = {PoseBlock(l_prev), PoseBlock(l_curr), PoseBlock(kOffset), w};
  for (const auto& [cost, anchor] : cases) {
    EXPECT_LT((Residual(*cost, own) - Residual(*motion_plain, {PoseBlock(l_prev), PoseBlock(l_curr),
                                                               PoseBlock(kOffset), m_from(anchor)}))
                  .norm(),
              1e-10);
    EXPECT_LT(JacobianError(*cost, own), 1e-7);
  }
  std::unique_ptr<ceres::CostFunction> further(Motion::AtFurtherPose(motion));
  const std::vector<Block> further_blocks = {PoseBlock(l_prev), PoseBlock(l_curr),
                                             PoseBlock(kOffset), PoseBlock(l_a), w};
  EXPECT_LT((Residual(*further, further_blocks) -
             Residual(*motion_plain,
                      {PoseBlock(l_prev), PoseBlock(l_curr), PoseBlock(kOffset), m_from(l_a)}))
                .norm(),
            1e-10);
  EXPECT_LT(JacobianError(*further, further_blocks), 1e-7);
}

// The chain rule through m_L gives the Jacobians of one autodiff pass over all blocks at once
// (the residual written as a single functor, below) to rounding, whichever pose is the anchor and
// whichever Jacobians Ceres asks for.
template <typename Inner, int kAnchor>
struct OnePassAnchored {  // kAnchor < 3: one of Inner's poses; 3: a further pose block
  Inner inner;
  template <typename T>
  bool operator()(const T* const a, const T* const b, const T* const c, const T* const d,
                  T* residual) const {  // (L_prev, L_curr, H, w) or (X, L, L_a, w)
    const T* const poses[] = {a, b, c};
    T m_o[3];
    if constexpr (kAnchor < 3) {
      PoseInverseTransformPoint(poses[kAnchor], d, m_o);
      return inner(a, b, c, m_o, residual);
    } else {
      PoseInverseTransformPoint(c, d, m_o);
      return inner(a, b, m_o, residual);
    }
  }
  template <typename T>
  bool operator()(const T* const a, const T* const b, const T* const c, const T* const l_a,
                  const T* const w, T* residual) const {  // (L_prev, L_curr, H, L_a, w)
    T m_o[3];
    PoseInverseTransformPoint(l_a, w, m_o);
    return inner(a, b, c, m_o, residual);
  }
};

using Jacobians = std::vector<Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>;

// Evaluates with Jacobians of the blocks in `wanted` only (null pointers for the others).
Jacobians EvaluateSome(const ceres::CostFunction& cost, const std::vector<Block>& blocks,
                       const std::vector<bool>& wanted, Eigen::VectorXd* residual) {
  std::vector<const double*> parameters;
  Jacobians jacobians;
  std::vector<double*> pointers;
  for (size_t b = 0; b < blocks.size(); ++b) {
    parameters.push_back(blocks[b].data());
    jacobians.emplace_back(Eigen::MatrixXd::Constant(cost.num_residuals(), blocks[b].size(), 7.0));
  }
  for (size_t b = 0; b < blocks.size(); ++b) pointers.push_back(wanted[b] ? jacobians[b].data() : nullptr);
  residual->resize(cost.num_residuals());
  EXPECT_TRUE(cost.Evaluate(parameters.data(), residual->data(), pointers.data()));
  return jacobians;
}

void ExpectSameAsOnePass(const ceres::CostFunction& chained, const ceres::CostFunction& one_pass,
                         const std::vector<Block>& blocks) {
  const size_t n = blocks.size();
  std::vector<std::vector<bool>> requests = {std::vector<bool>(n, true)};
  for (size_t b = 0; b < n; ++b) {
    std::vector<bool> only(n, false);
    only[b] = true;
    requests.push_back(only);
  }
  for (const std::vector<bool>& wanted : requests) {
    Eigen::VectorXd r_chained, r_one_pass;
    const Jacobians j_chained = EvaluateSome(chained, blocks, wanted, &r_chained);
    const Jacobians j_one_pass = EvaluateSome(one_pass, blocks, std::vector<bool>(n, true), &r_one_pass);
    EXPECT_LT((r_chained - r_one_pass).norm(), 1e-13 * (1 + r_one_pass.norm()));
    EXPECT_LT((Residual(chained, blocks) - r_one_pass).norm(), 1e-13 * (1 + r_one_pass.norm()));
    for (size_t b = 0; b < n; ++b) {
      if (!wanted[b]) {
        EXPECT_TRUE((j_chained[b].array() == 7.0).all()) << "block " << b << " was not asked for";
        continue;
      }
      EXPECT_LT((j_chained[b] - j_one_pass[b]).norm(), 1e-12 * (1 + j_one_pass[b].norm()))
          << "block " << b;
    }
  }
}

TEST(WorldAnchoredObjectPointTest, ChainRuleGivesTheOnePassJacobians) {
  const Pose x = Exp((Vector6d() << 0.1, -0.2, 0.05, 1, 2, -3).finished());
  const Pose l_prev = Exp((Vector6d() << 0.2, 0.1, -0.4, 3, 1, 10).finished());
  const Pose l_curr = Compose(kOffset, l_prev);
  const Pose l_a = Exp((Vector6d() << -0.3, 0.2, 0.1, 2, 0, 9).finished());
  const Block w{4, -1, 12};

  const ObjectPointMeasurementError measurement(Eigen::Vector3d(0.5, -0.3, 8), Information3());
  std::unique_ptr<ceres::CostFunction> chained(
      WorldAnchored<ObjectPointMeasurementError, 3, 2>::AtFurtherPose(measurement));
  ceres::AutoDiffCostFunction<OnePassAnchored<ObjectPointMeasurementError, 3>, 3, kPoseSize,
                              kPoseSize, kPoseSize, kPointSize>
      one_pass(new OnePassAnchored<ObjectPointMeasurementError, 3>{measurement});
  ExpectSameAsOnePass(*chained, one_pass, {PoseBlock(x), PoseBlock(l_curr), PoseBlock(l_a), w});

  const ObjectPointMotionError motion(kZero3, Information3());
  using Motion = WorldAnchored<ObjectPointMotionError, 3, 3>;
  const std::vector<Block> own = {PoseBlock(l_prev), PoseBlock(l_curr), PoseBlock(kOffset), w};
  std::unique_ptr<ceres::CostFunction> at_prev(Motion::AtOwnPose<0>(motion));
  ceres::AutoDiffCostFunction<OnePassAnchored<ObjectPointMotionError, 0>, 3, kPoseSize, kPoseSize,
                              kPoseSize, kPointSize>
      one_pass_prev(new OnePassAnchored<ObjectPointMotionError, 0>{motion});
  ExpectSameAsOnePass(*at_prev, one_pass_prev, own);
  std::unique_ptr<ceres::CostFunction> at_curr(Motion::AtOwnPose<1>(motion));
  ceres::AutoDiffCostFunction<OnePassAnchored<ObjectPointMotionError, 1>, 3, kPoseSize, kPoseSize,
                              kPoseSize, kPointSize>
      one_pass_curr(new OnePassAnchored<ObjectPointMotionError, 1>{motion});
  ExpectSameAsOnePass(*at_curr, one_pass_curr, own);
  std::unique_ptr<ceres::CostFunction> further(Motion::AtFurtherPose(motion));
  ceres::AutoDiffCostFunction<OnePassAnchored<ObjectPointMotionError, 3>, 3, kPoseSize, kPoseSize,
                              kPoseSize, kPoseSize, kPointSize>
      one_pass_further(new OnePassAnchored<ObjectPointMotionError, 3>{motion});
  ExpectSameAsOnePass(*further, one_pass_further,
                      {PoseBlock(l_prev), PoseBlock(l_curr), PoseBlock(kOffset), PoseBlock(l_a), w});
}

// SPEC §7 item 2: (m_prev − H⁻¹·m_curr)/σ. H = translation (1,0,0), m_prev = 0,
// m_curr = (2,0,0), σ = 0.1: H⁻¹·m_curr = (1,0,0), r = (−10, 0, 0).
TEST(PointMotionErrorDscTest, HandValueZeroAndJacobian) {
  std::unique_ptr<ceres::CostFunction> cost(PointMotionErrorDsc::Create(0.1));
  EXPECT_LT((Residual(*cost, {Block{0, 0, 0}, Block{2, 0, 0}, PoseBlock(Translation(1, 0, 0))}) -
             Eigen::Vector3d(-10, 0, 0))
                .norm(),
            1e-14);
  const Eigen::Vector3d p_curr = Transform(kOffset, Eigen::Vector3d(1, -2, 8));
  EXPECT_LT(Residual(*cost, {Block{1, -2, 8}, Block{p_curr.x(), p_curr.y(), p_curr.z()},
                             PoseBlock(kOffset)})
                .norm(),
            1e-12);
  for (const Pose& h : CheckPoses()) {
    EXPECT_LT(JacobianError(*cost, {Block{1, -2, 8}, Block{0.5, 0.5, 7}, PoseBlock(h)}), 1e-7);
  }
}

// SPEC §7 item 6: L_curr⁻¹·H·L_prev·m_L — equal to m_L (not zero) when the kinematics hold.
TEST(ObjectPointMotionErrorDscTest, IsTheObjectPointWhenKinematicsHold) {
  const Pose l_prev = Exp((Vector6d() << 0.2, 0.1, -0.4, 3, 1, 10).finished());
  const Pose l_curr = Compose(kOffset, l_prev);
  std::unique_ptr<ceres::CostFunction> cost(
      ObjectPointMotionErrorDsc::Create(Eigen::Matrix3d::Identity()));
  const Block m_o{0.5, 0.2, -1};
  EXPECT_LT((Residual(*cost, {PoseBlock(l_prev), PoseBlock(l_curr), PoseBlock(kOffset), m_o}) -
             Eigen::Vector3d(0.5, 0.2, -1))
                .norm(),
            1e-13);
  for (const Pose& x : CheckPoses()) {
    EXPECT_LT(JacobianError(*cost, {PoseBlock(x), PoseBlock(l_curr), PoseBlock(kOffset), m_o}), 1e-7);
  }
}

}  // namespace
}  // namespace dynslam
