// Assembly and solve on small graphs whose answers are known by hand.
#include "dynslam/solver.h"

#include <cmath>
#include <sstream>

#include <gtest/gtest.h>

#include "dynslam/graph_io.h"
#include "dynslam/se3.h"
#include "convergence_rows.h"

namespace dynslam {
namespace {

Graph Read(const std::string& text) {
  std::istringstream in(text);
  Expected<Graph> graph = ReadGraph(in, "test.g2o");
  EXPECT_TRUE(graph.ok()) << graph.error().ToString();
  return graph.ok() ? std::move(graph).value() : Graph{};
}

// Two poses, a prior on the first at the identity and an odometry edge of 1 m along x and 90°
// about z; the second pose starts off by 0.3 m. Optimum: cost 0, pose 1 = the measurement.
constexpr char kTwoPoses[] =
    "VERTEX_SE3:QUAT 0 0 0 0 0 0 0 1\n"
    "VERTEX_SE3:QUAT 1 1.3 0.2 0 0 0 0.3 0.95393920141694566\n"
    "EDGE_SE3_PRIOR 0 0 0 0 0 0 0 1 1 0 0 0 0 0 1 0 0 0 0 1 0 0 0 1 0 0 1 0 1\n"
    "EDGE_SE3:QUAT 0 1 1 0 0 0 0 0.70710678118654757 0.70710678118654757 "
    "1 0 0 0 0 0 1 0 0 0 0 1 0 0 0 1 0 0 1 0 1\n";

TEST(SolverTest, TwoPosesReachZeroCostAtTheMeasurement) {
  Graph graph = Read(kTwoPoses);
  Expected<SolveReport> report = Solve(SolverOptions{}, &graph);
  ASSERT_TRUE(report.ok()) << report.error().ToString();
  EXPECT_TRUE(report->usable);
  EXPECT_GT(report->initial_cost, 0.01);
  EXPECT_LT(report->final_cost, 1e-20);
  const Pose solved = graph.Find(1)->pose();
  EXPECT_NEAR(solved.translation().x(), 1.0, 1e-10);
  EXPECT_NEAR(solved.translation().y(), 0.0, 1e-10);
  EXPECT_NEAR(RotationAngle(solved), M_PI / 2, 1e-10);
  EXPECT_EQ(report->edges_by_kind[static_cast<int>(EdgeKind::kPrior)], 1);
  EXPECT_EQ(report->edges_by_kind[static_cast<int>(EdgeKind::kOdometry)], 1);
}

// A camera held fixed and one point seen at the camera's origin with information 100·I: the
// cost is linear least squares, 50·|m|², and Gauss–Newton's step takes m to 0. LM's first step
// with damping λ = 100 goes a fraction of the way: 100 / (100 + λ) = 1/2 with λ·I
// (jacobi_scaling off, GTSAM's damping), 1 / (1 + λ) with λ·diag(JᵀJ) (the default).
TEST(SolverTest, JacobiScalingOffDampsWithLambdaTimesIdentity) {
  constexpr char kFixedCameraAndPoint[] =
      "VERTEX_SE3:QUAT 0 0 0 0 0 0 0 1\n"
      "VERTEX_TRACKXYZ 1 1 2 3\n"
      "EDGE_SE3_TRACKXYZ 0 1 0 0 0 100 0 0 100 0 100 0\n";
  for (const bool jacobi_scaling : {false, true}) {
    Graph graph = Read(kFixedCameraAndPoint);
    SolverOptions options;
    options.fix_first = true;
    options.minimizer = MinimizerType::kLevenbergMarquardt;
    options.initial_lambda = 100;
    options.max_iterations = 1;
    options.jacobi_scaling = jacobi_scaling;
    Expected<SolveReport> report = Solve(options, &graph);
    ASSERT_TRUE(report.ok()) << report.error().ToString();
    ASSERT_EQ(report->convergence.size(), 1u);
    const double fraction = jacobi_scaling ? 1.0 / 101 : 0.5;
    EXPECT_NEAR(report->initial_cost, 50 * 14, 1e-9);
    EXPECT_NEAR(report->convergence[0].trial_cost, 50 * 14 * std::pow(1 - fraction, 2), 1e-9)
        << "jacobi_scaling " << jacobi_scaling;
    EXPECT_NEAR(graph.Find(1)->value[2], 3 * (1 - fraction), 1e-12);
  }
}

TEST(SolverTest, ConvergenceRowsFollowSpecSection4) {
  Graph graph = Read(kTwoPoses);
  Expected<SolveReport> report = Solve(SolverOptions{}, &graph);
  ASSERT_TRUE(report.ok());
  ASSERT_FALSE(report->convergence.empty());
  testing::ExpectRowsFollowSpecSection4(*report);
}

TEST(SolverTest, RefusesGaugeFreedomUnlessFixFirst) {
  std::string text = kTwoPoses;
  text.erase(text.find("EDGE_SE3_PRIOR"), text.find("EDGE_SE3:QUAT") - text.find("EDGE_SE3_PRIOR"));
  Graph graph = Read(text);
  Expected<SolveReport> refused = Solve(SolverOptions{}, &graph);
  ASSERT_FALSE(refused.ok());
  EXPECT_NE(refused.error().message.find("gauge"), std::string::npos);
  EXPECT_NE(refused.error().message.find("--fix-first"), std::string::npos);

  SolverOptions options;
  options.fix_first = true;
  const Pose first_before = graph.Find(0)->pose();
  Expected<SolveReport> solved = Solve(options, &graph);
  ASSERT_TRUE(solved.ok()) << solved.error().ToString();
  EXPECT_EQ(graph.Find(0)->pose(), first_before);
  ASSERT_EQ(solved->held_constant.size(), 1u);
  EXPECT_EQ(solved->held_constant[0], 0);
  EXPECT_LT(solved->final_cost, 1e-20);
}

TEST(SolverTest, UnusedVertexIsHeldConstantAndReported) {
  Graph graph = Read(std::string(kTwoPoses) + "VERTEX_TRACKXYZ 7 1 2 3\n");
  Expected<SolveReport> report = Solve(SolverOptions{}, &graph);
  ASSERT_TRUE(report.ok()) << report.error().ToString();
  EXPECT_EQ(report->unused_variables, 1);
  ASSERT_EQ(report->held_constant.size(), 1u);
  EXPECT_EQ(report->held_constant[0], 7);
  EXPECT_EQ(graph.Find(7)->point(), Eigen::Vector3d(1, 2, 3));
  EXPECT_FALSE(report->warnings.empty());
}

TEST(SolverTest, EdgeNamingOneVertexTwiceIsAnErrorNotACrash) {
  Graph graph = Read(kTwoPoses);
  graph.Edges<BetweenEdge>()[0].to = graph.Edges<BetweenEdge>()[0].from;
  Expected<SolveReport> report = Solve(SolverOptions{}, &graph);
  ASSERT_FALSE(report.ok());
  EXPECT_EQ(report.error().line, 4);
  EXPECT_NE(report.error().message.find("twice"), std::string::npos);
}

TEST(SolverTest, NonFiniteInitialCostIsAnErrorNamingTheEdge) {
  std::string text = kTwoPoses;
  text.replace(text.find("VERTEX_SE3:QUAT 1 1.3"), 21, "VERTEX_SE3:QUAT 1 1e300");
  Graph graph = Read(text);
  Expected<SolveReport> report = Solve(SolverOptions{}, &graph);
  ASSERT_FALSE(report.ok());
  EXPECT_EQ(report.error().line, 4);
  EXPECT_NE(report.error().message.find("not finite"), std::string::npos);
}

TEST(SolverTest, HuberKernelLowersTheCostOfALargeResidual) {
  // The odometry residual is far beyond k = 0.01: with Huber(k) its cost is ½(2k‖r‖ − k²)
  // (SPEC §1.5, Ceres's HuberLoss), computed here from the plain cost ½‖r‖².
  Graph graph = Read(kTwoPoses);
  Expected<CostByKind> plain = EvaluateCost(graph);
  SolverOptions options;
  options.robust[static_cast<int>(EdgeKind::kOdometry)] = {RobustKernel::Type::kHuber, 0.01};
  Expected<CostByKind> robust = EvaluateCost(graph, options);
  ASSERT_TRUE(plain.ok() && robust.ok());
  const double squared_norm = 2 * (*plain)[static_cast<int>(EdgeKind::kOdometry)];
  EXPECT_NEAR((*robust)[static_cast<int>(EdgeKind::kOdometry)],
              0.5 * (2 * 0.01 * std::sqrt(squared_norm) - 0.01 * 0.01), 1e-15);
}

// Two object poses (2, 3) joined by a kinematic edge, as in oc_b and oc_c graphs.
constexpr char kObjectCentric[] =
    "VERTEX_SE3:QUAT 0 0 0 0 0 0 0 1\n"
    "VERTEX_SE3:QUAT 1 1 0 0 0 0 0 1\n"
    "VERTEX_SE3:QUAT 2 0 0 5 0 0 0 1\n"
    "VERTEX_SE3:QUAT 3 0 0 6 0 0 0 1\n"
    "VERTEX_SE3:QUAT 4 0 0 1 0 0 0 1\n"
    "VERTEX_TRACKXYZ 5 0 1 0\n"
    "EDGE_SE3_PRIOR 0 0 0 0 0 0 0 1 1 0 0 0 0 0 1 0 0 0 0 1 0 0 0 1 0 0 1 0 1\n"
    "EDGE_SE3_PRIOR 2 0 0 5 0 0 0 1 1 0 0 0 0 0 1 0 0 0 0 1 0 0 0 1 0 0 1 0 1\n"
    "EDGE_SE3:QUAT 0 1 1 0 0 0 0 0 1 1 0 0 0 0 0 1 0 0 0 0 1 0 0 0 1 0 0 1 0 1\n"
    "EDGE_SE3_OBJ_TRACKXYZ 0 2 5 0 1 5 1 0 0 1 0 1\n"
    "EDGE_SE3_OBJ_TRACKXYZ 1 3 5 -1 1 6 1 0 0 1 0 1\n"
    "EDGE_SE3_OBJ_MOTION 2 3 4 5 1 0 0 1 0 1\n"
    "EDGE_SE3_OBJ_KINEMATIC 2 3 4 1 0 0 0 0 0 1 0 0 0 0 1 0 0 0 1 0 0 1 0 1\n";

TEST(SolverTest, NonmonotonicStepsAreOnByDefaultOnlyWithTheObjectFrameKinematicResidual) {
  Graph object_centric = Read(kObjectCentric);
  ASSERT_FALSE(object_centric.Edges<KinematicEdge>().empty());
  Expected<SolveReport> report = Solve(SolverOptions{}, &object_centric);
  ASSERT_TRUE(report.ok()) << report.error().ToString();
  EXPECT_EQ(report->options_used.nonmonotonic_steps, 0);
  SolverOptions object_frame;
  object_frame.kinematic_residual_frame = Frame::kObject;
  object_centric = Read(kObjectCentric);
  report = Solve(object_frame, &object_centric);
  ASSERT_TRUE(report.ok()) << report.error().ToString();
  EXPECT_EQ(report->options_used.nonmonotonic_steps, 5);

  Graph pose_graph = Read(kTwoPoses);
  report = Solve(SolverOptions{}, &pose_graph);
  ASSERT_TRUE(report.ok()) << report.error().ToString();
  EXPECT_EQ(report->options_used.nonmonotonic_steps, 0);

  SolverOptions options;
  options.nonmonotonic_steps = 2;
  pose_graph = Read(kTwoPoses);
  report = Solve(options, &pose_graph);
  ASSERT_TRUE(report.ok()) << report.error().ToString();
  EXPECT_EQ(report->options_used.nonmonotonic_steps, 2);
  EXPECT_LT(report->final_cost, 1e-20);

  options.nonmonotonic_steps = -2;
  EXPECT_FALSE(Solve(options, &pose_graph).ok());
}

TEST(SolverTest, AutoChoosesBySolverClassOfTheGraph) {
  // Every graph: sparse normal Cholesky on CHOLMOD (this Ceres has SuiteSparse).
  // Points and kinematic edges: LM, first damping 1e-6, monotonic (world-frame kinematic residual).
  Graph kinematic = Read(kObjectCentric);
  Expected<SolveReport> report = Solve(SolverOptions{}, &kinematic);
  ASSERT_TRUE(report.ok()) << report.error().ToString();
  EXPECT_EQ(report->options_used.minimizer, MinimizerType::kLevenbergMarquardt);
  EXPECT_EQ(report->options_used.linear_solver, LinearSolverType::kSparseNormalCholesky);
  EXPECT_EQ(report->options_used.sparse_backend, SparseBackend::kSuiteSparse);
  EXPECT_EQ(report->options_used.initial_lambda, 1e-6);
  EXPECT_EQ(report->options_used.nonmonotonic_steps, 0);

  // Object-centric without kinematic edges (oc_a): LM, monotonic.
  Graph oc_a = Read(kObjectCentric);
  oc_a.Edges<KinematicEdge>().clear();
  report = Solve(SolverOptions{}, &oc_a);
  ASSERT_TRUE(report.ok()) << report.error().ToString();
  EXPECT_EQ(report->options_used.minimizer, MinimizerType::kLevenbergMarquardt);
  EXPECT_EQ(report->options_used.linear_solver, LinearSolverType::kSparseNormalCholesky);
  EXPECT_EQ(report->options_used.nonmonotonic_steps, 0);

  // World-centric, points and no object-centric edge: dogleg.
  Graph world_centric = Read(std::string(kTwoPoses) +
                             "VERTEX_TRACKXYZ 5 0 1 4\n"
                             "EDGE_SE3_TRACKXYZ 0 5 0 1 4 1 0 0 1 0 1 0\n"
                             "EDGE_SE3_TRACKXYZ 1 5 1 -1 4 1 0 0 1 0 1 0\n");
  report = Solve(SolverOptions{}, &world_centric);
  ASSERT_TRUE(report.ok()) << report.error().ToString();
  EXPECT_EQ(report->options_used.minimizer, MinimizerType::kDogleg);
  EXPECT_EQ(report->options_used.initial_lambda, 1e-6);

  // Pose graph: LM starting nearly at Gauss–Newton.
  Graph pose_graph = Read(kTwoPoses);
  report = Solve(SolverOptions{}, &pose_graph);
  ASSERT_TRUE(report.ok()) << report.error().ToString();
  EXPECT_EQ(report->options_used.minimizer, MinimizerType::kLevenbergMarquardt);
  EXPECT_EQ(report->options_used.linear_solver, LinearSolverType::kSparseNormalCholesky);
  EXPECT_EQ(report->options_used.sparse_backend, SparseBackend::kSuiteSparse);
  EXPECT_EQ(report->options_used.initial_lambda, 1e-10);

  SolverOptions options;
  options.minimizer = MinimizerType::kDogleg;
  pose_graph = Read(kTwoPoses);
  report = Solve(options, &pose_graph);
  ASSERT_TRUE(report.ok()) << report.error().ToString();
  EXPECT_EQ(report->options_used.minimizer, MinimizerType::kDogleg);
  EXPECT_LT(report->final_cost, 1e-20);
}

}  // namespace
}  // namespace dynslam

