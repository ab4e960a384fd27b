// The inverse on the factor's pattern (src/selected_inverse.h) against Eigen's dense inverse.
#include "src/selected_inverse.h"

#include <random>

#include <Eigen/Dense>
#include <gtest/gtest.h>

namespace dynslam {
namespace {

// JᵀJ of a random sparse J: `rows` residuals, each joining two or three of `n` columns.
Eigen::SparseMatrix<double> RandomInformation(int n, int rows, unsigned seed, int zero_column = -1) {
  std::mt19937 random(seed);
  std::uniform_int_distribution<int> column(0, n - 1);
  std::normal_distribution<double> value(0.0, 1.0);
  std::vector<Eigen::Triplet<double>> triplets;
  for (int r = 0; r < rows; ++r) {
    for (int c = 0; c < 2 + r % 2; ++c) {
      const int j = column(random);
      if (j != zero_column) triplets.emplace_back(r, j, value(random));
    }
  }
  for (int j = 0; j < n; ++j) {  // every column seen at least once
    if (j != zero_column) triplets.emplace_back(rows + j, j, 1.0 + std::abs(value(random)));
  }
  Eigen::SparseMatrix<double> jacobian(rows + n, n);
  jacobian.setFromTriplets(triplets.begin(), triplets.end());
  return Eigen::SparseMatrix<double>(jacobian.transpose() * jacobian);
}

TEST(SelectedInverseTest, EqualsTheDenseInverseWhereTheMatrixIsNonZero) {
  for (const unsigned seed : {1u, 2u, 3u}) {
    const Eigen::SparseMatrix<double> a = RandomInformation(60, 150, seed);
    const Eigen::MatrixXd inverse = Eigen::MatrixXd(a).inverse();
    SelectedInverse selected(a);
    ASSERT_TRUE(selected.WeakColumns(1e-12).empty());
    selected.Invert();
    int checked = 0;
    for (int j = 0; j < a.outerSize(); ++j) {
      for (Eigen::SparseMatrix<double>::InnerIterator it(a, j); it; ++it) {
        const int i = static_cast<int>(it.row());
        EXPECT_NEAR(selected(i, j), inverse(i, j), 1e-10 * inverse.cwiseAbs().maxCoeff())
            << "seed " << seed << " (" << i << ", " << j << ")";
        ++checked;
      }
    }
    EXPECT_GT(checked, 200);
  }
}

TEST(SelectedInverseTest, NamesTheColumnOfASingularMatrix) {
  // Column 17 of J is zero: JᵀJ is singular along e_17 and nowhere else.
  const Eigen::SparseMatrix<double> a = RandomInformation(40, 100, 4, 17);
  const std::vector<int> weak = SelectedInverse(a).WeakColumns(1e-10);
  ASSERT_EQ(weak.size(), 1u);
  EXPECT_EQ(weak[0], 17);
}

}  // namespace
}  // namespace dynslam
