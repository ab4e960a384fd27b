#include "dynslam/solver.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <limits>
#include <memory>
#include <optional>
#include <unordered_map>
#include <unordered_set>

#include <ceres/ceres.h>

#include "dynslam/formulation.h"
#include "dynslam/se3.h"
#include "dynslam/se3_manifold.h"
#include "src/edge_costs.h"
#include "src/blas_runtime.h"
#include "src/openmp_thread_cap.h"
#include "src/own_minimizer.h"
#include "src/segment_gauge.h"
#include "src/stop_policy.h"

namespace dynslam {
namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();
// SolverOptions::extrapolation: the step quality ρ (actual / predicted decrease) of two accepted
// steps in a row that starts an extrapolation, and the largest factor it moves by.
constexpr double kExtrapolationRho = 1.5;
constexpr double kMaxExtrapolation = 64;
// SolverOptions::gauge_moves: the step quality ρ an accepted step needs before a gauge
// move (Ceres's "very successful" step). Moves made earlier, while the steps are still large and
// the model poor, sent whole KITTI 0018 oc_a on a longer path to a higher stop
// (docs/CONVERGENCE.md §7).
constexpr double kGaugeMoveRho = 0.75;

std::unique_ptr<ceres::LossFunction> MakeLoss(const RobustKernel& kernel) {
  switch (kernel.type) {
    case RobustKernel::Type::kNone: return nullptr;
    case RobustKernel::Type::kHuber: return std::make_unique<ceres::HuberLoss>(kernel.threshold);
    case RobustKernel::Type::kCauchy: return std::make_unique<ceres::CauchyLoss>(kernel.threshold);
  }
  return nullptr;
}

// The ceres::Problem of a graph: its own copy of the values (one 7-double block per vertex,
// allocated once so that the addresses Ceres holds stay valid), one residual block per edge,
// the residual blocks of each kind (for the per-kind cost of SPEC §1.5).
class Assembly {
 public:
  static Expected<std::unique_ptr<Assembly>> Build(const Graph& graph,
                                                   const SolverOptions& options);

  ceres::Problem& problem() { return *problem_; }
  // Cost per kind at the current values of the blocks.
  CostByKind Evaluate();
  // The total cost at the current values (`threads` evaluate it).
  double Cost(int threads);
  // The values of every block: a state of the solve.
  using Values = SegmentGauges::Values;
  const Values& values() const { return values_; }
  void Restore(const Values& values) { std::copy(values.begin(), values.end(), values_.begin()); }
  // The object segments whose gauge SolverOptions::gauge_moves moves, and the move.
  SegmentGauges FindSegmentGauges(const Graph& graph);
  void SnapGauges(const SegmentGauges& gauges) { gauges.Snap(&values_); }
  // Sets every block to from ⊞ alpha·(to ⊟ from): along the manifold's tangent for poses, along
  // the straight line for points; blocks that `from` and `to` agree on are left at `to`.
  void MoveAlong(const Values& from, const Values& to, double alpha);
  void WriteBack(Graph* graph) const;
  // An error naming the first edge of `kind` whose cost is not finite, if any.
  Status CheckFinite(EdgeKind kind);
  // Schur ordering: points no residual joins to another point go first — object-frame points
  // only when asked (docs/SOLVER.md). Null when no point can go first (Ceres then finds an
  // independent set itself).
  std::shared_ptr<ceres::ParameterBlockOrdering> MakeOrdering(bool eliminate_object_points,
                                                              std::string* description);
  const std::vector<VertexId>& unused() const { return unused_; }
  // The vertices in the problem, ascending, their blocks, and whether MakeOrdering puts them
  // in the first (eliminated) group.
  struct Variable {
    VertexId id;
    double* block;
    bool eliminated_first;
  };
  std::vector<Variable> Variables(bool eliminate_object_points);
  // SPEC §1.7 --fix-first: holds the smallest-id pose that is a variable of the problem constant.
  std::optional<VertexId> HoldFirstPoseConstant();

 private:
  Assembly() = default;

  double* Block(VertexId id) { return values_[index_.at(id)].data(); }
  // Adds a residual of `kind` over `ids` (in that order); refuses an edge that names one vertex
  // twice (Ceres would abort on it).
  Status Add(const Graph& graph, EdgeKind kind, int64_t line, ceres::CostFunction* cost,
             const std::vector<VertexId>& ids);
  // An edge's residual from the table (src/edge_costs.h); object-frame points may be anchored.
  template <typename Edge>
  Status AddEdge(const Graph& graph, const Edge& e, const SolverOptions& options) {
    return Add(graph, KindOf(graph, e), e.line, MakeCost(e, options), VertexIds(e, true));
  }
  Status AddEdge(const Graph& graph, const ObjectPointEdge& e, const SolverOptions& options);
  Status AddEdge(const Graph& graph, const ObjectMotionEdge& e, const SolverOptions& options);

  // SolverOptions::object_point_variables: each object-frame point's anchor pose, chosen
  // before any residual is added; its block then holds w = L_a · m_L (WriteBack undoes it).
  void AnchorObjectPoints(const Graph& graph);
  // Records the points of a residual that joins two or more (for the Schur ordering).
  void NoteJoinedPoints(const Graph& graph, const std::vector<VertexId>& ids);

