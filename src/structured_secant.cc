#include "src/structured_secant.h"

#include <cmath>

#include <Eigen/LU>

namespace dynslam {
namespace {

// Symmetric rank-one's safeguard: a pair is used only when |sᵀ(y − S s)| ≥ kSkip ‖s‖‖y − S s‖
// (Nocedal and Wright, eq. 6.26).
constexpr double kSkip = 1e-8;
// M and the Woodbury system are treated as singular below this reciprocal condition estimate.
constexpr double kMinRcond = 1e-12;

}  // namespace

void StructuredSecant::Add(const Eigen::VectorXd& s, const Eigen::VectorXd& y) {
  if (memory_ <= 0 || !s.allFinite() || !y.allFinite()) return;
  const Eigen::VectorXd residual = y - Times(s);
  if (std::abs(s.dot(residual)) < kSkip * s.norm() * residual.norm()) return;
  pairs_.push_back({s, y});
  if (static_cast<int>(pairs_.size()) > memory_) pairs_.pop_front();
}

bool StructuredSecant::Compact(Eigen::MatrixXd* Y, Eigen::MatrixXd* M) const {
  const int k = static_cast<int>(pairs_.size());
  Y->resize(pairs_.front().y.size(), k);
  M->resize(k, k);
  for (int j = 0; j < k; ++j) Y->col(j) = pairs_[j].y;
  for (int i = 0; i < k; ++i) {
    for (int j = 0; j <= i; ++j) {
      (*M)(i, j) = (*M)(j, i) = pairs_[i].s.dot(pairs_[j].y);  // D on the diagonal, L and Lᵀ
    }
  }
  return Eigen::FullPivLU<Eigen::MatrixXd>(*M).rcond() > kMinRcond;
}

Eigen::VectorXd StructuredSecant::Times(const Eigen::VectorXd& v) const {
  Eigen::MatrixXd Y, M;
  if (pairs_.empty() || !Compact(&Y, &M)) return Eigen::VectorXd::Zero(v.size());
  return Y * M.fullPivLu().solve(Y.transpose() * v);
}

bool StructuredSecant::Correct(const std::function<Eigen::MatrixXd(const Eigen::MatrixXd&)>& solve,
                               Eigen::VectorXd* delta) const {
  Eigen::MatrixXd Y, M;
  if (pairs_.empty() || !Compact(&Y, &M)) return false;
  const Eigen::MatrixXd Z = solve(Y);  // A⁻¹Y
  const Eigen::MatrixXd K = M + Y.transpose() * Z;
  const Eigen::FullPivLU<Eigen::MatrixXd> lu(K);
  if (lu.rcond() <= kMinRcond) return false;
  const Eigen::VectorXd corrected = *delta - Z * lu.solve(Y.transpose() * *delta);
  if (!corrected.allFinite()) return false;
  *delta = corrected;
  return true;
}

}  // namespace dynslam
