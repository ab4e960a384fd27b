#include "src/selected_inverse.h"

#include <algorithm>
#include <utility>

#include <Eigen/SparseCholesky>

namespace dynslam {

SelectedInverse::SelectedInverse(const Eigen::SparseMatrix<double>& a) {
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>, Eigen::Lower, Eigen::AMDOrdering<int>> ldlt;
  ldlt.analyzePattern(a);
  ldlt.factorize(a);
  const int n = static_cast<int>(a.cols());
  const Eigen::VectorXi& p = ldlt.permutationP().indices();
  permuted_.assign(p.data(), p.data() + n);
  const Eigen::VectorXd d = ldlt.vectorD();  // a copy, not a reference
  d_.assign(d.data(), d.data() + n);
  diagonal_.assign(n, 0.0);
  for (int k = 0; k < n; ++k) diagonal_[permuted_[k]] = a.coeff(k, k);

  // L's strictly lower part, each column's rows sorted, behind a diagonal slot.
  const Eigen::SparseMatrix<double>& l = ldlt.matrixL().nestedExpression();
  column_start_.assign(n + 1, 0);
  for (int j = 0; j < n; ++j) {
    int below = 0;
    for (Eigen::SparseMatrix<double>::InnerIterator it(l, j); it; ++it) below += it.row() > j;
    column_start_[j + 1] = column_start_[j] + 1 + below;
  }
  row_.resize(column_start_[n]);
  l_.resize(column_start_[n]);
  for (int j = 0; j < n; ++j) {
    std::vector<std::pair<int, double>> entries;
    for (Eigen::SparseMatrix<double>::InnerIterator it(l, j); it; ++it) {
      if (it.row() > j) entries.emplace_back(static_cast<int>(it.row()), it.value());
    }
    std::sort(entries.begin(), entries.end());
    int slot = column_start_[j];
    row_[slot] = j;
    l_[slot] = 1.0;
    for (const auto& [row, value] : entries) {
      ++slot;
      row_[slot] = row;
      l_[slot] = value;
    }
  }
}

std::vector<int> SelectedInverse::WeakColumns(double tolerance) const {
  std::vector<int> weak;
  for (int k = 0; k < static_cast<int>(permuted_.size()); ++k) {
    const int j = permuted_[k];
    if (!(d_[j] > tolerance * diagonal_[j])) weak.push_back(k);
  }
  return weak;
}

double& SelectedInverse::ZLower(int i, int j) {
  const auto first = row_.begin() + column_start_[j];
  const auto last = row_.begin() + column_start_[j + 1];
  return z_[std::lower_bound(first, last, i) - row_.begin()];
}

void SelectedInverse::Invert() {
  z_.assign(row_.size(), 0.0);
  const int n = static_cast<int>(d_.size());
  for (int j = n - 1; j >= 0; --j) {
    const int begin = column_start_[j] + 1;  // the rows below the diagonal
    const int end = column_start_[j + 1];
    // Off-diagonal entries first, from the bottom: each needs only columns right of j.
    for (int s = end - 1; s >= begin; --s) {
      const int i = row_[s];
      double sum = 0;
      for (int t = begin; t < end; ++t) {
        const int k = row_[t];
        sum += l_[t] * (i >= k ? ZLower(i, k) : ZLower(k, i));
      }
      z_[s] = -sum;
    }
    double sum = 0;
    for (int t = begin; t < end; ++t) sum += l_[t] * z_[t];
    z_[column_start_[j]] = 1.0 / d_[j] - sum;
  }
}

double SelectedInverse::operator()(int i, int j) const {
  int pi = permuted_[i], pj = permuted_[j];
  if (pi < pj) std::swap(pi, pj);
  const auto first = row_.begin() + column_start_[pj];
  const auto last = row_.begin() + column_start_[pj + 1];
  return z_[std::lower_bound(first, last, pi) - row_.begin()];
}

}  // namespace dynslam