  std::unordered_map<VertexId, VertexId> anchor_;  // object-frame point → its anchor pose
  std::unordered_map<VertexId, size_t> index_;
  std::vector<VertexId> ids_;
  std::vector<VertexType> types_;
  std::vector<Role> roles_;
  std::vector<std::array<double, kPoseSize>> values_;
  std::vector<VertexId> unused_;
  SE3Manifold manifold_;
  std::array<std::unique_ptr<ceres::LossFunction>, kNumEdgeKinds> losses_;
  std::array<std::vector<ceres::ResidualBlockId>, kNumEdgeKinds> blocks_;
  std::array<std::vector<int64_t>, kNumEdgeKinds> lines_;  // file line of each residual block
  // For the Schur ordering: points that share a residual with another point.
  std::unordered_set<VertexId> joined_points_;
  std::unique_ptr<ceres::Problem> problem_;
};

Status Assembly::Add(const Graph& graph, EdgeKind kind, int64_t line, ceres::CostFunction* cost,
                     const std::vector<VertexId>& ids) {
  std::unique_ptr<ceres::CostFunction> owned(cost);
  std::vector<double*> blocks;
  for (const VertexId id : ids) {
    if (std::count(ids.begin(), ids.end(), id) > 1) {
      return Error{"", line, std::string(EdgeKindName(kind)) + " edge uses vertex " +
                                 std::to_string(id) + " twice"};
    }
    if (graph.Find(id) == nullptr) {
      return Error{"", line, "edge names vertex " + std::to_string(id) + ", which is not declared"};
    }
    blocks.push_back(Block(id));
  }
  const int k = static_cast<int>(kind);
  blocks_[k].push_back(problem_->AddResidualBlock(owned.release(), losses_[k].get(), blocks));
  lines_[k].push_back(line);
  return Status::Ok();
}

Expected<std::unique_ptr<Assembly>> Assembly::Build(const Graph& graph,
                                                    const SolverOptions& options) {
  std::unique_ptr<Assembly> a(new Assembly());
  a->values_.reserve(graph.vertices.size());
  for (const auto& [id, vertex] : graph.vertices) {
    a->index_.emplace(id, a->values_.size());
    a->ids_.push_back(id);
    a->types_.push_back(vertex.type);
    a->roles_.push_back(vertex.label.role);
    a->values_.push_back(vertex.value);
  }
  for (int k = 0; k < kNumEdgeKinds; ++k) a->losses_[k] = MakeLoss(options.robust[k]);

  ceres::Problem::Options problem_options;
  problem_options.cost_function_ownership = ceres::TAKE_OWNERSHIP;
  problem_options.loss_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  problem_options.manifold_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  a->problem_ = std::make_unique<ceres::Problem>(problem_options);

  if ((options.object_point_variables == Frame::kWorld)) a->AnchorObjectPoints(graph);
  Status status;
  graph.ForEachEdgeVector([&](const auto& edges) {
    for (const auto& e : edges) {
      if (status.ok()) status = a->AddEdge(graph, e, options);
      a->NoteJoinedPoints(graph, VertexIds(e, true));
    }
  });
  if (!status.ok()) return status.error();

  for (size_t i = 0; i < a->values_.size(); ++i) {
    double* block = a->values_[i].data();
    if (!a->problem_->HasParameterBlock(block)) {
      a->unused_.push_back(a->ids_[i]);
    } else if (a->types_[i] == VertexType::kPose) {
      a->problem_->SetManifold(block, &a->manifold_);
    }
    const RoleInfo* role = InfoOf(a->roles_[i]);
    if (role != nullptr && role->constant && a->problem_->HasParameterBlock(block)) {
      a->problem_->SetParameterBlockConstant(block);
    }
  }
  return a;
}

std::optional<VertexId> Assembly::HoldFirstPoseConstant() {
  for (size_t i = 0; i < values_.size(); ++i) {
    if (types_[i] == VertexType::kPose && problem_->HasParameterBlock(values_[i].data()) &&
        !problem_->IsParameterBlockConstant(values_[i].data())) {
      problem_->SetParameterBlockConstant(values_[i].data());
      return ids_[i];
    }
  }
  return std::nullopt;
}

CostByKind Assembly::Evaluate() {
  CostByKind cost{};
  for (int k = 0; k < kNumEdgeKinds; ++k) {
    if (blocks_[k].empty()) continue;
    ceres::Problem::EvaluateOptions evaluate_options;
    evaluate_options.residual_blocks = blocks_[k];
    evaluate_options.apply_loss_function = true;
    problem_->Evaluate(evaluate_options, &cost[k], nullptr, nullptr, nullptr);
  }
  return cost;
}

double Assembly::Cost(int threads) {
  ceres::Problem::EvaluateOptions evaluate_options;
  evaluate_options.num_threads = threads;
  double cost = 0;
  problem_->Evaluate(evaluate_options, &cost, nullptr, nullptr, nullptr);
  return cost;
}

void Assembly::MoveAlong(const Values& from, const Values& to, double alpha) {
  for (size_t i = 0; i < values_.size(); ++i) {
    if (from[i] == to[i]) {
      values_[i] = to[i];
    } else if (types_[i] == VertexType::kPose) {
      double delta[kTangentSize];
      manifold_.Minus(to[i].data(), from[i].data(), delta);
      for (double& d : delta) d *= alpha;
      manifold_.Plus(from[i].data(), delta, values_[i].data());
    } else {
      for (int k = 0; k < kPointSize; ++k) {
        values_[i][k] = from[i][k] + alpha * (to[i][k] - from[i][k]);
      }
    }
  }
}

Status Assembly::CheckFinite(EdgeKind kind) {
  const int k = static_cast<int>(kind);
  for (size_t i = 0; i < blocks_[k].size(); ++i) {
    double cost = 0;
    const bool evaluated =
        problem_->EvaluateResidualBlock(blocks_[k][i], true, &cost, nullptr, nullptr);
    if (!evaluated || !std::isfinite(cost)) {
      return Error{"", lines_[k][i],
                   std::string("the ") + EdgeKindName(kind) +
                       " edge on this line has a cost that is not finite at the initial values "
                       "(a huge coordinate or information?); nothing was solved"};
    }
  }
  return Status::Ok();
}

void Assembly::AnchorObjectPoints(const Graph& graph) {
  auto consider = [&](VertexId point, VertexId pose) {
    auto [it, inserted] = anchor_.emplace(point, pose);
    if (!inserted) it->second = std::min(it->second, pose);
  };
  for (const ObjectPointEdge& e : graph.Edges<ObjectPointEdge>()) consider(e.point, e.object_pose);
  for (const ObjectMotionEdge& e : graph.Edges<ObjectMotionEdge>()) {
    consider(e.point, e.pose_prev);
    consider(e.point, e.pose_curr);
  }
  for (auto it = anchor_.begin(); it != anchor_.end();) {
    const Vertex* point = graph.Find(it->first);
    const Vertex* pose = graph.Find(it->second);
    if (point == nullptr || pose == nullptr || point->type != VertexType::kPoint ||
        pose->type != VertexType::kPose) {
      it = anchor_.erase(it);  // a malformed edge: Add reports it
      continue;
    }
    const Eigen::Vector3d w = Transform(pose->pose(), point->point());
    std::copy(w.data(), w.data() + 3, Block(it->first));
    ++it;
  }
}

void Assembly::NoteJoinedPoints(const Graph& graph, const std::vector<VertexId>& ids) {
  std::vector<VertexId> points;
  for (const VertexId id : ids) {
    const Vertex* vertex = graph.Find(id);
    if (vertex != nullptr && vertex->type == VertexType::kPoint) points.push_back(id);
  }
  if (points.size() >= 2) joined_points_.insert(points.begin(), points.end());
}

Status Assembly::AddEdge(const Graph& graph, const ObjectPointEdge& e,
                         const SolverOptions& options) {
  auto anchor = anchor_.find(e.point);
  if (anchor == anchor_.end()) {
    return Add(graph, EdgeKind::kObjectPoint, e.line, MakeCost(e, options), VertexIds(e, true));
  }
  const AnchoredCost anchored = MakeAnchoredCost(e, anchor->second);
  return Add(graph, EdgeKind::kObjectPoint, e.line, anchored.cost, anchored.ids);
}

Status Assembly::AddEdge(const Graph& graph, const ObjectMotionEdge& e,
                         const SolverOptions& options) {
  auto anchor = anchor_.find(e.point);
  if (anchor == anchor_.end()) {
    return Add(graph, EdgeKind::kObjectMotion, e.line, MakeCost(e, options), VertexIds(e, true));
  }
  const AnchoredCost anchored = MakeAnchoredCost(e, options, anchor->second);
  return Add(graph, EdgeKind::kObjectMotion, e.line, anchored.cost, anchored.ids);
}

void Assembly::WriteBack(Graph* graph) const {
  for (size_t i = 0; i < ids_.size(); ++i) {
    graph->vertices.at(ids_[i]).value = values_[i];
  }
  for (const auto& [point, pose] : anchor_) {  // m_L = L_a⁻¹ · w
    const Eigen::Vector3d m = Transform(Inverse(graph->Find(pose)->pose()),
                                        graph->Find(point)->point());
    graph->Find(point)->point() = m;
  }
}

SegmentGauges Assembly::FindSegmentGauges(const Graph& graph) {
  SegmentGauges::Layout layout;
  layout.index = [&](VertexId id) { return index_.at(id); };
  layout.movable = [&](VertexId id) {
    double* block = Block(id);
    return problem_->HasParameterBlock(block) && !problem_->IsParameterBlockConstant(block);
  };
  layout.world_anchored = [&](VertexId id) { return anchor_.count(id) > 0; };
  return SegmentGauges::Find(graph, layout);
}

std::vector<Assembly::Variable> Assembly::Variables(bool eliminate_object_points) {
  std::vector<Variable> variables;
  for (size_t i = 0; i < values_.size(); ++i) {
    double* block = values_[i].data();
    if (!problem_->HasParameterBlock(block)) continue;
    const bool independent = types_[i] == VertexType::kPoint &&
                             joined_points_.count(ids_[i]) == 0 &&
                             (eliminate_object_points || roles_[i] != Role::kObjectPoint);
    variables.push_back({ids_[i], block, independent});
  }
  std::sort(variables.begin(), variables.end(),
            [](const Variable& a, const Variable& b) { return a.id < b.id; });
  return variables;
}

std::shared_ptr<ceres::ParameterBlockOrdering> Assembly::MakeOrdering(bool eliminate_object_points,
                                                                      std::string* description) {
  auto ordering = std::make_shared<ceres::ParameterBlockOrdering>();
  int64_t first = 0;
  int64_t joined = 0;
  for (const Variable& v : Variables(eliminate_object_points)) {
    const bool is_point = problem_->ParameterBlockSize(v.block) == kPointSize;
    joined += is_point && !v.eliminated_first;  // joined by motion edges, or object-frame points
    first += v.eliminated_first;
    ordering->AddElementToGroup(v.block, v.eliminated_first ? 0 : 1);
  }
  if (first == 0) {
    *description = "no point can be eliminated first; Ceres chose an independent set";
    return nullptr;
  }
  *description = std::to_string(first) + " points first";
  if (joined > 0) {
    *description += "; " + std::to_string(joined) + " points kept with the poses";
  }
  return ordering;
}

// `options` has no auto left (ResolveAuto).
ceres::Solver::Options MakeCeresOptions(const SolverOptions& options) {
  ceres::Solver::Options o;
  o.minimizer_type = ceres::TRUST_REGION;
  o.trust_region_strategy_type = options.minimizer == MinimizerType::kDogleg
                                     ? ceres::DOGLEG
                                     : ceres::LEVENBERG_MARQUARDT;
  switch (options.linear_solver) {
    case LinearSolverType::kSparseSchur: o.linear_solver_type = ceres::SPARSE_SCHUR; break;
    case LinearSolverType::kSparseNormalCholesky:
      o.linear_solver_type = ceres::SPARSE_NORMAL_CHOLESKY;
      break;
    case LinearSolverType::kIterativeSchur:
      o.linear_solver_type = ceres::ITERATIVE_SCHUR;
      o.preconditioner_type = ceres::SCHUR_JACOBI;
      break;
    case LinearSolverType::kDenseSchur: o.linear_solver_type = ceres::DENSE_SCHUR; break;
    case LinearSolverType::kAuto: break;  // resolved before
  }
  o.sparse_linear_algebra_library_type = options.sparse_backend == SparseBackend::kEigen
                                             ? ceres::EIGEN_SPARSE
                                             : ceres::SUITE_SPARSE;
  o.num_threads = options.threads;
  o.max_num_iterations = options.max_iterations;
  o.function_tolerance = options.function_tolerance;
  o.gradient_tolerance = options.gradient_tolerance;
  o.parameter_tolerance = options.parameter_tolerance;
  o.initial_trust_region_radius = 1.0 / options.initial_lambda;
  if (!options.jacobi_scaling) {  // damping λ·I: the LM diagonal held at 1
    o.jacobi_scaling = false;
    o.min_lm_diagonal = 1;
    o.max_lm_diagonal = 1;
  }
  if (options.dsc_released_lm) {  // its λ·I damping: jacobi_scaling off (ResolveAuto)
    o.min_trust_region_radius = 1.0 / kReleasedMaxLambda;
    o.max_num_iterations = std::numeric_limits<int>::max();  // the recorder counts accepted steps
  }
  o.use_nonmonotonic_steps = options.nonmonotonic_steps > 0;
  if (o.use_nonmonotonic_steps) o.max_consecutive_nonmonotonic_steps = options.nonmonotonic_steps;
  o.logging_type = ceres::SILENT;
  o.minimizer_progress_to_stdout = false;
  return o;
}

// Turns Ceres's per-iteration summaries into SPEC §4 convergence rows. Ceres reports a rejected
// step with the trial point's cost, an invalid step (no trial point) with cost_change 0 and
// step_is_valid false, and its LM damping as 1 / trust_region_radius at the end of the step
// (so the damping a step used is the radius reported before it).
class ConvergenceRecorder : public ceres::IterationCallback {
 public:
  using Clock = std::chrono::steady_clock;
  // `scratch` is used only when options.on_accepted_state is set; `gauges` are the segments
  // SolverOptions::gauge_moves moves; `policy` says when to stop.
  ConvergenceRecorder(const SolverOptions& options, const Assembly* assembly, Graph* scratch,
                      const SegmentGauges* gauges, const StopPolicy* policy)
      : options_(options), assembly_(assembly), scratch_(scratch), gauges_(gauges), policy_(policy),
        extrapolating_(options.extrapolation),
        moving_gauges_(options.gauge_moves && !gauges->empty()) {}

