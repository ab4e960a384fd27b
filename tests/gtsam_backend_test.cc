// The GTSAM backend (gtsam_backend.h): its factors' Jacobians, its costs against the Ceres
// path's, and its solves against the independent GTSAM program's (data/gtsam_ref: not made by
// this backend, tests/reference_util.h) — initial cost per kind to 1e-12, final cost to 1e-9,
// LM iterations on `released`, marginals to 1e-8. Built only with DYNSLAM_WITH_GTSAM (label
// gtsam).
#include <cmath>
#include <filesystem>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <gtsam/nonlinear/factorTesting.h>

#include "dynslam/compat.h"
#include "dynslam/graph_io.h"
#include "dynslam/gtsam_backend.h"
#include "dynslam/solver.h"
#include "src/gtsam/factors.h"
#include "src/gtsam/problem.h"
#include "src/json_io.h"
#include "tests/reference_util.h"

namespace dynslam::testing {
namespace {

namespace fs = std::filesystem;
using gtsam::Point3;
using gtsam::Pose3;

// ---- factors ----

// Rotations well inside (−π, π) (σ 0.3 rad per axis): near π, Log's derivative and the
// numerical one it is checked against are both ill-conditioned.
Pose3 RandomPose(std::mt19937* rng) {
  std::normal_distribution<double> n(0, 1);
  return Pose3::Expmap((gtsam::Vector6() << 0.3 * n(*rng), 0.3 * n(*rng), 0.3 * n(*rng),
                        5 * n(*rng), 5 * n(*rng), 5 * n(*rng)).finished());
}

Point3 RandomPoint(std::mt19937* rng) {
  std::normal_distribution<double> n(0, 5);
  return Point3(n(*rng), n(*rng), n(*rng));
}

// Checks each custom factor's Jacobians against GTSAM's numerical derivative at random values.
TEST(GtsamFactors, JacobiansEqualNumericalDerivatives) {
  std::mt19937 rng(7);
  const auto noise3 = gtsam::noiseModel::Unit::Create(3);
  const auto noise6 = gtsam::noiseModel::Unit::Create(6);
  using namespace gtsam_backend;
  for (int trial = 0; trial < 20; ++trial) {
    gtsam::Values values;
    for (gtsam::Key k : {0, 1, 2}) values.insert(k, RandomPose(&rng));
    for (gtsam::Key k : {10, 11}) values.insert(k, RandomPoint(&rng));
    const Point3 z = RandomPoint(&rng);
    const Pose3 Z = RandomPose(&rng);
    const std::vector<std::pair<std::string, gtsam::NoiseModelFactor::shared_ptr>> factors = {
        {"camera point", boost::make_shared<CameraPointFactor>(0, 10, z, noise3)},
        {"point motion", boost::make_shared<PointMotionFactor>(10, 11, 0, z, false, noise3)},
        {"point motion dsc", boost::make_shared<PointMotionFactor>(10, 11, 0, z, true, noise3)},
        {"object point", boost::make_shared<ObjectPointFactor>(0, 1, 10, z, noise3)},
        {"object motion", boost::make_shared<ObjectMotionFactor>(0, 1, 2, 10, z, false, noise3)},
        {"object motion dsc", boost::make_shared<ObjectMotionFactor>(0, 1, 2, 10, z, true, noise3)},
        {"kinematic", boost::make_shared<KinematicFactor>(0, 1, 2, noise6)},
        {"exact prior", boost::make_shared<ExactPriorFactor>(0, Z, noise6)},
        {"exact between", boost::make_shared<ExactBetweenFactor>(0, 1, Z, noise6)},
        {"hybrid point", boost::make_shared<HybridPointFactor>(0, 1, 10, Z, z, noise3)},
        {"hybrid smoothing", boost::make_shared<HybridSmoothingFactor>(0, 1, 2, Z, noise6)},
    };
    for (const auto& [name, factor] : factors) {
      EXPECT_TRUE(gtsam::internal::testFactorJacobians(name, *factor, values, 1e-5, 1e-5))
          << name << ", trial " << trial;
    }
  }
}

// ---- against the Ceres path and the independent GTSAM program ----

fs::path IndependentDir(const ReferenceGraph& graph, const std::string& profile) {
  return graph.IndependentDir(profile);
}

std::vector<ReferenceGraph> AllReferenceGraphs() {
  std::vector<ReferenceGraph> graphs = ReferenceGraphs();
  for (const char* scene : {"synthetic", "kitti_0003"}) {
    const fs::path path = fs::path(ReferenceHybridDir()) / scene / "graphs" / "hy.g2o";
    if (fs::exists(path)) graphs.push_back({scene, "hy", path.string()});
  }
  return graphs;
}

class GtsamBackendTest : public ::testing::TestWithParam<ReferenceGraph> {
 protected:
  Graph Read() const {
    Expected<Graph> graph = ReadGraph(GetParam().graph_path);
    EXPECT_TRUE(graph.ok()) << graph.error().ToString();
    return graph.ok() ? std::move(graph).value() : Graph();
  }
  JsonValue Independent(const std::string& profile) const {
    const fs::path path = IndependentDir(GetParam(), profile) / "summary.json";
    Expected<JsonValue> json = ReadJsonFile(path.string());
    EXPECT_TRUE(json.ok()) << path;
    return json.ok() ? *json : JsonValue();
  }
};

// 1e-12 relative, or 1e-6 where residuals fall in GTSAM's approximate near-π branch of Logmap
// (torus3D: tests/reference_cost_test.cc, docs/SPEC_NOTES.md).
double Tolerance(const Graph& graph) {
  return ResidualsInGtsamNearPiBranch(graph) > 0 ? 1e-6 : 1e-12;
}

// The same SPEC §1.5 cost per edge kind as the Ceres cost functions with `options`, at the
// graph's values.
void ExpectCostPerKindOfTheCeresPath(const Graph& graph, const SolverOptions& options,
                                     double tolerance) {
  Expected<CostByKind> ceres = EvaluateCost(graph, options);
  ASSERT_TRUE(ceres.ok()) << ceres.error().ToString();
  Expected<gtsam_backend::Problem> problem =
      gtsam_backend::BuildProblem(graph, *GtsamProfileNamed("tight_exact"), options);
  ASSERT_TRUE(problem.ok());
  const CostByKind gtsam = gtsam_backend::CostsByKind(*problem, problem->values);
  const double total = TotalCost(*ceres);
  for (const EdgeKind kind : kAllEdgeKinds) {
    const int k = static_cast<int>(kind);
    EXPECT_NEAR(gtsam[k], (*ceres)[k], tolerance * std::abs((*ceres)[k]) + 1e-15 * total)
        << EdgeKindName(kind);
  }
}

TEST_P(GtsamBackendTest, InitialCostPerKindEqualsTheCeresPath) {
  const Graph graph = Read();
  ExpectCostPerKindOfTheCeresPath(graph, SolverOptions(), Tolerance(graph));
}

// With the released code's residuals and kernels (SPEC §7 items 2, 3, 5, 6: `--compat dsc`), the
// same cost per kind as the Ceres path with the same options.
TEST_P(GtsamBackendTest, ReleasedCodeResidualsCostAsTheCeresPath) {
  const Graph graph = Read();
  Compat compat;
  ASSERT_FALSE(ParseCompat("dsc", &compat).has_value());
  SolverOptions options;
  ApplyCompat(compat, GetParam().formulation == "wc", &options);
  ExpectCostPerKindOfTheCeresPath(graph, options, Tolerance(graph));
}

// Initial cost per kind to 1e-12, final cost to 1e-9, and on `released` GTSAM's LM iteration
// count, against the independent program on every profile.
TEST_P(GtsamBackendTest, SolvesAsTheIndependentGtsamProgram) {
  for (const std::string profile : {"released", "tight", "tight_exact"}) {
    if (!fs::exists(IndependentDir(GetParam(), profile))) continue;
    SCOPED_TRACE(profile);
    Graph graph = Read();
    Expected<SolveReport> report =
        SolveWithGtsam(*GtsamProfileNamed(profile), SolverOptions(), &graph);
    ASSERT_TRUE(report.ok()) << report.error().ToString();
    const JsonValue expected = Independent(profile);
    const double initial = NumberAt(expected, {"initial_cost"});
    for (const EdgeKind kind : kAllEdgeKinds) {  // the hybrid summaries list only hy's kinds
      if (!expected["cost_by_kind"]["initial"].contains(EdgeKindName(kind))) continue;
      const double want = NumberAt(expected, {"cost_by_kind", "initial", EdgeKindName(kind)});
      EXPECT_NEAR(report->initial_cost_by_kind[static_cast<int>(kind)], want,
                  1e-12 * std::abs(want) + 1e-15 * initial)
          << EdgeKindName(kind);
    }
    EXPECT_LE(RelativeDifference(report->final_cost, NumberAt(expected, {"final_cost"})), 1e-9);
    if (profile == "released") {
      EXPECT_EQ(report->iterations, NumberAt(expected, {"iterations"}));
    }
  }
}

class GtsamMarginalsTest : public GtsamBackendTest {};

// gtsam::Marginals at the tight_exact solution, to 1e-8 of each block's largest entry.
TEST_P(GtsamMarginalsTest, EqualTheIndependentProgramS) {
  const fs::path expected_path = IndependentDir(GetParam(), "tight_exact") / "marginals.csv";
  Graph graph = Read();
  const GtsamProfile profile = *GtsamProfileNamed("tight_exact");
  ASSERT_TRUE(SolveWithGtsam(profile, SolverOptions(), &graph).ok());
  const std::map<VertexId, Eigen::MatrixXd> expected = ReadMarginals(expected_path.string());
  std::vector<VertexId> ids;
  for (const auto& [id, covariance] : expected) ids.push_back(id);
  Expected<CovarianceReport> computed = GtsamCovariances(graph, profile, SolverOptions(), ids);
  ASSERT_TRUE(computed.ok()) << computed.error().ToString();
  ASSERT_EQ(computed->marginals.size(), expected.size());
  for (const MarginalCovariance& m : computed->marginals) {
    const Eigen::MatrixXd& want = expected.at(m.id);
    EXPECT_LE((m.covariance - want).cwiseAbs().maxCoeff(), 1e-8 * want.cwiseAbs().maxCoeff())
        << "vertex " << m.id;
  }
}

INSTANTIATE_TEST_SUITE_P(Reference, GtsamBackendTest, ::testing::ValuesIn(AllReferenceGraphs()),
                         [](const auto& info) { return info.param.TestName(); });

// The graphs the independent program has marginals for (not the pose graphs, hy or kitti_0003
// oc_a, whose system GTSAM finds singular: SingularMarginalsAreAnErrorThatNamesThem).
std::vector<ReferenceGraph> GraphsWithMarginals() {
  std::vector<ReferenceGraph> graphs;
  for (const ReferenceGraph& g : AllReferenceGraphs()) {
    if (fs::exists(IndependentDir(g, "tight_exact") / "marginals.csv")) graphs.push_back(g);
  }
  return graphs;
}

INSTANTIATE_TEST_SUITE_P(Reference, GtsamMarginalsTest, ::testing::ValuesIn(GraphsWithMarginals()),
                         [](const auto& info) { return info.param.TestName(); });

// A graph GTSAM cannot solve: Gauss–Newton on a camera that one point edge leaves undetermined.
TEST(GtsamBackend, SingularSystemIsAFailureThatNamesIt) {
  std::istringstream text(
      "VERTEX_SE3:QUAT 0 0 0 0 0 0 0 1\n"
      "VERTEX_SE3:QUAT 1 1 0 0 0 0 0 1\n"
      "VERTEX_TRACKXYZ 2 1 0 5\n"
      "EDGE_SE3_PRIOR 0 0 0 0 0 0 0 1 1 0 0 0 0 0 1 0 0 0 0 1 0 0 0 1 0 0 1 0 1\n"
      "EDGE_SE3_TRACKXYZ 1 2 0 0 5 1 0 0 1 0 1\n");
  Expected<Graph> graph = ReadGraph(text, "singular.g2o");
  ASSERT_TRUE(graph.ok()) << graph.error().ToString();
  Expected<SolveReport> report = SolveWithGtsam(*GtsamProfileNamed("gn"), SolverOptions(), &*graph);
  ASSERT_TRUE(report.ok()) << report.error().ToString();
  EXPECT_EQ(report->termination, "failure");
  EXPECT_FALSE(report->usable);
  EXPECT_NE(report->termination_detail.find("singular"), std::string::npos)
      << report->termination_detail;
}

TEST(GtsamBackend, UnknownProfileNamesTheKnownOnes) {
  Expected<std::optional<GtsamProfile>> parsed = ParseBackend("gtsam:fast");
  ASSERT_FALSE(parsed.ok());
  EXPECT_NE(parsed.error().message.find("released, tight, tight_exact, dogleg, gn"),
            std::string::npos);
  EXPECT_FALSE(ParseBackend("g2o").ok());
  EXPECT_FALSE(ParseBackend("ceres")->has_value());
}

}  // namespace
}  // namespace dynslam::testing