namespace dynslam {
namespace {

// The solver's chart for object-frame points and frame for the kinematic residual
// (SolverOptions::object_point_variables, kinematic_residual_frame) change the
// steps, never the cost: on the embedded synthetic oc_b graph every combination gives the same
// cost per edge kind at the initial values, and solving with the defaults and with both off
// ends at the same optimum with the object-frame points written back.
class ObjectCentricChartTest : public ::testing::Test {
 protected:
  void SetUp() override {
    Expected<Graph> graph =
        ReadGraph(std::string(DYNSLAM_SOURCE_DIR) + "/data/reference/synthetic/graphs/oc_b.g2o");
    ASSERT_TRUE(graph.ok()) << graph.error().ToString();
    graph_ = std::move(*graph);
  }
  static SolverOptions Options(bool anchored, bool world_kinematic) {
    SolverOptions options;
    options.object_point_variables = anchored ? Frame::kWorld : Frame::kObject;
    options.kinematic_residual_frame = world_kinematic ? Frame::kWorld : Frame::kObject;
    return options;
  }
  static SolverOptions Tight(SolverOptions options) { return TightRule(options); }
  Graph graph_;
};

TEST_F(ObjectCentricChartTest, EveryChartHasTheSameCostPerKind) {
  Expected<CostByKind> reference = EvaluateCost(graph_, Options(false, false));
  ASSERT_TRUE(reference.ok());
  EXPECT_GT((*reference)[static_cast<int>(EdgeKind::kKinematic)], 1.0);
  for (const bool anchored : {false, true}) {
    for (const bool world_kinematic : {false, true}) {
      Expected<CostByKind> cost = EvaluateCost(graph_, Options(anchored, world_kinematic));
      ASSERT_TRUE(cost.ok());
      for (int k = 0; k < kNumEdgeKinds; ++k) {
        EXPECT_NEAR((*cost)[k], (*reference)[k], 1e-10 * std::max(1.0, (*reference)[k]))
            << EdgeKindName(kAllEdgeKinds[k]) << " anchored " << anchored << " world kinematic "
            << world_kinematic;
      }
    }
  }
}

// SolverOptions::should_stop is polled after every step: the solve ends there, usable, at the
// last accepted state (the cost the convergence rows last accepted), and says why.
TEST_F(ObjectCentricChartTest, StopRequestEndsAtTheLastAcceptedState) {
  int polls = 0;
  SolverOptions options;
  options.should_stop = [&polls] { return ++polls > 4; };  // the 5th poll: after step 4
  Graph graph = graph_;
  Expected<SolveReport> report = Solve(options, &graph);
  ASSERT_TRUE(report.ok()) << report.error().ToString();
  EXPECT_EQ(report->termination, "interrupted");
  EXPECT_TRUE(report->usable);
  ASSERT_EQ(report->steps, 4);
  double last_accepted = report->initial_cost;
  for (const StepRecord& row : report->convergence) {
    if (row.accepted) last_accepted = row.trial_cost;
  }
  EXPECT_LT(last_accepted, report->initial_cost);
  EXPECT_NEAR(report->final_cost, last_accepted, 1e-12 * last_accepted);
  Expected<CostByKind> written = EvaluateCost(graph, options);
  ASSERT_TRUE(written.ok());
  EXPECT_NEAR(TotalCost(*written), last_accepted, 1e-12 * last_accepted);
}

TEST_F(ObjectCentricChartTest, StopBeforeTheFirstStepKeepsTheInitialValues) {
  SolverOptions options;
  options.should_stop = [] { return true; };
  Graph graph = graph_;
  Expected<SolveReport> report = Solve(options, &graph);
  ASSERT_TRUE(report.ok()) << report.error().ToString();
  EXPECT_EQ(report->termination, "interrupted");
  EXPECT_EQ(report->steps, 0);
  EXPECT_EQ(report->final_cost, report->initial_cost);
  for (const auto& [id, vertex] : graph.vertices) {
    for (int i = 0; i < kPoseSize; ++i) {  // object points pass through the solver's w = L_a·m_L
      EXPECT_NEAR(vertex.value[i], graph_.Find(id)->value[i], 1e-12) << "vertex " << id;
    }
  }
}

TEST_F(ObjectCentricChartTest, TimeLimitIsItsOwnTermination) {
  SolverOptions options;
  options.max_time = 1e-9;  // reached before the first step
  Graph graph = graph_;
  Expected<SolveReport> report = Solve(options, &graph);
  ASSERT_TRUE(report.ok()) << report.error().ToString();
  EXPECT_EQ(report->termination, "time_limit");
  EXPECT_TRUE(report->usable);
  EXPECT_EQ(report->steps, 0);
  options.max_time = -1;
  EXPECT_FALSE(Solve(options, &graph).ok());
}

// SPEC §7 item 7: the released code's LM stops when an accepted step lowers the cost by at most
// 1e-5 (relative or absolute) or after 100 accepted steps, with LM whatever the graph.
TEST_F(ObjectCentricChartTest, ReleasedRuleStopsOnTheFirstSmallDecrease) {
  SolverOptions options;
  options.dsc_released_lm = true;
  Graph graph = graph_;
  Expected<SolveReport> report = Solve(options, &graph);
  ASSERT_TRUE(report.ok()) << report.error().ToString();
  EXPECT_EQ(report->options_used.minimizer, MinimizerType::kLevenbergMarquardt);
  EXPECT_EQ(report->options_used.initial_lambda, 1e-5);
  EXPECT_FALSE(report->options_used.jacobi_scaling);  // GTSAM's λ·I
  EXPECT_LE(report->iterations, 100);
  ASSERT_GE(report->iterations, 2);
  // The rule: stop at the first step whose |cost change| ≤ 1e-5 · cost (Ceres's function
  // tolerance, which ends the solve before it records that trial step), or that is accepted with
  // a decrease ≤ 1e-5 (the last row), or after 100 accepted steps, or once λ ≥ 1e5.
  const std::vector<StepRecord>& rows = report->convergence;
  for (size_t i = 0; i < rows.size(); ++i) {
    const double change = rows[i].cost - rows[i].trial_cost;
    EXPECT_GT(std::abs(change), 1e-5 * rows[i].cost) << "step " << i + 1;
    if (rows[i].accepted && i + 1 < rows.size()) EXPECT_GT(change, 1e-5) << "step " << i + 1;
  }
  EXPECT_EQ(report->termination, "convergence") << report->termination_detail;
  EXPECT_TRUE(report->usable);
}

TEST_F(ObjectCentricChartTest, DefaultsAndObjectFrameReachTheSameOptimum) {
  ASSERT_EQ(SolverOptions{}.object_point_variables, Frame::kWorld);
  ASSERT_EQ(SolverOptions{}.kinematic_residual_frame, Frame::kWorld);
  Graph defaults = graph_, object_frame = graph_;
  Expected<SolveReport> a = Solve(Tight(Options(true, true)), &defaults);
  Expected<SolveReport> b = Solve(Tight(Options(false, false)), &object_frame);
  ASSERT_TRUE(a.ok() && b.ok());
  EXPECT_NEAR(a->final_cost, b->final_cost, 1e-9 * b->final_cost);
  // The graph holds m_L again, not the solver's w: its cost is the reported final cost.
  Expected<CostByKind> written = EvaluateCost(defaults, Options(false, false));
  ASSERT_TRUE(written.ok());
  EXPECT_NEAR(TotalCost(*written), a->final_cost, 1e-10 * a->final_cost);
  double largest = 0;
  for (const auto& [id, v] : defaults.vertices) {
    if (v.label.role != Role::kObjectPoint) continue;
    largest = std::max(largest, (v.point() - object_frame.Find(id)->point()).norm());
  }
  EXPECT_LT(largest, 1e-4);  // m; the two solves stop at tolerances, not at the exact optimum
}

// The default stopping rule (SolverOptions::remaining_chi2): the solve stops with termination
// "convergence" once the χ² it can still gain is estimated at most remaining_chi2, and that
// estimate holds: twice the distance of the final cost to the tight rule's optimum is at most
// remaining_chi2. The tight rule takes more steps to get there.
TEST_F(ObjectCentricChartTest, RemainingChi2RuleStopsWithinItsBoundOfTheOptimum) {
  Graph tight_graph = graph_;
  Expected<SolveReport> tight = Solve(Tight(SolverOptions{}), &tight_graph);
  ASSERT_TRUE(tight.ok()) << tight.error().ToString();
  for (const double remaining_chi2 : {1.0, 0.01, 1e-4}) {
    SolverOptions options;
    options.remaining_chi2 = remaining_chi2;
    Graph graph = graph_;
    Expected<SolveReport> report = Solve(options, &graph);
    ASSERT_TRUE(report.ok()) << report.error().ToString();
    EXPECT_EQ(report->termination, "convergence") << report->termination_detail;
    EXPECT_NE(report->termination_detail.find("remaining_chi2"), std::string::npos)
        << report->termination_detail;
    EXPECT_TRUE(report->usable);
    EXPECT_LT(report->steps, tight->steps) << remaining_chi2;
    EXPECT_GE(report->final_cost, tight->final_cost * (1 - 1e-12)) << remaining_chi2;
    EXPECT_LE(2 * (report->final_cost - tight->final_cost), remaining_chi2) << remaining_chi2;
  }
}

// The estimate needs two accepted decreases in a row: a first step, however small its decrease,
// never stops the solve by the rule.
TEST(SolverTest, RemainingChi2RuleNeedsTwoAcceptedStepsInARow) {
  Graph graph = Read(kTwoPoses);
  SolverOptions options;
  options.remaining_chi2 = 1e300;
  Expected<SolveReport> report = Solve(options, &graph);
  ASSERT_TRUE(report.ok()) << report.error().ToString();
  ASSERT_EQ(report->steps, 2);  // the first step's estimate is not told
  EXPECT_TRUE(report->convergence[0].accepted && report->convergence[1].accepted);
  EXPECT_EQ(report->termination, "convergence");
  options.remaining_chi2 = -1;
  EXPECT_FALSE(Solve(options, &graph).ok());
}

}  // namespace
}  // namespace dynslam