  // Ceres restarts after an extrapolation (Solve); each run is a segment whose clock starts at
  // `offset_s` seconds after the first run started.
  void BeginSegment(double offset_s) { offset_s_ = offset_s; }

  ceres::CallbackReturnType operator()(const ceres::IterationSummary& s) override {
    if (s.iteration == 0) {
      accepted_cost_ = s.cost;
      radius_ = s.trust_region_radius;
      if (extrapolating_) {
        before_ = assembly_->values();
        two_before_.clear();
      }
      return StopRequested() ? ceres::SOLVER_TERMINATE_SUCCESSFULLY : ceres::SOLVER_CONTINUE;
    }
    StepRecord row;
    row.lambda = 1.0 / radius_;
    row.trial_cost = s.step_is_valid ? s.cost : kInfinity;
    row.accepted = s.step_is_successful;
    row.time_s = offset_s_ + s.cumulative_time_in_seconds;  // less preprocessing, after the solve
    row.relative_decrease = s.step_is_valid ? s.relative_decrease : 0;
    row.step_norm = s.step_norm;
    radius_ = s.trust_region_radius;
    Record(row);
    if (GaugeMoveWanted()) {  // Solve moves the gauges, restarts
      gauge_move_requested_ = true;
      return ceres::SOLVER_TERMINATE_SUCCESSFULLY;
    }
    if (StopRequested()) return ceres::SOLVER_TERMINATE_SUCCESSFULLY;
    if (extrapolating_ && s.step_is_successful) {
      const bool wanted = ExtrapolationWanted() && !two_before_.empty();
      if (wanted) extrapolation_from_ = std::move(two_before_);
      std::swap(two_before_, before_);
      before_ = assembly_->values();  // into the buffer two_before_ held: no allocation
      if (wanted) return ceres::SOLVER_TERMINATE_SUCCESSFULLY;  // Solve extrapolates, restarts
    }
    return ceres::SOLVER_CONTINUE;
  }

