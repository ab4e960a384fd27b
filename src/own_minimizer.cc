#include "src/own_minimizer.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <thread>
#include <utility>

#include <Eigen/CholmodSupport>
#include <Eigen/SparseCore>
#include <ceres/cost_function.h>
#include <ceres/loss_function.h>
#include <ceres/manifold.h>

#include "src/structured_secant.h"

namespace dynslam {
namespace {

using Clock = StopPolicy::Clock;
// The largest residual (6: a pose residual) and parameter block (7: a pose) of a dynslam graph:
// every per-residual matrix lives on the stack.
constexpr int kMaxResiduals = 6;
constexpr int kMaxAmbient = 7;
constexpr int kMaxTangent = 6;
using Residuals = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kMaxResiduals, 1>;
using AmbientJacobian = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor,
                                      kMaxResiduals, kMaxAmbient>;
using TangentJacobian = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor,
                                      kMaxResiduals, kMaxTangent>;
using PlusJacobian = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor,
                                   kMaxAmbient, kMaxTangent>;
using BlockProduct = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::ColMajor,
                                   kMaxTangent, kMaxTangent>;
constexpr double kInfinity = std::numeric_limits<double>::infinity();
// Ceres's LM constants (ceres::Solver::Options defaults), so that the two loops take the same
// steps: a step is taken when it achieves this fraction of the model's decrease; the LM diagonal
// is clamped to [kMinDiagonal, kMaxDiagonal]; the radius (1/λ) stays within these bounds.
constexpr double kMinRelativeDecrease = 1e-3;
constexpr double kMinDiagonal = 1e-6;
constexpr double kMaxDiagonal = 1e32;
constexpr double kMaxRadius = 1e16;
constexpr double kMinRadius = 1e-32;

// Ceres's LM diagonal with Jacobi scaling, in the unscaled variables: Ceres scales column c by
// s = 1/(1 + √h_cc), clamps the scaled diagonal s²h_cc and damps with λ times it; undone, that is
// λ·clamp(s²h_cc)/s².
double JacobiScaledDiagonal(double h) {
  const double inverse_scale = 1 + std::sqrt(h);
  const double scaled = h / (inverse_scale * inverse_scale);
  return std::clamp(scaled, kMinDiagonal, kMaxDiagonal) * inverse_scale * inverse_scale;
}

double SecondsSince(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// One parameter block: where it lives in the state vectors, and its columns when it varies.
struct Block {
  double* problem_values;  // the block Ceres holds (start and result)
  int offset = 0;          // in the state vectors
  int size = 0;
  int tangent = 0;
  const ceres::Manifold* manifold = nullptr;
  int column = -1;  // first column in JᵀJ; -1 for a constant block
};

struct Residual {
  const ceres::CostFunction* cost = nullptr;
  const ceres::LossFunction* loss = nullptr;
  std::vector<int> blocks;  // indices into the block list, in the cost function's order
  // For each ordered pair (i ≤ j) of the residual's varying blocks: where their JᵀJ block starts.
  struct Pair {
    int first, second;  // positions in `blocks`; first's column ≤ second's
    int prefix;         // rows of the second block's columns above the first block's rows
  };
  std::vector<Pair> pairs;
};

// JᵀJ's upper part in CSC form (whole dense diagonal blocks: CHOLMOD reads the upper triangle)
// and Jᵀr, accumulated block by block.
struct NormalEquations {
  Eigen::SparseMatrix<double> hessian;
  Eigen::VectorXd gradient;
  double cost = 0;
};

// The Triggs correction Ceres applies for a robust loss (ceres/internal/corrector.cc): scales
// the residual and Jacobian so that the Gauss–Newton model is that of ½ρ(‖r‖²).
void CorrectForLoss(const ceres::LossFunction& loss, double sq_norm, Residuals* r,
                    std::vector<TangentJacobian>* jacobians, double* cost) {
  double rho[3];
  loss.Evaluate(sq_norm, rho);
  *cost = 0.5 * rho[0];
  const double sqrt_rho1 = std::sqrt(rho[1]);
  if (sq_norm == 0 || rho[2] <= 0) {
    *r *= sqrt_rho1;
    for (TangentJacobian& J : *jacobians) J *= sqrt_rho1;
    return;
  }
  const double alpha = 1 - std::sqrt(1 + 2 * sq_norm * rho[2] / rho[1]);
  for (TangentJacobian& J : *jacobians) {
    if (J.size() == 0) continue;
    const Eigen::Matrix<double, 1, Eigen::Dynamic, Eigen::RowMajor, 1, kMaxTangent> rJ =
        r->transpose() * J;
    J = sqrt_rho1 * (J - (alpha / sq_norm) * (*r) * rJ);
  }
  *r *= sqrt_rho1 / (1 - alpha);
}

class OwnLoop {
 public:
  OwnLoop(ceres::Problem* problem, const SolverOptions& options, const StopPolicy& policy,
          Clock::time_point start, std::vector<StepRecord>* rows)
      : problem_(problem),
        options_(options),
        policy_(policy),
        start_(start),
        rows_(rows),
        secant_(options.secant_memory) {
    CollectBlocks();
    CollectResiduals();
    BuildPattern();
  }

  OwnMinimizerResult Run();

 private:
  void CollectBlocks();
  void CollectResiduals();
  void BuildPattern();
  // Residuals, Jacobians, JᵀJ, Jᵀr and the cost at `state`, in SolverOptions::threads threads
  // (thread k sums residuals k, k + threads, …, which mixes the kinds, whose costs differ; the
  // sums are added); false when a cost function fails.
  bool Evaluate(const std::vector<double>& state, NormalEquations* out);
  // The sums of residuals first, first + stride, … alone.
  bool EvaluateShare(const std::vector<double>& state, size_t first, size_t stride,
                     NormalEquations* out) const;
  // state ⊞ δ for every varying block.
  void Plus(const std::vector<double>& state, const Eigen::VectorXd& delta,
            std::vector<double>* result) const;
  void WriteBack(const std::vector<double>& state) const;
  // A step to try, with its model's decrease.
  struct Candidate {
    Eigen::VectorXd delta;
    double model_decrease = 0;
    bool secant = false;  // with the structured secant estimate
  };
  // The LM steps from `at` with damping λ, in the order to try them: the secant model's when it
  // is in use (and predicts a decrease), then Gauss–Newton's, both from one factorisation of
  // H + λD (D: Ceres's diagonal, or I without Jacobi scaling). False when CHOLMOD fails or the
  // step is not finite.
  bool DampedStep(NormalEquations* at, double lambda, std::vector<Candidate>* candidates);
  // Sets use_secant_ from how well each model predicted `actual`, the decrease along δ.
  void ChooseModel(const NormalEquations& at, const Eigen::VectorXd& delta, double actual);
  // Evaluates the candidates from state_ in order until the ratio accepts one (left in trial_
  // and next_, its ratio in *rho) and adds the linear solve's one row (SPEC §4: the last
  // candidate tried). Nullptr when every one is rejected.
  const Candidate* TryCandidates(const std::vector<Candidate>& candidates, double lambda,
                                 double* rho);
  // Moves to the accepted trial, teaching the secant estimate the step.
  void Accept(const Eigen::VectorXd& delta);
  void AddRow(double lambda, double cost, double trial, bool accepted, double rho, double norm);
  int Accepted() const {
    return static_cast<int>(std::count_if(rows_->begin(), rows_->end(),
                                          [](const StepRecord& r) { return r.accepted; }));
  }

  ceres::Problem* problem_;
  const SolverOptions& options_;
  const StopPolicy& policy_;
  const Clock::time_point start_;
  std::vector<StepRecord>* rows_;
  std::vector<Block> blocks_;
  std::vector<Residual> residuals_;
  std::vector<int> diagonal_;  // index of each column's diagonal entry in the hessian's values
  int columns_ = 0;
  bool supported_ = true;  // every residual and block within the stack matrices' sizes
  Eigen::SparseMatrix<double> pattern_;  // JᵀJ's pattern, zero values
  Eigen::CholmodSupernodalLLT<Eigen::SparseMatrix<double>, Eigen::Upper> cholesky_;
  std::vector<double> state_, trial_;  // the last accepted values, and a step's trial values
  NormalEquations current_, next_;      // at state_ and at trial_
  std::vector<NormalEquations> partial_;  // the other threads' sums in Evaluate
  StructuredSecant secant_;
  // Whether the secant model predicted the last trial's decrease better than Gauss–Newton's
  // (NL2SOL's choice of model, Dennis, Gay and Welsch 1981).
  bool use_secant_ = false;
  OwnMinimizerResult result_;
};

void OwnLoop::CollectBlocks() {
  std::vector<double*> pointers;
  problem_->GetParameterBlocks(&pointers);
  int offset = 0;
  for (double* values : pointers) {
    Block b;
    b.problem_values = values;
    b.offset = offset;
    b.size = problem_->ParameterBlockSize(values);
    b.tangent = problem_->ParameterBlockTangentSize(values);
    b.manifold = problem_->GetManifold(values);
    if (b.size > kMaxAmbient || b.tangent > kMaxTangent) supported_ = false;
    if (!problem_->IsParameterBlockConstant(values)) {
      b.column = columns_;
      columns_ += b.tangent;
    }
    offset += b.size;
    blocks_.push_back(b);
  }
}

void OwnLoop::CollectResiduals() {
  std::map<const double*, int> index;
  for (size_t i = 0; i < blocks_.size(); ++i) {
    index[blocks_[i].problem_values] = static_cast<int>(i);
  }
  std::vector<ceres::ResidualBlockId> ids;
  problem_->GetResidualBlocks(&ids);
  for (const ceres::ResidualBlockId id : ids) {
    Residual r;
    r.cost = problem_->GetCostFunctionForResidualBlock(id);
    r.loss = problem_->GetLossFunctionForResidualBlock(id);
    std::vector<double*> parameters;
    problem_->GetParameterBlocksForResidualBlock(id, &parameters);
    for (double* p : parameters) r.blocks.push_back(index.at(p));
    if (r.cost->num_residuals() > kMaxResiduals) supported_ = false;
    residuals_.push_back(std::move(r));
  }
}

// The pattern: a dense block for every pair of varying blocks that share a residual, each
// column's rows sorted; then where each residual's pairs start.
void OwnLoop::BuildPattern() {
  std::vector<std::vector<int>> rows_of(blocks_.size());  // block → the blocks above it
  for (const Residual& r : residuals_) {
    for (int a : r.blocks) {
      for (int b : r.blocks) {
        if (blocks_[a].column >= 0 && blocks_[b].column >= 0 &&
            blocks_[a].column <= blocks_[b].column) {
          rows_of[b].push_back(a);
        }
      }
    }
  }
  std::vector<std::map<int, int>> prefix_of(blocks_.size());  // block → {row block → prefix}
  std::vector<Eigen::Triplet<double>> entries;
  for (size_t b = 0; b < blocks_.size(); ++b) {
    std::vector<int>& above = rows_of[b];
    std::sort(above.begin(), above.end(),
              [&](int x, int y) { return blocks_[x].column < blocks_[y].column; });
    above.erase(std::unique(above.begin(), above.end()), above.end());
    int prefix = 0;
    for (int a : above) {
      prefix_of[b][a] = prefix;
      prefix += blocks_[a].tangent;
      for (int i = 0; i < blocks_[a].tangent; ++i) {
        for (int j = 0; j < blocks_[b].tangent; ++j) {
          entries.emplace_back(blocks_[a].column + i, blocks_[b].column + j, 0.0);
        }
      }
    }
  }
  pattern_.resize(columns_, columns_);
  pattern_.setFromTriplets(entries.begin(), entries.end());
  pattern_.makeCompressed();
  for (Residual& r : residuals_) {
    for (size_t i = 0; i < r.blocks.size(); ++i) {
      for (size_t j = 0; j < r.blocks.size(); ++j) {
        const Block &a = blocks_[r.blocks[i]], &b = blocks_[r.blocks[j]];
        if (a.column < 0 || b.column < 0 || a.column > b.column) continue;
        const int prefix = prefix_of[r.blocks[j]].at(r.blocks[i]);
        r.pairs.push_back({static_cast<int>(i), static_cast<int>(j), prefix});
      }
    }
  }
  diagonal_.resize(columns_);
  for (const Block& b : blocks_) {
    if (b.column < 0) continue;
    const int prefix = prefix_of[&b - blocks_.data()].at(static_cast<int>(&b - blocks_.data()));
    for (int j = 0; j < b.tangent; ++j) {
      diagonal_[b.column + j] = pattern_.outerIndexPtr()[b.column + j] + prefix + j;
    }
  }
}

bool OwnLoop::Evaluate(const std::vector<double>& state, NormalEquations* out) {
  const int threads = std::clamp(options_.threads, 1, std::max<int>(1, residuals_.size()));
  partial_.resize(threads - 1);
  std::vector<std::thread> workers;
  std::vector<char> ok(threads, 1);
  for (int k = 1; k < threads; ++k) {
    workers.emplace_back([&, k] { ok[k] = EvaluateShare(state, k, threads, &partial_[k - 1]); });
  }
  ok[0] = EvaluateShare(state, 0, threads, out);
  for (std::thread& w : workers) w.join();
  for (const NormalEquations& p : partial_) {
    Eigen::Map<Eigen::VectorXd>(out->hessian.valuePtr(), out->hessian.nonZeros()) +=
        Eigen::Map<const Eigen::VectorXd>(p.hessian.valuePtr(), p.hessian.nonZeros());
    out->gradient += p.gradient;
    out->cost += p.cost;
  }
  return std::all_of(ok.begin(), ok.end(), [](char c) { return c != 0; }) &&
         std::isfinite(out->cost);
}

bool OwnLoop::EvaluateShare(const std::vector<double>& state, size_t first, size_t stride,
                            NormalEquations* out) const {
  if (out->hessian.nonZeros() != pattern_.nonZeros()) out->hessian = pattern_;
  std::fill(out->hessian.valuePtr(), out->hessian.valuePtr() + out->hessian.nonZeros(), 0.0);
  out->gradient.setZero(columns_);
  out->cost = 0;
  double* values = out->hessian.valuePtr();
  const int* outer = out->hessian.outerIndexPtr();
  std::vector<const double*> parameters;
  std::vector<double*> jacobian_pointers;
  std::vector<AmbientJacobian> ambient;
  std::vector<TangentJacobian> jacobians;
  PlusJacobian plus;
  BlockProduct product;
  Residuals r;
  for (size_t index = first; index < residuals_.size(); index += stride) {
    const Residual& res = residuals_[index];
    const int m = res.cost->num_residuals();
    const size_t n = res.blocks.size();
    parameters.resize(n);
    jacobian_pointers.assign(n, nullptr);
    ambient.resize(n);
    jacobians.resize(n);
    for (size_t k = 0; k < n; ++k) {
      const Block& b = blocks_[res.blocks[k]];
      parameters[k] = state.data() + b.offset;
      if (b.column < 0) {
        jacobians[k].resize(0, 0);
        continue;
      }
      ambient[k].resize(m, b.size);
      jacobian_pointers[k] = ambient[k].data();
    }
    r.resize(m);
    if (!res.cost->Evaluate(parameters.data(), r.data(), jacobian_pointers.data())) return false;
    for (size_t k = 0; k < n; ++k) {
      const Block& b = blocks_[res.blocks[k]];
      if (b.column < 0) continue;
      if (b.manifold == nullptr) {
        jacobians[k] = ambient[k];
        continue;
      }
      plus.resize(b.size, b.tangent);
      b.manifold->PlusJacobian(parameters[k], plus.data());
      jacobians[k].noalias() = ambient[k] * plus;
    }
    const double sq_norm = r.squaredNorm();
    double cost = 0.5 * sq_norm;
    if (res.loss != nullptr) CorrectForLoss(*res.loss, sq_norm, &r, &jacobians, &cost);
    out->cost += cost;
    for (size_t k = 0; k < n; ++k) {
      const Block& b = blocks_[res.blocks[k]];
      if (b.column >= 0) out->gradient.segment(b.column, b.tangent) += jacobians[k].transpose() * r;
    }
    for (const Residual::Pair& p : res.pairs) {
      const Block& a = blocks_[res.blocks[p.first]];
      const Block& b = blocks_[res.blocks[p.second]];
      product.noalias() = jacobians[p.first].transpose() * jacobians[p.second];
      for (int j = 0; j < b.tangent; ++j) {
        double* column = values + outer[b.column + j] + p.prefix;
        for (int i = 0; i < a.tangent; ++i) column[i] += product(i, j);
      }
    }
  }
  return std::isfinite(out->cost);
}

void OwnLoop::Plus(const std::vector<double>& state, const Eigen::VectorXd& delta,
                   std::vector<double>* result) const {
  *result = state;
  for (const Block& b : blocks_) {
    if (b.column < 0) continue;
    if (b.manifold == nullptr) {
      for (int i = 0; i < b.size; ++i) (*result)[b.offset + i] += delta[b.column + i];
    } else {
      b.manifold->Plus(state.data() + b.offset, delta.data() + b.column,
                       result->data() + b.offset);
    }
  }
}

void OwnLoop::WriteBack(const std::vector<double>& state) const {
  for (const Block& b : blocks_) {
    std::copy(state.begin() + b.offset, state.begin() + b.offset + b.size, b.problem_values);
  }
}

void OwnLoop::AddRow(double lambda, double cost, double trial, bool accepted, double rho,
                     double norm) {
  StepRecord row;
  row.step = static_cast<int>(rows_->size()) + 1;
  row.iteration = Accepted() + 1;
  row.lambda = lambda;
  row.cost = cost;
  row.trial_cost = trial;
  row.accepted = accepted;
  row.time_s = SecondsSince(start_);
  row.relative_decrease = rho;
  row.step_norm = norm;
  rows_->push_back(row);
  if (options_.on_step) options_.on_step(row);
}

bool OwnLoop::DampedStep(NormalEquations* at, double lambda,
                         std::vector<Candidate>* candidates) {
  candidates->clear();
  // H + λD is factorised in place, its diagonal restored afterwards from a copy (exactly: no
  // copy of H, which at the paper's scale is a large part of the memory).
  double* hessian = at->hessian.valuePtr();
  Eigen::VectorXd undamped(columns_), diagonal(columns_);
  for (int c = 0; c < columns_; ++c) {
    undamped[c] = hessian[diagonal_[c]];
    diagonal[c] = options_.jacobi_scaling ? JacobiScaledDiagonal(undamped[c]) : 1.0;
    hessian[diagonal_[c]] += lambda * diagonal[c];
  }
  cholesky_.factorize(at->hessian);
  for (int c = 0; c < columns_; ++c) hessian[diagonal_[c]] = undamped[c];
  if (cholesky_.info() != Eigen::Success) return false;
  // (H + λD + S)δ = −g gives the model's decrease −gᵀδ − ½δᵀ(H + S)δ = ½(λδᵀDδ − gᵀδ), with
  // S = 0 (Gauss–Newton) or the structured secant estimate.
  auto candidate = [&](Eigen::VectorXd delta, bool secant) {
    const double decrease =
        0.5 * (lambda * delta.dot(diagonal.cwiseProduct(delta)) - at->gradient.dot(delta));
    return Candidate{std::move(delta), decrease, secant};
  };
  Candidate plain = candidate(-cholesky_.solve(at->gradient), false);
  if (!plain.delta.allFinite()) return false;
  Eigen::VectorXd corrected = plain.delta;
  const auto solve = [this](const Eigen::MatrixXd& b) -> Eigen::MatrixXd {
    return cholesky_.solve(b);
  };
  if (use_secant_ && secant_.Correct(solve, &corrected)) {
    Candidate secant = candidate(std::move(corrected), true);
    if (secant.model_decrease > 0) candidates->push_back(std::move(secant));
  }
  candidates->push_back(std::move(plain));
  return true;
}

void OwnLoop::ChooseModel(const NormalEquations& at, const Eigen::VectorXd& delta,
                          double actual) {
  if (secant_.empty()) return;
  const double gauss_newton = -at.gradient.dot(delta) -
                              0.5 * delta.dot(at.hessian.selfadjointView<Eigen::Upper>() * delta);
  const double secant = gauss_newton - 0.5 * delta.dot(secant_.Times(delta));
  use_secant_ = std::abs(actual - secant) < std::abs(actual - gauss_newton);
}

const OwnLoop::Candidate* OwnLoop::TryCandidates(const std::vector<Candidate>& candidates,
                                                 double lambda, double* rho) {
  for (const Candidate& c : candidates) {
    Plus(state_, c.delta, &trial_);
    const Clock::time_point t = Clock::now();
    const bool evaluated = Evaluate(trial_, &next_);
    result_.evaluation_s += SecondsSince(t);
    const double trial_cost = evaluated ? next_.cost : kInfinity;
    *rho = evaluated ? (current_.cost - trial_cost) / c.model_decrease : 0;
    const bool accepted = evaluated && c.model_decrease > 0 && *rho > kMinRelativeDecrease;
    if (accepted || &c == &candidates.back()) {
      AddRow(lambda, current_.cost, trial_cost, accepted, *rho, c.delta.norm());
    }
    if (accepted) {
      ChooseModel(current_, c.delta, current_.cost - trial_cost);
      return &c;
    }
    if (c.secant) {  // the estimate misled: start it afresh from the next steps
      secant_.Clear();
      use_secant_ = false;
    }
  }
  return nullptr;
}

void OwnLoop::Accept(const Eigen::VectorXd& delta) {
  if (options_.secant_memory > 0) {
    secant_.Add(delta, next_.gradient - current_.gradient -
                           next_.hessian.selfadjointView<Eigen::Upper>() * delta);
  }
  state_.swap(trial_);
  std::swap(current_, next_);
}

OwnMinimizerResult OwnLoop::Run() {
  if (!supported_) {
    return {"failure", "dynslam_lm handles residuals of at most 6 and blocks of at most 7 values",
            false};
  }
  for (const Block& b : blocks_) {
    state_.insert(state_.end(), b.problem_values, b.problem_values + b.size);
  }
  Clock::time_point t = Clock::now();
  if (!Evaluate(state_, &current_)) {
    return {"failure", "a residual could not be evaluated at the start", false};
  }
  result_.evaluation_s += SecondsSince(t);
  cholesky_.cholmod().nmethods = 1;  // AMD only, as Ceres asks CHOLMOD
  cholesky_.cholmod().method[0].ordering = CHOLMOD_AMD;
  cholesky_.cholmod().postorder = 1;
  cholesky_.analyzePattern(current_.hessian);
  double radius = 1.0 / options_.initial_lambda;
  double decrease_factor = 2;
  const double min_radius = options_.dsc_released_lm ? 1.0 / kReleasedMaxLambda : kMinRadius;
  // Ceres's rule after a rejected step: shrink the radius ever faster; true once it is below
  // its bound.
  auto shrink = [&] {
    radius /= decrease_factor;
    decrease_factor *= 2;
    return radius < min_radius;
  };
  auto stop = [&](std::string termination, std::string detail) {
    result_.termination = std::move(termination);
    result_.detail = std::move(detail);
    WriteBack(state_);
    return result_;
  };
  while (true) {
    if (std::optional<StopDecision> decision = policy_.Check(*rows_, Accepted())) {
      return stop(decision->termination, decision->detail);
    }
    if (result_.linear_solves >= options_.max_iterations) {
      return stop("no_convergence", "the step limit (max_iterations) was reached");
    }
    if (current_.gradient.lpNorm<Eigen::Infinity>() <= options_.gradient_tolerance) {
      return stop("convergence", "gradient max-norm <= gradient_tolerance");
    }
    t = Clock::now();
    const double lambda = 1.0 / radius;
    std::vector<Candidate> candidates;
    const bool solved = DampedStep(&current_, lambda, &candidates);
    ++result_.linear_solves;
    result_.linear_solve_s += SecondsSince(t);
    if (!solved) {
      AddRow(lambda, current_.cost, kInfinity, false, 0, 0);
      if (shrink()) return stop("convergence", "the damping reached its bound");
      continue;
    }
    const double tolerance = options_.parameter_tolerance;
    const double state_norm =
        Eigen::Map<const Eigen::VectorXd>(state_.data(), state_.size()).norm();
    if (candidates.back().delta.norm() <= tolerance * (state_norm + tolerance)) {
      return stop("convergence", "step norm <= parameter_tolerance");
    }
    double rho = 0;
    const Candidate* taken = TryCandidates(candidates, lambda, &rho);
    if (taken == nullptr) {
      if (shrink()) return stop("convergence", "the damping reached its bound");
      continue;
    }
    const double change = current_.cost - next_.cost;
    Accept(taken->delta);
    radius = std::min(kMaxRadius, radius / std::max(1.0 / 3.0, 1 - std::pow(2 * rho - 1, 3)));
    decrease_factor = 2;
    if (change <= options_.function_tolerance * (current_.cost + change)) {
      return stop("convergence", "relative cost change <= function_tolerance");
    }
  }
}

}  // namespace

OwnMinimizerResult MinimizeWithOwnLoop(ceres::Problem* problem, const SolverOptions& options,
                                       const StopPolicy& policy,
                                       StopPolicy::Clock::time_point start,
                                       std::vector<StepRecord>* rows) {
  return OwnLoop(problem, options, policy, start, rows).Run();
}

}  // namespace dynslam
