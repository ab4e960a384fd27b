// The structured secant estimate of the curvature Gauss–Newton leaves out
// (src/structured_secant.h): the secant equations it promises, and its Woodbury step against a
// dense solve.
#include "src/structured_secant.h"

#include <Eigen/Dense>
#include <gtest/gtest.h>

namespace dynslam {
namespace {

// A symmetric indefinite "true" S and the pairs (s, S·s) it yields along random steps.
struct Curvature {
  Eigen::MatrixXd S;
  explicit Curvature(int n) {
    const Eigen::MatrixXd R = Eigen::MatrixXd::Random(n, n);
    S = R + R.transpose();
  }
};

TEST(StructuredSecant, MeetsTheSecantEquationOfEveryPairItKeeps) {
  std::srand(7);
  const Curvature truth(8);
  StructuredSecant secant(3);
  std::vector<Eigen::VectorXd> steps;
  for (int k = 0; k < 5; ++k) {
    steps.push_back(Eigen::VectorXd::Random(8));
    secant.Add(steps.back(), truth.S * steps.back());
  }
  // The last three pairs are kept: S s = y for each (the rank-one updates' hereditary property).
  for (int k = 2; k < 5; ++k) {
    const Eigen::VectorXd y = truth.S * steps[k];
    EXPECT_LT((secant.Times(steps[k]) - y).norm(), 1e-9 * y.norm()) << "pair " << k;
  }
  // The oldest pair was dropped: its equation no longer holds.
  const Eigen::VectorXd y0 = truth.S * steps[0];
  EXPECT_GT((secant.Times(steps[0]) - y0).norm(), 1e-3 * y0.norm());
}

TEST(StructuredSecant, CorrectedStepSolvesTheSystemWithTheEstimateAdded) {
  std::srand(11);
  const int n = 10;
  const Eigen::MatrixXd R = Eigen::MatrixXd::Random(n, n);
  const Eigen::MatrixXd A = R * R.transpose() + n * Eigen::MatrixXd::Identity(n, n);
  const Curvature truth(n);
  StructuredSecant secant(2);
  for (int k = 0; k < 2; ++k) {
    const Eigen::VectorXd s = Eigen::VectorXd::Random(n);
    secant.Add(s, 0.1 * truth.S * s);
  }
  Eigen::MatrixXd S(n, n);
  for (int j = 0; j < n; ++j) S.col(j) = secant.Times(Eigen::VectorXd::Unit(n, j));
  EXPECT_LT((S - S.transpose()).norm(), 1e-12 * S.norm()) << "the estimate is symmetric";

  const Eigen::VectorXd g = Eigen::VectorXd::Random(n);
  const Eigen::LLT<Eigen::MatrixXd> llt(A);
  Eigen::VectorXd delta = -llt.solve(g);
  const auto solve = [&](const Eigen::MatrixXd& b) { return Eigen::MatrixXd(llt.solve(b)); };
  ASSERT_TRUE(secant.Correct(solve, &delta));
  const Eigen::VectorXd dense = -(A + S).partialPivLu().solve(g);
  EXPECT_LT((delta - dense).norm(), 1e-10 * dense.norm());
}

TEST(StructuredSecant, WithoutPairsOrWithZeroMemoryLeavesTheStepAlone) {
  StructuredSecant none(0);
  none.Add(Eigen::VectorXd::Ones(3), Eigen::VectorXd::Ones(3));
  EXPECT_TRUE(none.empty());
  Eigen::VectorXd delta = Eigen::VectorXd::Ones(3);
  EXPECT_FALSE(none.Correct([](const Eigen::MatrixXd& b) { return b; }, &delta));
  EXPECT_EQ(delta, Eigen::VectorXd::Ones(3));
  EXPECT_EQ(none.Times(Eigen::VectorXd::Ones(3)), Eigen::VectorXd::Zero(3));
}

// A pair whose y is what the estimate already predicts adds nothing (the rank-one update's
// denominator vanishes): it is skipped rather than making M singular.
TEST(StructuredSecant, SkipsAPairTheEstimateAlreadyMeets) {
  StructuredSecant secant(4);
  secant.Add(Eigen::Vector2d(1, 0), Eigen::Vector2d(2, 0));
  secant.Add(Eigen::Vector2d(3, 0), Eigen::Vector2d(6, 0));
  Eigen::VectorXd delta = Eigen::Vector2d(1, 1);
  EXPECT_TRUE(secant.Correct([](const Eigen::MatrixXd& b) { return b; }, &delta));
  // With one pair kept S = diag(2, 0): (I + S)⁻¹(1, 1) = (1/3, 1).
  EXPECT_NEAR(delta[0], 1.0 / 3, 1e-15);
  EXPECT_NEAR(delta[1], 1.0, 1e-15);
}

}  // namespace
}  // namespace dynslam