  // Adds a row (numbering it) and reports it to the options' hooks.
  void Record(StepRecord row) {
    row.step = static_cast<int>(rows_.size()) + 1;
    row.iteration = accepted_ + 1;
    row.cost = accepted_cost_;
    rows_.push_back(row);
    extrapolations_ += row.extrapolation;
    gauge_moves_ += row.gauge_move;
    if (row.accepted) {
      ++accepted_;
      accepted_cost_ = row.trial_cost;
    }
    if (options_.on_step) options_.on_step(row);
    if (row.accepted && options_.on_accepted_state) {
      assembly_->WriteBack(scratch_);
      options_.on_accepted_state(row, *scratch_);
    }
  }

  // The state two accepted steps back when the recorder ended the segment to extrapolate, else
  // empty; taking it clears the request.
  Assembly::Values TakeExtrapolationRequest() { return std::move(extrapolation_from_); }
  // True when the recorder ended the segment to move the gauges; taking it clears the request.
  bool TakeGaugeMoveRequest() { return std::exchange(gauge_move_requested_, false); }
  // Gauge moves stop for the rest of the solve (after one that did not lower the cost).
  void StopMovingGauges() { moving_gauges_ = false; }
  // The remaining-χ² stop that ended the segment to probe it with an extrapolation first, else
  // nothing; taking it clears it.
  std::optional<StopDecision> TakeProbe() { return std::exchange(probe_, std::nullopt); }
  // Ends the solve with `decision`'s termination (Ceres has stopped, or will at the next step).
  void Stop(StopDecision decision) { stop_ = std::move(decision); }
  // Extrapolation stops for the rest of the solve (after one that found no lower cost).
  void StopExtrapolating() {
    extrapolating_ = false;
    before_.clear();
    two_before_.clear();
  }
  const std::vector<StepRecord>& rows() const { return rows_; }
  int extrapolations() const { return extrapolations_; }
  int gauge_moves() const { return gauge_moves_; }
  int linear_solves() const {
    return static_cast<int>(rows_.size()) - extrapolations_ - gauge_moves_;
  }
  double radius() const { return radius_; }
  std::vector<StepRecord> TakeRows() { return std::move(rows_); }
  // How the policy ended the solve (USER_SUCCESS in Ceres's terms), when it did.
  const std::optional<StopDecision>& stop() const { return stop_; }

