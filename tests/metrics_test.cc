// SPEC §5 metrics: a hand-computed case, and the metrics.json of every tight_exact solution of the
// independent GTSAM program (data/gtsam_ref) recomputed from its solution.g2o and the scene's gt.txt.
#include "dynslam/metrics.h"

#include <cmath>
#include <filesystem>
#include <functional>
#include <map>
#include <set>
#include <sstream>

#include <gtest/gtest.h>

#include "dynslam/graph_io.h"
#include "reference_util.h"

namespace dynslam {
namespace {

Pose TranslationZ(double z) {
  Pose pose;
  pose.translation() = Eigen::Vector3d(0, 0, z);
  return pose;
}

// Cameras at z = 0, 1, 2.5 against ground truth 0, 1, 2: pair (0,1) exact, pair (1,2) off by
// 0.5 m → mean E_t = 0.25 m over 2 pairs, E_r = 0. Object 3 moves +1 m per frame in truth; its
// estimated motion at frame 1 moves 1.2 m → one motion with E_t = 0.2 m.
TEST(MetricsTest, HandComputedCameraAndMotionErrors) {
  std::istringstream in(
      "VERTEX_SE3:QUAT 0 0 0 0 0 0 0 1\nVERTEX_SE3:QUAT 1 0 0 1 0 0 0 1\n"
      "VERTEX_SE3:QUAT 2 0 0 2.5 0 0 0 1\nVERTEX_SE3:QUAT 3 1.2 0 0 0 0 0 1\n"
      "LABEL_CAMERA 0 0\nLABEL_CAMERA 1 1\nLABEL_CAMERA 2 2\nLABEL_MOTION 3 3 1\n");
  Expected<Graph> graph = ReadGraph(in, "hand.g2o");
  ASSERT_TRUE(graph.ok()) << graph.error().ToString();
  GroundTruth gt;
  for (int k = 0; k < 3; ++k) gt.cameras[k] = TranslationZ(k);
  gt.objects[{3, 0}] = Pose::FromRotationTranslation(Eigen::Quaterniond::Identity(), {5, 0, 0});
  gt.objects[{3, 1}] = Pose::FromRotationTranslation(Eigen::Quaterniond::Identity(), {6, 0, 0});
  const Metrics m = ComputeMetrics(*graph, gt);
  EXPECT_EQ(m.camera.count, 2);
  EXPECT_NEAR(m.camera.mean_trans_m, 0.25, 1e-15);
  EXPECT_EQ(m.camera.mean_rot_deg, 0);
  EXPECT_EQ(m.object_motion.count, 1);
  EXPECT_EQ(m.object_motion.objects, 1);
  EXPECT_NEAR(m.object_motion.mean_trans_m, 0.2, 1e-15);
  // World-centric pose: L_0 = L^gt_0, L_1 = H_1 · L_0 → relative pose error equals the motion's.
  EXPECT_EQ(m.object_pose.count, 1);
  EXPECT_NEAR(m.object_pose.mean_trans_m, 0.2, 1e-15);
}

TEST(MetricsTest, RotationErrorIsInDegreesAndRobustNearPi) {
  const Pose identity;
  Pose half_turn;
  half_turn.data = {0, 0, 1, 0, 0, 0, 0};  // 180° about z
  EXPECT_NEAR(PoseError(identity, half_turn).first, 180.0, 1e-12);
  Pose quarter = Pose::FromRotationTranslation(
      Eigen::Quaterniond(Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitX())), {0, 0, 0});
  EXPECT_NEAR(PoseError(quarter, identity).first, 90.0, 1e-12);
}

// E_r is robust at both ends: 1e-9 rad and π − 1e-9 rad (acos of the trace would lose both).
TEST(MetricsTest, RotationErrorIsAccurateNearZeroAndNearPi) {
  const Pose identity;
  const Eigen::Vector3d axis = Eigen::Vector3d(1, -2, 0.5).normalized();
  for (const double angle : {1e-9, 1e-6, M_PI - 1e-6, M_PI - 1e-9}) {
    const Pose rotated = Pose::FromRotationTranslation(
        Eigen::Quaterniond(Eigen::AngleAxisd(angle, axis)), {0, 0, 0});
    EXPECT_NEAR(PoseError(identity, rotated).first, angle * 180 / M_PI, 1e-12 * 180) << angle;
    EXPECT_NEAR(PoseError(rotated, identity).first, angle * 180 / M_PI, 1e-12 * 180) << angle;
  }
}

// World-centric object poses start each run of motions at its ground-truth pose (SPEC §5).
// Object 5: motions at frames 1, 2 and 5, 6; ground truth at frames 0, 1, 2, 5, 6 (not 4), moving
// +1 m in x per frame. Estimated motions move exactly that except H_2 (+1.5 m).
// Motions: H_1, H_2, H_6 have ground truth (H_5 needs L^gt_4): 3 motions, E_t 0, 0.5, 0 → 1/6.
// Poses: the run 1..2 starts at L^gt_0 → pairs (0,1) E_t 0 and (1,2) E_t 0.5, mean 0.25; the run
// 5..6 has no L^gt_4 → skipped (no pairs) and counted.
TEST(MetricsTest, WorldCentricSegmentWithoutGroundTruthStartIsSkippedAndCounted) {
  std::istringstream in(
      "VERTEX_SE3:QUAT 0 0 0 0 0 0 0 1\n"
      "VERTEX_SE3:QUAT 1 1 0 0 0 0 0 1\nVERTEX_SE3:QUAT 2 1.5 0 0 0 0 0 1\n"
      "VERTEX_SE3:QUAT 5 1 0 0 0 0 0 1\nVERTEX_SE3:QUAT 6 1 0 0 0 0 0 1\n"
      "LABEL_CAMERA 0 0\nLABEL_MOTION 1 5 1\nLABEL_MOTION 2 5 2\nLABEL_MOTION 5 5 5\n"
      "LABEL_MOTION 6 5 6\n");
  Expected<Graph> graph = ReadGraph(in, "wc.g2o");
  ASSERT_TRUE(graph.ok()) << graph.error().ToString();
  GroundTruth gt;
  for (const int k : {0, 1, 2, 5, 6}) {
    gt.objects[{5, k}] = Pose::FromRotationTranslation(Eigen::Quaterniond::Identity(), {double(k), 0, 0});
  }
  const Metrics m = ComputeMetrics(*graph, gt);
  EXPECT_FALSE(m.object_centric);
  EXPECT_EQ(m.camera.count, 0);
  EXPECT_EQ(m.object_motion.count, 3);
  EXPECT_NEAR(m.object_motion.mean_trans_m, 0.5 / 3, 1e-15);
  EXPECT_EQ(m.object_pose.count, 2);
  EXPECT_EQ(m.object_pose.objects, 1);
  EXPECT_NEAR(m.object_pose.per_object.at(5).mean_trans_m, 0.25, 1e-15);
  EXPECT_EQ(m.segments_without_ground_truth_start, 1);
  const Expected<JsonValue> json = ParseJson(MetricsJson(m), "metrics");
  ASSERT_TRUE(json.ok()) << json.error().ToString();
  EXPECT_EQ(NumberAt(*json, {"object_pose", "segments_without_ground_truth_start"}), 1);
  EXPECT_EQ(NumberAt(*json, {"object_pose", "per_object", "5", "pairs"}), 2);
}

// Object-centric: the L variables themselves, over the pairs (k−1, k) that have a motion H_k.
// L at the truth (+1 m per frame) except L_2 at 2.5 m: pairs (0,1) E_t 0, (1,2) 0.5, (5,6) 0;
// (4,5) has a motion but no L_4 variable and no L^gt_4 → not a pair. Mean 1/6.
TEST(MetricsTest, ObjectCentricUsesTheObjectPoses) {
  std::ostringstream text;
  for (const int k : {1, 2, 5, 6}) text << "VERTEX_SE3:QUAT " << k << " 1 0 0 0 0 0 1\nLABEL_MOTION " << k << " 5 " << k << "\n";
  for (const int k : {0, 1, 2, 5, 6}) {
    text << "VERTEX_SE3:QUAT " << 10 + k << " " << (k == 2 ? 2.5 : k) << " 0 0 0 0 0 1\nLABEL_OBJECT_POSE "
         << 10 + k << " 5 " << k << "\n";
  }
  std::istringstream in(text.str());
  Expected<Graph> graph = ReadGraph(in, "oc.g2o");
  ASSERT_TRUE(graph.ok()) << graph.error().ToString();
  GroundTruth gt;
  for (const int k : {0, 1, 2, 5, 6}) {
    gt.objects[{5, k}] = Pose::FromRotationTranslation(Eigen::Quaterniond::Identity(), {double(k), 0, 0});
  }
  const Metrics m = ComputeMetrics(*graph, gt);
  EXPECT_TRUE(m.object_centric);
  EXPECT_EQ(m.object_pose.count, 3);
  EXPECT_NEAR(m.object_pose.mean_trans_m, 0.5 / 3, 1e-15);
  EXPECT_EQ(m.object_motion.count, 3);  // H_1, H_2, H_6 exact
  EXPECT_NEAR(m.object_motion.mean_trans_m, 0, 1e-15);
  // Object-centric metrics carry no segments_without_ground_truth_start (as the reference files).
  EXPECT_FALSE(MetricsToJson(m)["object_pose"].contains("segments_without_ground_truth_start"));
}

// The same keys, recursively, as the reference (the shape of SPEC §5).
void ExpectSameKeys(const JsonValue& ours, const JsonValue& reference, const std::string& path) {
  std::set<std::string> mine, theirs;
  for (const auto& [key, value] : ours.items()) mine.insert(key);
  for (const auto& [key, value] : reference.items()) theirs.insert(key);
  EXPECT_EQ(mine, theirs) << path;
  for (const auto& [key, value] : reference.items()) {
    if (ours.contains(key) && value.is_object()) ExpectSameKeys(ours[key], value, path + key + ".");
  }
}

// Every numeric leaf of the reference metrics equals ours (counts exactly, means to 1e-9).
void ExpectSameNumbers(const JsonValue& ours, const JsonValue& reference, const std::string& path) {
  for (const auto& [key, value] : reference.items()) {
    ASSERT_TRUE(ours.contains(key)) << path + key;
    if (value.is_object()) {
      ExpectSameNumbers(ours[key], value, path + key + ".");
    } else if (value.is_number()) {
      const double expected = value.get<double>();
      EXPECT_NEAR(NumberAt(ours, {key.c_str()}), expected, 1e-9 * std::max(1.0, std::abs(expected)))
          << path + key;
    }
  }
}

class ReferenceMetricsTest : public ::testing::TestWithParam<testing::ReferenceGraph> {};

TEST_P(ReferenceMetricsTest, RecomputedFromTheSolutionMatchGtsamMetrics) {
  const testing::ReferenceGraph& reference = GetParam();
  const std::filesystem::path solve_dir = reference.IndependentDir("tight_exact");
  Expected<Graph> solution = ReadGraph((solve_dir / "solution.g2o").string());
  ASSERT_TRUE(solution.ok()) << solution.error().ToString();
  const std::filesystem::path scene = std::filesystem::path(reference.graph_path).parent_path().parent_path();
  Expected<GroundTruth> gt = ReadGroundTruth((scene / "gt.txt").string());
  ASSERT_TRUE(gt.ok()) << gt.error().ToString();
  Expected<JsonValue> expected = ReadJsonFile((solve_dir / "metrics.json").string());
  ASSERT_TRUE(expected.ok()) << expected.error().ToString();
  const Expected<JsonValue> ours = ParseJson(MetricsJson(ComputeMetrics(*solution, *gt)), "ours");
  ASSERT_TRUE(ours.ok()) << ours.error().ToString();
  for (const char* family : {"camera", "object_motion", "object_pose"}) {
    ASSERT_TRUE(expected->contains(family)) << family;
    ExpectSameNumbers((*ours)[family], (*expected)[family], std::string(family) + ".");
    ExpectSameKeys((*ours)[family], (*expected)[family], std::string(family) + ".");
  }
  EXPECT_EQ((*ours)["object_centric"], (*expected)["object_centric"]);
}

// errors.csv's rows (Metrics::per_frame) are exactly what the tables average: per quantity and
// object, their count and mean are the metrics' (which the test above holds to GTSAM's).
TEST_P(ReferenceMetricsTest, PerFrameErrorsAverageToTheTables) {
  const testing::ReferenceGraph& reference = GetParam();
  Expected<Graph> solution =
      ReadGraph((std::filesystem::path(reference.IndependentDir("tight_exact")) / "solution.g2o").string());
  ASSERT_TRUE(solution.ok()) << solution.error().ToString();
  const std::filesystem::path scene = std::filesystem::path(reference.graph_path).parent_path().parent_path();
  Expected<GroundTruth> gt = ReadGroundTruth((scene / "gt.txt").string());
  ASSERT_TRUE(gt.ok()) << gt.error().ToString();
  const Metrics metrics = ComputeMetrics(*solution, *gt);
  std::map<std::pair<std::string, int64_t>, ErrorMean> sums;
  for (const FrameError& e : metrics.per_frame) {
    ErrorMean& sum = sums[{e.quantity, e.object}];
    ++sum.count;
    sum.mean_rot_deg += e.rot_deg;
    sum.mean_trans_m += e.trans_m;
  }
  auto expect_mean = [&](const std::string& quantity, int64_t object, const ErrorMean& mean) {
    const ErrorMean& sum = sums[{quantity, object}];
    ASSERT_EQ(sum.count, mean.count) << quantity << " " << object;
    EXPECT_NEAR(sum.mean_rot_deg / sum.count, mean.mean_rot_deg, 1e-12 * (1 + mean.mean_rot_deg));
    EXPECT_NEAR(sum.mean_trans_m / sum.count, mean.mean_trans_m, 1e-12 * (1 + mean.mean_trans_m));
  };
  expect_mean("camera", -1, metrics.camera);
  size_t groups = 1;
  for (const auto& [name, family] : {std::pair{"object_motion", &metrics.object_motion},
                                     std::pair{"object_pose", &metrics.object_pose}}) {
    for (const auto& [object, mean] : family->per_object) expect_mean(name, object, mean);
    groups += family->per_object.size();
  }
  EXPECT_EQ(sums.size(), groups);  // no rows beyond what the tables average
  EXPECT_GT(metrics.object_motion.count, 0);
}

// The dynamic scenes: those whose tight_exact solve has metrics.
std::vector<testing::ReferenceGraph> GraphsWithMetrics() {
  std::vector<testing::ReferenceGraph> graphs;
  for (const testing::ReferenceGraph& graph : testing::ReferenceGraphs()) {
    if (std::filesystem::exists(graph.IndependentDir("tight_exact") + "/metrics.json")) {
      graphs.push_back(graph);
    }
  }
  return graphs;
}

INSTANTIATE_TEST_SUITE_P(Reference, ReferenceMetricsTest, ::testing::ValuesIn(GraphsWithMetrics()),
                         [](const auto& info) { return info.param.TestName(); });
GTEST_ALLOW_UNINSTANTIATED_PARAMETERIZED_TEST(ReferenceMetricsTest);

}  // namespace
}  // namespace dynslam
