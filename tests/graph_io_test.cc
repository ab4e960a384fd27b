// Graph files (SPEC §1): every tag, the 6×6 permutation, quaternion normalisation, bit-exact
// round trips, and every bad input of SPEC §1.6 as an error naming file, line and problem.
#include "dynslam/graph_io.h"

#include <cmath>
#include <cstring>
#include <filesystem>
#include <sstream>

#include <gtest/gtest.h>

#include "dynslam/json.h"
#include "reference_util.h"

namespace dynslam {
namespace {

Expected<Graph> ReadText(const std::string& text, const ReadOptions& options = {},
                         ReadReport* report = nullptr) {
  std::istringstream in(text);
  return ReadGraph(in, "test.g2o", options, report);
}

// Expects an error on `line` whose message contains `fragment`.
void ExpectError(const std::string& text, int64_t line, const std::string& fragment) {
  Expected<Graph> graph = ReadText(text);
  ASSERT_FALSE(graph.ok()) << "accepted:\n" << text;
  EXPECT_EQ(graph.error().file, "test.g2o");
  EXPECT_EQ(graph.error().line, line) << graph.error().ToString();
  EXPECT_NE(graph.error().message.find(fragment), std::string::npos)
      << "message: " << graph.error().message << "\nwanted: " << fragment;
}

const std::string kI21 = " 1 0 0 0 0 0 1 0 0 0 0 1 0 0 0 1 0 0 1 0 1";
const std::string kI6 = " 1 0 0 1 0 1";
const std::string kPose0 = "VERTEX_SE3:QUAT 0 0 0 0 0 0 0 1\n";
const std::string kPose1 = "VERTEX_SE3:QUAT 1 1 0 0 0 0 0 1\n";

// A small front-end file with every §1.2 tag: cameras 0, 1; static point 2; dynamic points 3
// (frame 0) and 4 (frame 1) of object 7; motion 5 at frame 1.
std::string FrontEnd() {
  return kPose0 + kPose1 +
         "VERTEX_TRACKXYZ 2 0 0 5\nVERTEX_TRACKXYZ 3 1 0 5\nVERTEX_TRACKXYZ 4 2 0 5\n"
         "VERTEX_SE3:QUAT 5 1 0 0 0 0 0 1\n"
         "EDGE_SE3_PRIOR 0 0 0 0 0 0 0 1" + kI21 + "\n"
         "EDGE_SE3:QUAT 0 1 1 0 0 0 0 0 1" + kI21 + "\n"
         "EDGE_SE3_TRACKXYZ 0 2 0 0 5" + kI6 + "\n"
         "EDGE_SE3_TRACKXYZ 0 3 1 0 5" + kI6 + " 1\n"
         "EDGE_SE3_TRACKXYZ 1 4 1 0 5" + kI6 + " 1\n"
         "EDGE_SE3_MOTION 3 4 5 0 0 0" + kI6 + " 7 1 1\n";
}

TEST(GraphIoTest, ReadsEveryFrontEndTagAndInfersRoles) {
  Expected<Graph> graph = ReadText(FrontEnd());
  ASSERT_TRUE(graph.ok()) << graph.error().ToString();
  EXPECT_FALSE(graph->labelled);
  EXPECT_EQ(graph->Find(0)->label.role, Role::kCamera);
  EXPECT_EQ(graph->Find(0)->label.frame, 0);
  EXPECT_EQ(graph->Find(1)->label.frame, 1);
  EXPECT_EQ(graph->Find(2)->label.role, Role::kStaticPoint);
  EXPECT_EQ(graph->Find(3)->label.role, Role::kDynamicPoint);
  EXPECT_EQ(graph->Find(3)->label.frame, 0);
  EXPECT_EQ(graph->Find(4)->label.frame, 1);
  EXPECT_EQ(graph->Find(4)->label.object, 7);
  EXPECT_EQ(graph->Find(5)->label.role, Role::kMotion);
  const auto counts = CountEdgesByKind(*graph);
  EXPECT_EQ(counts[static_cast<int>(EdgeKind::kPrior)], 1);
  EXPECT_EQ(counts[static_cast<int>(EdgeKind::kOdometry)], 1);
  EXPECT_EQ(counts[static_cast<int>(EdgeKind::kPoint)], 1);
  EXPECT_EQ(counts[static_cast<int>(EdgeKind::kDynamicPoint)], 2);
  EXPECT_EQ(counts[static_cast<int>(EdgeKind::kMotion)], 1);
  EXPECT_EQ(graph->motion_edges[0].camera, 1);
  EXPECT_TRUE(UnusedVertices(*graph).empty());
}

// File order is translation first (g2o); tangent order is [ω; ρ]: file diag 1..6 becomes
// 4 5 6 1 2 3, and file element (0, 4) — translation x with rotation y — lands at (3, 1).
TEST(GraphIoTest, PermutesSixBySixInformationOnceToTangentOrder) {
  const std::string info =
      " 1 0 0 0 0.5 0  2 0 0 0 0  3 0 0 0  4 0 0  5 0  6";
  Expected<Graph> graph =
      ReadText(kPose0 + kPose1 + "EDGE_SE3_PRIOR 0 0 0 0 0 0 0 1" + kI21 + "\nEDGE_SE3:QUAT 0 1 1 0 0 0 0 0 1" + info + "\n");
  ASSERT_TRUE(graph.ok()) << graph.error().ToString();
  const Matrix6d& m = graph->betweens[0].information;
  EXPECT_EQ(m.diagonal(), (Vector6d() << 4, 5, 6, 1, 2, 3).finished());
  EXPECT_EQ(m(3, 1), 0.5);
  EXPECT_EQ(m(1, 3), 0.5);
  EXPECT_EQ(m(0, 4), 0.0);
  std::ostringstream out;
  WriteGraph(*graph, out);
  EXPECT_NE(out.str().find("EDGE_SE3:QUAT 0 1 1 0 0 0 0 0 1 1 0 0 0 0.5 0 2 0 0 0 0 3 0 0 0 4 0 0 5 0 6\n"),
            std::string::npos)
      << out.str();
}

// SPEC §7 item 1: the released code reads the 6×6 information as already in [ω; ρ] order.
TEST(GraphIoTest, CompatReadsInformationWithoutPermutation) {
  ReadOptions options;
  options.information_in_tangent_order = true;
  Expected<Graph> graph = ReadText(kPose0 + "EDGE_SE3_PRIOR 0 0 0 0 0 0 0 1 1 0 0 0 0 0 2 0 0 0 0 3 0 0 0 4 0 0 5 0 6\n", options);
  ASSERT_TRUE(graph.ok()) << graph.error().ToString();
  EXPECT_EQ(graph->priors[0].information.diagonal(), (Vector6d() << 1, 2, 3, 4, 5, 6).finished());
}

TEST(GraphIoTest, NormalisesQuaternionsOffByMoreThan1e12Only) {
  Expected<Graph> graph = ReadText(
      "VERTEX_SE3:QUAT 0 0 0 0 0 0 0 2\nVERTEX_SE3:QUAT 1 0 0 0 0 0 0 1.0000000000001\n"
      "EDGE_SE3_PRIOR 0 0 0 0 0 0 0 1" + kI21 + "\nEDGE_SE3:QUAT 0 1 0 0 0 0 0 0 1" + kI21 + "\n");
  ASSERT_TRUE(graph.ok()) << graph.error().ToString();
  EXPECT_EQ(graph->Find(0)->value[3], 1.0);
  EXPECT_EQ(graph->Find(1)->value[3], 1.0000000000001);  // within 1e-12: kept as written
}

TEST(GraphIoTest, AcceptsBothPriorFormsCrlfTabsAndComments) {
  Expected<Graph> graph = ReadText(
      "# a comment\r\n\r\n" + kPose0 + "VERTEX_SE3:QUAT\t1\t1 0 0 0 0 0 1  # trailing\r\n"
      "EDGE_SE3_PRIOR 0 0 0 0 0 0 0 0 1" + kI21 + "\r\n"
      "EDGE_SE3_PRIOR 1 1 0 0 0 0 0 1" + kI21 + "\r\n");
  ASSERT_TRUE(graph.ok()) << graph.error().ToString();
  ASSERT_EQ(graph->priors.size(), 2u);
  EXPECT_TRUE(graph->priors[0].has_parameter_id);
  EXPECT_FALSE(graph->priors[1].has_parameter_id);
  EXPECT_EQ(graph->priors[1].measurement.translation().x(), 1.0);
}

TEST(GraphIoTest, SkipsAndCountsUnknownTagsOnlyWhenAsked) {
  const std::string text = kPose0 + "FIX 0\nFIX 0\nPARAMS_SE3OFFSET 0 0 0 0 0 0 0 1\n";
  ExpectError(text, 2, "unknown tag 'FIX'");
  ReadOptions options;
  options.skip_unknown_tags = true;
  ReadReport report;
  Expected<Graph> graph = ReadText(text, options, &report);
  ASSERT_TRUE(graph.ok()) << graph.error().ToString();
  EXPECT_EQ(report.skipped_tags["FIX"], 2);
  EXPECT_EQ(report.skipped_tags["PARAMS_SE3OFFSET"], 1);
}

TEST(GraphIoTest, RoundTripIsBitExact) {
  std::string text = FrontEnd();
  text += "VERTEX_SE3:QUAT 9 0.1 0.30000000000000004 1e-300 0.1 0.2 0.3 0.92736184954957035\n";
  Expected<Graph> first = ReadText(text);
  ASSERT_TRUE(first.ok()) << first.error().ToString();
  std::ostringstream out;
  WriteGraph(*first, out);
  Expected<Graph> second = ReadText(out.str());
  ASSERT_TRUE(second.ok()) << second.error().ToString() << "\n" << out.str();
  ASSERT_EQ(first->vertices.size(), second->vertices.size());
  for (const auto& [id, vertex] : first->vertices) {
    EXPECT_EQ(0, std::memcmp(vertex.value.data(), second->Find(id)->value.data(),
                             sizeof(vertex.value)))
        << "vertex " << id;
  }
  EXPECT_EQ(first->betweens[0].information, second->betweens[0].information);
  EXPECT_EQ(first->motion_edges[0].camera, second->motion_edges[0].camera);
}

// --- SPEC §1.6, one test per class ---

TEST(GraphIoBadInputTest, WrongFieldCount) {
  ExpectError(kPose0 + "VERTEX_TRACKXYZ 1 0 0\n", 2, "has 3 fields after the tag, expected 4");
  ExpectError(kPose0 + "EDGE_SE3_PRIOR 0 0 0 0 0 0 0 1 1\n", 2, "expected 29 or 30");
}

TEST(GraphIoBadInputTest, FieldNotANumberOrNotFinite) {
  ExpectError("VERTEX_TRACKXYZ 1 0 abc 0\n", 1, "'abc' is not a number");
  ExpectError("VERTEX_TRACKXYZ 1 0 nan 0\n", 1, "not finite");
  ExpectError("VERTEX_TRACKXYZ 1 0 1e999 0\n", 1, "'1e999'");
  ExpectError("VERTEX_TRACKXYZ -1 0 0 0\n", 1, "non-negative integer");
  ExpectError("VERTEX_TRACKXYZ 9223372036854775808 0 0 0\n", 1, "below 2^63");
  ExpectError("VERTEX_TRACKXYZ 1.5 0 0 0\n", 1, "non-negative integer");
}

TEST(GraphIoBadInputTest, InformationNotPositiveDefinite) {
  ExpectError(kPose0 + "VERTEX_TRACKXYZ 1 0 0 1\nEDGE_SE3_TRACKXYZ 0 1 0 0 1 1 0 0 -1 0 1\n", 3,
              "not symmetric positive definite");
  ExpectError(kPose0 + "EDGE_SE3_PRIOR 0 0 0 0 0 0 0 1 1 0 0 0 0 0 1 0 0 0 0 1 0 0 0 1 0 0 1 0 0\n", 2,
              "not symmetric positive definite");
}

TEST(GraphIoBadInputTest, ZeroQuaternion) {
  ExpectError("VERTEX_SE3:QUAT 0 0 0 0 0 0 0 0\n", 1, "quaternion");
}

TEST(GraphIoBadInputTest, EdgeNamesUndeclaredVertex) {
  ExpectError(kPose0 + "EDGE_SE3:QUAT 0 8 0 0 0 0 0 0 1" + kI21 + "\n", 2,
              "names vertex 8, which is not declared");
}

TEST(GraphIoBadInputTest, EdgesMayComeBeforeTheirVertices) {
  Expected<Graph> graph = ReadText("EDGE_SE3_PRIOR 0 0 0 0 0 0 0 1" + kI21 + "\n" + kPose0);
  EXPECT_TRUE(graph.ok()) << graph.error().ToString();
}

TEST(GraphIoBadInputTest, DuplicateVertexIdAndIdUsedAsTwoTypes) {
  ExpectError(kPose0 + kPose0, 2, "duplicate vertex id 0 (first declared on line 1)");
  ExpectError(kPose0 + "VERTEX_TRACKXYZ 0 1 2 3\n", 2, "used as two vertex types");
}

TEST(GraphIoBadInputTest, VertexOfWrongTypeForAnEdge) {
  ExpectError(kPose0 + "VERTEX_TRACKXYZ 1 0 0 1\nEDGE_SE3:QUAT 0 1 0 0 0 0 0 0 1" + kI21 + "\n", 3,
              "a point (line 2); expected a pose");
}

TEST(GraphIoBadInputTest, PartialLabels) {
  ExpectError(kPose0 + kPose1 + "LABEL_CAMERA 0 0\n", 2, "has no label, but the file labels others");
}

TEST(GraphIoBadInputTest, InconsistentLabels) {
  // A label on a missing vertex, on the wrong vertex type, twice on one vertex, and a role that
  // disagrees with an edge.
  ExpectError(kPose0 + "LABEL_CAMERA 0 0\nLABEL_CAMERA 4 1\n", 3, "names vertex 4, which is not declared");
  ExpectError(kPose0 + "LABEL_STATIC_POINT 0 0\n", 2, "this label is for a point");
  ExpectError(kPose0 + "LABEL_CAMERA 0 0\nLABEL_MOTION 0 1 1\n", 3, "second label");
  ExpectError(kPose0 + "VERTEX_TRACKXYZ 1 0 0 1\nEDGE_SE3_TRACKXYZ 0 1 0 0 1" + kI6 +
                  "\nLABEL_MOTION 0 1 1\nLABEL_STATIC_POINT 1 0\n",
              3, "expected a camera");
  ExpectError(kPose0 + "LABEL_FORMULATION wc\nLABEL_FORMULATION wc\nLABEL_CAMERA 0 0\n", 3, "appears twice");
}

TEST(GraphIoBadInputTest, StaticPointUsedByMotionEdge) {
  std::string text = FrontEnd();
  text.replace(text.find("EDGE_SE3_TRACKXYZ 0 3 1 0 5" + kI6 + " 1"),
               std::string("EDGE_SE3_TRACKXYZ 0 3 1 0 5" + kI6 + " 1").size(),
               "EDGE_SE3_TRACKXYZ 0 3 1 0 5" + kI6 + " 0");
  ExpectError(text, 12, "static_point");
}

TEST(GraphIoBadInputTest, TrackletThatBranches) {
  const std::string text = FrontEnd() + "VERTEX_TRACKXYZ 6 2 0 5\nEDGE_SE3_TRACKXYZ 1 6 1 0 5" + kI6 +
                           " 1\nEDGE_SE3_MOTION 3 6 5 0 0 0" + kI6 + " 7 1 1\n";
  ExpectError(text, 15, "tracklet branches: point 3 is 'prev' of two motion edges (the other on line 12)");
}

TEST(GraphIoBadInputTest, MotionEdgeCameraMustObserveTheCurrentPoint) {
  std::string text = FrontEnd();
  text.replace(text.find(" 7 1 1\n"), 7, " 7 1 0\n");
  ExpectError(text, 12, "is observed by camera 1");
}

// Found by fuzzing: with a dynamic point observed by two cameras, the motion edge's camera check
// depended on line order, so a file that read could be written in an order that did not.
TEST(GraphIoFuzzRegressionTest, MotionEdgeCameraCheckDoesNotDependOnLineOrder) {
  std::string text = FrontEnd();
  text += "EDGE_SE3_TRACKXYZ 0 4 1 0 5" + kI6 + " 1\n";  // point 4 also seen from camera 0
  Expected<Graph> graph = ReadText(text);
  ASSERT_TRUE(graph.ok()) << graph.error().ToString();
  std::ostringstream out;
  WriteGraph(*graph, out);  // camera 0's observation of point 4 is now written first
  Expected<Graph> again = ReadText(out.str());
  EXPECT_TRUE(again.ok()) << again.error().ToString();
}

// Found by fuzzing: a quaternion component of 1e290 overflowed the norm to inf and the reader
// stored a zero quaternion, which it then could not read back.
TEST(GraphIoFuzzRegressionTest, HugeQuaternionComponentsNormaliseWithoutOverflow) {
  Expected<Graph> graph = ReadText("VERTEX_SE3:QUAT 0 0 0 0 0 0 0 1e290\n"
                                   "VERTEX_SE3:QUAT 1 0 0 0 1e-200 0 0 1e-200\n");
  ASSERT_TRUE(graph.ok()) << graph.error().ToString();
  EXPECT_EQ(graph->Find(0)->value[3], 1.0);
  EXPECT_NEAR(graph->Find(1)->value[0], std::sqrt(0.5), 1e-15);
  EXPECT_NEAR(graph->Find(1)->value[3], std::sqrt(0.5), 1e-15);
}

TEST(GraphIoBadInputTest, NonexistentFileAndDirectory) {
  Expected<Graph> missing = ReadGraph("/nonexistent/graph.g2o");
  ASSERT_FALSE(missing.ok());
  EXPECT_EQ(missing.error().file, "/nonexistent/graph.g2o");
  EXPECT_FALSE(ReadGraph(std::filesystem::temp_directory_path().string()).ok());
}

// --- the reference set ---

class ReferenceGraphIoTest : public ::testing::TestWithParam<testing::ReferenceGraph> {};

// Roles and kinds as GTSAM's reference summary counts them, and a bit-exact round trip.
TEST_P(ReferenceGraphIoTest, CountsMatchReferenceAndRoundTripIsBitExact) {
  const testing::ReferenceGraph& reference = GetParam();
  Expected<Graph> graph = ReadGraph(reference.graph_path);
  ASSERT_TRUE(graph.ok()) << graph.error().ToString();
  Expected<Json> summary = Json::ReadFile(reference.ProfileDir("tight") + "/summary.json");
  ASSERT_TRUE(summary.ok()) << summary.error().ToString();
  for (const Role role : kAllRoles) {
    int64_t count = 0;
    for (const auto& [id, vertex] : graph->vertices) count += vertex.label.role == role;
    EXPECT_EQ(count, summary->FindPath({"variables", RoleName(role)})->number()) << RoleName(role);
  }
  const auto counts = CountEdgesByKind(*graph);
  for (const EdgeKind kind : kAllEdgeKinds) {
    EXPECT_EQ(counts[static_cast<int>(kind)],
              summary->FindPath({"edges", EdgeKindName(kind)})->number())
        << EdgeKindName(kind);
  }
  std::ostringstream out;
  WriteGraph(*graph, out);
  std::istringstream in(out.str());
  Expected<Graph> again = ReadGraph(in, "written");
  ASSERT_TRUE(again.ok()) << again.error().ToString();
  ASSERT_EQ(graph->vertices.size(), again->vertices.size());
  for (const auto& [id, vertex] : graph->vertices) {
    ASSERT_EQ(0, std::memcmp(vertex.value.data(), again->Find(id)->value.data(),
                             sizeof(vertex.value)))
        << "vertex " << id;
  }
  EXPECT_EQ(graph->NumEdges(), again->NumEdges());
}

INSTANTIATE_TEST_SUITE_P(Reference, ReferenceGraphIoTest,
                         ::testing::ValuesIn(testing::ReferenceGraphs()),
                         [](const auto& info) { return info.param.TestName(); });
GTEST_ALLOW_UNINSTANTIATED_PARAMETERIZED_TEST(ReferenceGraphIoTest);

}  // namespace
}  // namespace dynslam