 private:
  // Ceres keeps the last accepted state when a callback ends the solve (USER_SUCCESS).
  bool StopRequested() {
    std::optional<StopDecision> stop = policy_->Check(rows_, accepted_);
    if (!stop) return false;
    if (stop->after_probe && extrapolating_ && !two_before_.empty()) {  // RunSegments probes
      extrapolation_from_ = two_before_;
      probe_ = std::move(stop);
    } else {
      stop_ = std::move(stop);
    }
    return true;
  }
  // SolverOptions::gauge_moves: the last row is an accepted linear solve of quality
  // ρ ≥ kGaugeMoveRho that lowered the cost by less than the segments' priors still hold (all
  // of which a gauge move removes in oc_a).
  bool GaugeMoveWanted() const {
    if (!moving_gauges_) return false;
    const StepRecord& row = rows_.back();
    if (!row.accepted || !IsLinearSolve(row)) return false;
    if (row.relative_decrease < kGaugeMoveRho) return false;
    return gauges_->PriorCost(assembly_->values()) > row.cost - row.trial_cost;
  }
  // SolverOptions::extrapolation: the last two rows are accepted linear solves whose decrease the
  // model underestimated by ρ ≥ kExtrapolationRho.
  bool ExtrapolationWanted() const {
    if (!extrapolating_ || rows_.size() < 2) return false;
    for (size_t i = rows_.size() - 2; i < rows_.size(); ++i) {
      const StepRecord& row = rows_[i];
      if (!row.accepted || !IsLinearSolve(row) || row.relative_decrease < kExtrapolationRho) {
        return false;
      }
    }
    return true;
  }
  const SolverOptions& options_;
  const Assembly* assembly_;
  Graph* scratch_;
  const SegmentGauges* gauges_;
  const StopPolicy* policy_;
  std::optional<StopDecision> stop_;
  std::vector<StepRecord> rows_;
  double accepted_cost_ = 0;
  double radius_ = 1;
  int accepted_ = 0;
  int extrapolations_ = 0;
  int gauge_moves_ = 0;
  double offset_s_ = 0;
  bool extrapolating_;  // SolverOptions::extrapolation, until an extrapolation finds nothing
  bool moving_gauges_;  // SolverOptions::gauge_moves, until a move finds nothing
  bool gauge_move_requested_ = false;  // set when the segment ended to move the gauges
  Assembly::Values two_before_, before_;  // the states two accepted steps back and one back
  Assembly::Values extrapolation_from_;  // set when the segment ended to extrapolate
  std::optional<StopDecision> probe_;    // the remaining-χ² stop the extrapolation checks
};

// SolverOptions::extrapolation: from the state `from` two accepted steps back to the assembly's
// current state (whose cost is `cost`), tries α = 2, 4, 8, … ≤ kMaxExtrapolation along the two
// steps while the cost keeps falling, and leaves the assembly at the lowest cost found.
// Returns its row (extrapolation, lambda 0), or nothing — the assembly back where it was — when
// no α > 1 lowered the cost.
std::optional<StepRecord> Extrapolate(const Assembly::Values& from, double cost, int threads,
                                      Assembly* assembly) {
  const Assembly::Values to = assembly->values();
  double best_alpha = 1, best_cost = cost;
  for (double alpha = 2; alpha <= kMaxExtrapolation; alpha *= 2) {
    assembly->MoveAlong(from, to, alpha);
    const double trial = assembly->Cost(threads);
    if (!(trial < best_cost)) break;  // NaN too
    best_alpha = alpha;
    best_cost = trial;
  }
  assembly->MoveAlong(from, to, best_alpha);
  if (best_alpha == 1) return std::nullopt;
  StepRecord row;
  row.lambda = 0;
  row.trial_cost = best_cost;
  row.accepted = true;
  row.relative_decrease = best_alpha;  // for analysis: the factor moved by
  row.extrapolation = true;
  return row;
}

// SolverOptions::gauge_moves: moves every segment's gauge so that its prior residual is
// zero and returns the move's row, or nothing — the assembly back where it was — when the total
// cost (`cost` before) did not fall.
std::optional<StepRecord> MoveGauges(const SegmentGauges& gauges, double cost, int threads,
                                     Assembly* assembly) {
  const Assembly::Values before = assembly->values();
  assembly->SnapGauges(gauges);
  const double trial = assembly->Cost(threads);
  if (!(trial < cost)) {  // NaN too
    assembly->Restore(before);
    return std::nullopt;
  }
  StepRecord row;
  row.lambda = 0;
  row.trial_cost = trial;
  row.accepted = true;
  row.gauge_move = true;
  return row;
}

Status CheckOptions(const SolverOptions& options) {
  if (options.threads < 1) return Error{"", 0, "threads must be at least 1"};
  if (options.max_iterations < 0) return Error{"", 0, "max_iterations must not be negative"};
  if (!(options.max_time >= 0) || !std::isfinite(options.max_time)) {
    return Error{"", 0, "max_time must be 0 (no limit) or a positive number of seconds"};
  }
  if (!(options.remaining_chi2 >= 0) || !std::isfinite(options.remaining_chi2)) {
    return Error{"", 0, "remaining_chi2 must be 0 (off) or a positive number"};
  }
  if (options.nonmonotonic_steps < -1) {
    return Error{"", 0, "nonmonotonic_steps must be -1 (auto), 0 (off) or a positive count"};
  }
  if (options.secant_memory < 0) {
    return Error{"", 0, "secant_memory must be -1 (auto), 0 (off) or a count"};
  }
  if (options.secant_memory > 0 && options.minimizer != MinimizerType::kDynslamLm) {
    return Error{"", 0,
                 "secant_memory needs minimizer dynslam_lm: Ceres's own loops cannot take the "
                 "secant estimate"};
  }
  if (!(options.initial_lambda > 0) || !std::isfinite(1.0 / options.initial_lambda)) {
    return Error{"", 0, "initial_lambda must be 0 (auto) or positive with a finite inverse"};
  }
  const ceres::SparseLinearAlgebraLibraryType library =
      options.sparse_backend == SparseBackend::kEigen ? ceres::EIGEN_SPARSE : ceres::SUITE_SPARSE;
  if (options.linear_solver != LinearSolverType::kDenseSchur &&
      !ceres::IsSparseLinearAlgebraLibraryTypeAvailable(library)) {
    return Error{"", 0, std::string("this Ceres build has no ") + Name(options.sparse_backend) +
                            " sparse backend"};
  }
  return Status::Ok();
}

}  // namespace

