// Entries of the inverse of a sparse symmetric positive definite matrix without forming it: the
// inverse on the pattern of its LDLᵀ factor (Takahashi, Fagan and Chin, 1973), which holds every
// entry where the matrix itself is structurally non-zero, so every diagonal block of a variable
// of an information matrix JᵀJ — its marginal covariance (internal; include/dynslam/covariance.h).
//
// With P·A·Pᵀ = L·D·Lᵀ (L unit lower, fill-reducing P) and Z = (P·A·Pᵀ)⁻¹, Z = D⁻¹L⁻¹ + (I − Lᵀ)Z
// gives, column by column from the last, for i ≥ j in the pattern of L's column j:
//   Z_ij = δ_ij / D_j − Σ_{k > j, L_kj ≠ 0} L_kj · Z_ik,
// where every Z_ik needed is again on L's pattern (the rows of a column of L form a clique of
// the filled graph). The cost is Σ_j |column j|², about that of the factorisation.
#ifndef DYNSLAM_SRC_SELECTED_INVERSE_H_
#define DYNSLAM_SRC_SELECTED_INVERSE_H_

#include <vector>

#include <Eigen/SparseCore>

namespace dynslam {

class SelectedInverse {
 public:
  // Factorises `a` (symmetric; its lower triangle is read) with AMD ordering.
  explicit SelectedInverse(const Eigen::SparseMatrix<double>& a);

  // The columns of `a` (its own order) whose pivot D is at most `tolerance` times their diagonal
  // entry of P·A·Pᵀ: each adds a direction along which `a` is singular or nearly so. Empty when
  // `a` is positive definite to that tolerance.
  std::vector<int> WeakColumns(double tolerance) const;

  // Fills the inverse on L's pattern; needs no weak column (it divides by the pivots).
  void Invert();

  // (a⁻¹)_ij, i and j in `a`'s order, for a pair on the factor's pattern (any (i, j) where a_ij
  // is structurally non-zero); after Invert.
  double operator()(int i, int j) const;

 private:
  // Z_ij in permuted indices, i ≥ j; the entry must be on L's pattern.
  double& ZLower(int i, int j);

  std::vector<int> permuted_;  // a's index → P·A·Pᵀ's
  // L (unit diagonal not stored) and Z's lower triangle share one pattern: column j holds the
  // diagonal first, then its rows in ascending order.
  std::vector<int> column_start_;
  std::vector<int> row_;
  std::vector<double> l_;
  std::vector<double> z_;
  std::vector<double> d_;
  std::vector<double> diagonal_;  // of P·A·Pᵀ
};

}  // namespace dynslam

#endif  // DYNSLAM_SRC_SELECTED_INVERSE_H_
