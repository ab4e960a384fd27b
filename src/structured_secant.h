// The curvature Gauss–Newton leaves out, learnt from the steps (SolverOptions::secant_memory;
// docs/SOLVER.md "dynslam's own loop").
//
// The Hessian of ½‖r‖² is JᵀJ + S with S = Σ rᵢ∇²rᵢ; Gauss–Newton drops S, which is what makes
// the object-centric tails creep (docs/CONVERGENCE.md §2, §9). A structured secant method keeps
// JᵀJ exact and estimates S from the gradients of accepted steps: for a step s from x to x⁺,
//   S s ≈ y = ∇f(x⁺) − ∇f(x) − J(x⁺)ᵀJ(x⁺) s
// (Dennis, Gay and Welsch's structured secant condition). The estimate is the limited-memory
// symmetric rank-one matrix of the last `memory` pairs in compact form (Byrd, Nocedal and Schnabel
// 1994, with S₀ = 0): S = Y M⁻¹ Yᵀ, M = D + L + Lᵀ from SᵀY = L + D + U. The damped step solves
// (JᵀJ + λD + S) δ = −g through Woodbury's identity with the factor of JᵀJ + λD.
#ifndef DYNSLAM_SRC_STRUCTURED_SECANT_H_
#define DYNSLAM_SRC_STRUCTURED_SECANT_H_

#include <deque>
#include <functional>

#include <Eigen/Core>

namespace dynslam {

class StructuredSecant {
 public:
  explicit StructuredSecant(int memory) : memory_(memory) {}

  // Records an accepted step s and its y (above); pairs the rank-one update cannot use are
  // dropped.
  void Add(const Eigen::VectorXd& s, const Eigen::VectorXd& y);
  bool empty() const { return pairs_.empty(); }
  void Clear() { pairs_.clear(); }
  // S·v with the current estimate (zero without pairs).
  Eigen::VectorXd Times(const Eigen::VectorXd& v) const;
  // Turns δ = −A⁻¹g into −(A + S)⁻¹g, where `solve` applies A⁻¹ to columns. False (δ left as
  // it is) when the small Woodbury system is singular.
  bool Correct(const std::function<Eigen::MatrixXd(const Eigen::MatrixXd&)>& solve,
               Eigen::VectorXd* delta) const;

 private:
  struct Pair {
    Eigen::VectorXd s, y;
  };
  // The compact form's Y and M, or false when M is singular.
  bool Compact(Eigen::MatrixXd* Y, Eigen::MatrixXd* M) const;

  int memory_;
  std::deque<Pair> pairs_;
};

}  // namespace dynslam

#endif  // DYNSLAM_SRC_STRUCTURED_SECANT_H_