SolverOptions ResolveAuto(const SolverOptions& options, const Graph& graph) {
  SolverOptions resolved = options;
  const bool has_points = std::any_of(graph.vertices.begin(), graph.vertices.end(), [](const auto& v) {
    return v.second.type == VertexType::kPoint;
  });
  // The formulation table's rule (formulation.cc); dogleg for other graphs with points.
  if (resolved.minimizer == MinimizerType::kAuto) {
    const std::optional<Formulation> formulation = FormulationOfGraph(graph);
    const bool lm = formulation ? InfoOf(*formulation).lm_by_default : !has_points;
    resolved.minimizer = lm ? MinimizerType::kLevenbergMarquardt : MinimizerType::kDogleg;
  }
  // Sparse normal Cholesky on CHOLMOD was the fastest to the optimum on every reference graph
  // once CHOLMOD runs its supernodal factorisation in one thread (src/openmp_thread_cap.h).
  if (resolved.linear_solver == LinearSolverType::kAuto) {
    resolved.linear_solver = LinearSolverType::kSparseNormalCholesky;
  }
  if (resolved.sparse_backend == SparseBackend::kAuto) {
    resolved.sparse_backend = ceres::IsSparseLinearAlgebraLibraryTypeAvailable(ceres::SUITE_SPARSE)
                                  ? SparseBackend::kSuiteSparse
                                  : SparseBackend::kEigen;
  }
  if (resolved.initial_lambda == 0) resolved.initial_lambda = has_points ? 1e-6 : 1e-10;
  if (resolved.dsc_released_lm) {  // SPEC §6 `released`
    resolved.minimizer = MinimizerType::kLevenbergMarquardt;
    resolved.jacobi_scaling = false;
    resolved.initial_lambda = 1e-5;
    resolved.function_tolerance = kReleasedTolerance;
    resolved.gradient_tolerance = 0;
    resolved.parameter_tolerance = 0;
    resolved.max_iterations = 100;
    resolved.nonmonotonic_steps = 0;
    resolved.remaining_chi2 = 0;  // its own rule
    resolved.extrapolation = false;
    resolved.gauge_moves = false;
  }
  // Non-monotonic steps helped only the object-frame kinematic residual, whose gauge creep they
  // cut 3–5×; with the world-frame residual they lengthen the tail 2–3× (docs/CONVERGENCE.md).
  if (resolved.nonmonotonic_steps == -1) {
    resolved.nonmonotonic_steps =
        graph.Edges<KinematicEdge>().empty() || (resolved.kinematic_residual_frame == Frame::kWorld) ? 0 : 5;
  }
  // Two secant pairs held every reference optimum in as many or fewer steps (torus3D 293 → 72)
  // and cut the paper-scale object-centric tails by a fifth to two fifths (docs/SOLVER.md).
  if (resolved.secant_memory == -1) {
    resolved.secant_memory = resolved.minimizer == MinimizerType::kDynslamLm ? 2 : 0;
  }
  return resolved;
}

double TotalCost(const CostByKind& cost_by_kind) {
  double total = 0;
  for (const double cost : cost_by_kind) total += cost;
  return total;
}

Expected<CostByKind> EvaluateCost(const Graph& graph, const SolverOptions& options) {
  Expected<std::unique_ptr<Assembly>> assembly = Assembly::Build(graph, options);
  if (!assembly.ok()) return assembly.error();
  return (*assembly)->Evaluate();
}

Expected<SystemJacobian> EvaluateJacobian(const Graph& graph, const SolverOptions& options) {
  Expected<std::unique_ptr<Assembly>> built = Assembly::Build(graph, options);
  if (!built.ok()) return built.error();
  Assembly& assembly = **built;
  SystemJacobian out;
  ceres::Problem::EvaluateOptions evaluate_options;
  out.first_column.push_back(0);
  for (const Assembly::Variable& v : assembly.Variables(options.eliminate_object_points)) {
    // Ceres would give a constant block columns of zeros.
    if (assembly.problem().IsParameterBlockConstant(v.block)) continue;
    evaluate_options.parameter_blocks.push_back(v.block);
    out.variables.push_back(v.id);
    out.eliminated_first.push_back(v.eliminated_first);
    out.first_column.push_back(out.first_column.back() +
                               assembly.problem().ParameterBlockTangentSize(v.block));
  }
  ceres::CRSMatrix crs;
  double cost = 0;
  assembly.problem().Evaluate(evaluate_options, &cost, nullptr, nullptr, &crs);
  out.jacobian.resize(crs.num_rows, crs.num_cols);
  out.jacobian.resizeNonZeros(static_cast<Eigen::Index>(crs.values.size()));
  std::copy(crs.rows.begin(), crs.rows.end(), out.jacobian.outerIndexPtr());
  std::copy(crs.cols.begin(), crs.cols.end(), out.jacobian.innerIndexPtr());
  std::copy(crs.values.begin(), crs.values.end(), out.jacobian.valuePtr());
  return out;
}

// Ceres's times summed over the runs of RunSegments; the moves between runs (extrapolations,
// gauge moves) count as minimiser and evaluation time.
struct SegmentTimes {
  int segments = 0;
  double first_preprocessing_s = 0;
  double total_s = 0, minimizer_s = 0, preprocessor_s = 0, evaluation_s = 0, linear_solver_s = 0;

  void Add(const ceres::Solver::Summary& summary) {
    auto seconds = [](double s) { return std::max(0.0, s); };  // Ceres: −1 for a phase not run
    if (segments++ == 0) first_preprocessing_s = seconds(summary.preprocessor_time_in_seconds);
    total_s += seconds(summary.total_time_in_seconds);
    minimizer_s += seconds(summary.minimizer_time_in_seconds);
    preprocessor_s += seconds(summary.preprocessor_time_in_seconds);
    evaluation_s += seconds(summary.residual_evaluation_time_in_seconds) +
                    seconds(summary.jacobian_evaluation_time_in_seconds);
    linear_solver_s += seconds(summary.linear_solver_time_in_seconds);
  }
  void AddMove(double seconds) {
    total_s += seconds;
    minimizer_s += seconds;
    evaluation_s += seconds;
  }
};

// Runs Ceres; when the recorder ends a run to move the segments' gauges or to extrapolate, does
// that and runs Ceres again from there, with the trust region it had and the iterations left.
// `summary` is the last run's.
SegmentTimes RunSegments(const SolverOptions& options, const SegmentGauges& gauges,
                         const StopPolicy& policy, ceres::Solver::Options* ceres_options,
                         ConvergenceRecorder* recorder, Assembly* assembly,
                         ceres::Solver::Summary* summary) {
  using Clock = ConvergenceRecorder::Clock;
  const Clock::time_point first_run = Clock::now();
  auto since_first_run = [&] {
    return std::chrono::duration<double>(Clock::now() - first_run).count();
  };
  const ScopedOpenMpThreadCap cap(options.threads);
  const int max_linear_solves = ceres_options->max_num_iterations;
  SegmentTimes times;
  while (true) {
    recorder->BeginSegment(since_first_run());
    ceres::Solve(*ceres_options, &assembly->problem(), summary);
    times.Add(*summary);
    const double start = since_first_run();
    const double cost = recorder->rows().empty() ? 0 : recorder->rows().back().trial_cost;
    const bool gauge_move = recorder->TakeGaugeMoveRequest();
    const std::optional<StopDecision> probe = recorder->TakeProbe();
    const Assembly::Values from =
        gauge_move ? Assembly::Values() : recorder->TakeExtrapolationRequest();
    if (!gauge_move && from.empty()) return times;  // Ceres stopped the run itself
    std::optional<StepRecord> row = gauge_move
                                        ? MoveGauges(gauges, cost, options.threads, assembly)
                                        : Extrapolate(from, cost, options.threads, assembly);
    if (row) {
      row->time_s = since_first_run();
      recorder->Record(*row);
    }
    times.AddMove(since_first_run() - start);
    if (gauge_move) {
      if (!row) recorder->StopMovingGauges();
    } else if (probe) {
      const double gained_chi2 = row ? 2 * (cost - row->trial_cost) : 0;
      if (std::optional<StopDecision> stop = policy.AfterProbe(*probe, gained_chi2)) {
        recorder->Stop(std::move(*stop));
        return times;
      }
    } else if (!row) {
      recorder->StopExtrapolating();
    }
    if (recorder->linear_solves() >= max_linear_solves) {
      recorder->Stop(policy.StepLimit());
      return times;
    }
    ceres_options->max_num_iterations = max_linear_solves - recorder->linear_solves();
    ceres_options->initial_trust_region_radius = recorder->radius();
  }
}

// The rest of Solve with dynslam's own loop (own_minimizer.h) in place of Ceres's minimiser.
static SolveReport FinishOwnLoop(const SolverOptions& options, const StopPolicy& policy,
                          StopPolicy::Clock::time_point start, Assembly* assembly,
                          SolveReport report, Graph* graph) {
  const ScopedOpenMpThreadCap cap(options.threads);
  const auto minimizer_start = StopPolicy::Clock::now();
  const OwnMinimizerResult result =
      MinimizeWithOwnLoop(&assembly->problem(), options, policy, minimizer_start, &report.convergence);
  report.time_minimizer_s =
      std::chrono::duration<double>(StopPolicy::Clock::now() - minimizer_start).count();
  report.time_total_s = std::chrono::duration<double>(StopPolicy::Clock::now() - start).count();
  report.time_preprocessor_s = report.time_total_s - report.time_minimizer_s;
  report.time_evaluation_s = result.evaluation_s;
  report.time_linear_solver_s = result.linear_solve_s;
  report.steps = result.linear_solves;
  report.iterations = static_cast<int>(std::count_if(
      report.convergence.begin(), report.convergence.end(),
      [](const StepRecord& row) { return row.accepted; }));
  report.termination = result.termination;
  report.termination_detail = result.detail;
  report.usable = result.usable;
  report.ceres_report = "dynslam_lm: dynslam's own loop; Ceres evaluated the cost functions only";
  report.final_cost_by_kind = assembly->Evaluate();
  report.final_cost = TotalCost(report.final_cost_by_kind);
  assembly->WriteBack(graph);
  return report;
}

Expected<SolveReport> Solve(const SolverOptions& requested, Graph* graph) {
  const auto start = ConvergenceRecorder::Clock::now();
  const SolverOptions options = ResolveAuto(requested, *graph);
  if (Status status = CheckOptions(options); !status.ok()) return status.error();
  if (graph->NumEdges() == 0) return Error{"", 0, "the graph has no edges: there is nothing to solve"};
  if (graph->Edges<PriorEdge>().empty() && !options.fix_first) {
    return Error{"", 0,
                 "the graph has no EDGE_SE3_PRIOR, so it is determined only up to a rigid motion "
                 "(gauge freedom, SPEC §1.7); add a prior or pass --fix-first to hold the "
                 "smallest-id pose constant"};
  }
  Expected<std::unique_ptr<Assembly>> built = Assembly::Build(*graph, options);
  if (!built.ok()) return built.error();
  Assembly& assembly = **built;

  SolveReport report;
  report.variables_by_role = CountVerticesByRole(*graph);
  report.edges_by_kind = CountEdgesByKind(*graph);
  report.unused_variables = static_cast<int64_t>(assembly.unused().size());
  report.held_constant = assembly.unused();
  if (!assembly.unused().empty()) {
    report.warnings.push_back(std::to_string(assembly.unused().size()) +
                              " vertices are used by no edge and are held constant (first: " +
                              std::to_string(assembly.unused().front()) + ")");
  }
  if (options.fix_first) {
    if (std::optional<VertexId> first = assembly.HoldFirstPoseConstant()) {
      report.held_constant.push_back(*first);
    }
  }

  report.initial_cost_by_kind = assembly.Evaluate();
  report.initial_cost = TotalCost(report.initial_cost_by_kind);
  for (const EdgeKind kind : kAllEdgeKinds) {
    if (std::isfinite(report.initial_cost_by_kind[static_cast<int>(kind)])) continue;
    if (Status status = assembly.CheckFinite(kind); !status.ok()) return status.error();
  }

  ceres::Solver::Options ceres_options = MakeCeresOptions(options);
  report.options_used = options;
  // Only the Schur solvers need an elimination group; for sparse Cholesky a constrained
  // ordering only limits the fill-reducing ordering.
  if (options.linear_solver != LinearSolverType::kSparseNormalCholesky) {
    ceres_options.linear_solver_ordering =
        assembly.MakeOrdering(options.eliminate_object_points, &report.eliminated_first);
  } else {
    report.eliminated_first = "none: sparse Cholesky orders all variables to reduce fill";
  }
  std::string why_invalid;
  if (!ceres_options.IsValid(&why_invalid)) return Error{"", 0, "solver options: " + why_invalid};

  Graph scratch;
  if (options.on_accepted_state) scratch = *graph;
  const SegmentGauges gauges =
      options.gauge_moves ? assembly.FindSegmentGauges(*graph) : SegmentGauges();
  ceres_options.update_state_every_iteration =
      options.on_accepted_state || options.extrapolation || !gauges.empty();
  const StopPolicy policy(options, start);
  ConvergenceRecorder recorder(options, &assembly, &scratch, &gauges, &policy);
  ceres_options.callbacks.push_back(&recorder);
  ceres::Solver::Summary summary;
  UseOpenBlasThreads(options.threads);       // src/blas_runtime.h
  const ScopedBlasExclusion blas_exclusion;
  if (blas_exclusion.waited()) {
    report.warnings.push_back(
        "this process's BLAS is OpenBLAS built without locking (libopenblas0-serial), unsafe "
        "for concurrent solves: this solve waited for another to finish (install "
        "libopenblas0-pthread, docs/DEPENDENCIES.md)");
  }
  if (options.minimizer == MinimizerType::kDynslamLm) {
    return FinishOwnLoop(options, policy, start, &assembly, std::move(report), graph);
  }
  const SegmentTimes times =
      RunSegments(options, gauges, policy, &ceres_options, &recorder, &assembly, &summary);

  report.extrapolations = recorder.extrapolations();
  report.gauge_moves = recorder.gauge_moves();
  report.steps = recorder.linear_solves();
  report.convergence = recorder.TakeRows();
  for (StepRecord& row : report.convergence) row.time_s -= times.first_preprocessing_s;
  // Ceres's num_successful_steps also counts its iteration 0; the accepted rows are the steps.
  report.iterations = static_cast<int>(std::count_if(
      report.convergence.begin(), report.convergence.end(),
      [](const StepRecord& row) { return row.accepted; }));
  report.usable = summary.IsSolutionUsable();
  report.termination_detail = summary.message;
  report.ceres_report = summary.FullReport();
  if (times.segments > 1) {
    report.ceres_report = "Ceres's report of the last of " + std::to_string(times.segments) +
                          " runs (extrapolations and gauge moves restart it):\n" + report.ceres_report;
  }
  switch (summary.termination_type) {
    case ceres::CONVERGENCE: report.termination = "convergence"; break;
    case ceres::NO_CONVERGENCE: report.termination = "no_convergence"; break;
    case ceres::USER_SUCCESS:
      report.termination = recorder.stop()->termination;
      report.termination_detail =
          recorder.stop()->detail + "; the solution is the best accepted state";
      break;
    default: report.termination = "failure"; break;
  }
  report.time_total_s = times.total_s;
  report.time_minimizer_s = times.minimizer_s;
  report.time_preprocessor_s = times.preprocessor_s;
  report.time_evaluation_s = times.evaluation_s;
  report.time_linear_solver_s = times.linear_solver_s;

  report.final_cost_by_kind = assembly.Evaluate();
  report.final_cost = TotalCost(report.final_cost_by_kind);
  assembly.WriteBack(graph);
  return report;
}

}  // namespace dynslam
