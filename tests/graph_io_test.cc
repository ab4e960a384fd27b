// Graph files (SPEC §1): every tag, the 6×6 permutation, quaternion normalisation, bit-exact
// round trips, and every bad input of SPEC §1.6 as an error naming file, line and problem.
#include "dynslam/graph_io.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <unistd.h>

#include <Eigen/Eigenvalues>
#include <gtest/gtest.h>

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
  EXPECT_EQ(graph->Edges<MotionEdge>()[0].camera, 1);
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
  const Matrix6d& m = graph->Edges<BetweenEdge>()[0].information;
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
  EXPECT_EQ(graph->Edges<PriorEdge>()[0].information.diagonal(), (Vector6d() << 1, 2, 3, 4, 5, 6).finished());
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
  ASSERT_EQ(graph->Edges<PriorEdge>().size(), 2u);
  EXPECT_TRUE(graph->Edges<PriorEdge>()[0].has_parameter_id);
  EXPECT_FALSE(graph->Edges<PriorEdge>()[1].has_parameter_id);
  EXPECT_EQ(graph->Edges<PriorEdge>()[1].measurement.translation().x(), 1.0);
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
  EXPECT_EQ(first->Edges<BetweenEdge>()[0].information, second->Edges<BetweenEdge>()[0].information);
  EXPECT_EQ(first->Edges<MotionEdge>()[0].camera, second->Edges<MotionEdge>()[0].camera);
}

// --- SPEC §1.6, one test per class ---

TEST(GraphIoBadInputTest, WrongFieldCount) {
  ExpectError(kPose0 + "VERTEX_TRACKXYZ 1 0 0\n", 2, "has 3 fields after the tag, expected 4");
  ExpectError(kPose0 + "EDGE_SE3_PRIOR 0 0 0 0 0 0 0 1 1\n", 2, "expected 29 or 30");
  // A tag without an optional field names one count.
  ExpectError(kPose0 + "EDGE_SE3:QUAT 0 0 1\n", 2,
              "has 3 fields after the tag, expected 30 (a b tx ty tz qx qy qz qw I(21))");
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

// --- more SPEC §1.6 classes and the inference rules of SPEC §3.1 ---

// [1 0.7; 0.7 0.49] has determinant 0.49 − 0.7² = 0 (by hand): positive semi-definite only. In
// binary 0.49 rounds above fl(0.7·0.7), so a plain Cholesky factorisation succeeds on it.
TEST(GraphIoBadInputTest, NumericallySingularInformationIsRejected) {
  ExpectError(kPose0 + "VERTEX_TRACKXYZ 1 0 0 1\nEDGE_SE3_TRACKXYZ 0 1 0 0 1 1 0 0 1 0.7 0.49\n", 3,
              "not symmetric positive definite");
  // Asymmetry cannot be written (upper triangle only); a negative diagonal can.
  ExpectError(kPose0 + "VERTEX_TRACKXYZ 1 0 0 1\nEDGE_SE3_TRACKXYZ 0 1 0 0 1 -1 0 0 1 0 1\n", 3,
              "fields 6 to 11");
}

// ReadOptions::repair_information: diag(1, [1 0.7; 0.7 0.49]) (eigenvalues 0, 1, 1.49 by hand) and
// diag(1, −1, 1) become positive definite with their smallest eigenvalue at 1e-9 × the largest;
// an all-zero matrix has nothing to keep and stays an error.
TEST(GraphIoBadInputTest, RepairInformationClampsEigenvaluesAndReportsTheLines) {
  ReadOptions options;
  options.repair_information = true;
  ReadReport report;
  const std::string text = kPose0 + "VERTEX_TRACKXYZ 1 0 0 1\n" +
                           "EDGE_SE3_TRACKXYZ 0 1 0 0 1 1 0 0 1 0.7 0.49\n" +
                           "EDGE_SE3_TRACKXYZ 0 1 0 0 1 1 0 0 -1 0 1\n" +
                           "EDGE_SE3_TRACKXYZ 0 1 0 0 1 1 0 0 1 0 1\n";
  std::istringstream in(text);
  Expected<Graph> graph = ReadGraph(in, "repair.g2o", options, &report);
  ASSERT_TRUE(graph.ok()) << graph.error().ToString();
  EXPECT_EQ(report.repaired_information_lines, (std::vector<int64_t>{3, 4}));
  ASSERT_EQ(graph->Edges<PointEdge>().size(), 3u);
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> rank_one(graph->Edges<PointEdge>()[0].information);
  EXPECT_NEAR(rank_one.eigenvalues()(2), 1.49, 1e-12);
  EXPECT_NEAR(rank_one.eigenvalues()(0), 1.49e-9, 1e-15);
  EXPECT_NEAR(graph->Edges<PointEdge>()[0].information(1, 2), 0.7, 1e-9);
  const Eigen::Matrix3d& indefinite = graph->Edges<PointEdge>()[1].information;
  EXPECT_NEAR(indefinite(1, 1), 1e-9, 1e-15);
  EXPECT_NEAR(indefinite(0, 0), 1.0, 1e-12);
  EXPECT_EQ(graph->Edges<PointEdge>()[2].information, Eigen::Matrix3d::Identity());  // untouched

  std::istringstream zero(kPose0 + "VERTEX_TRACKXYZ 1 0 0 1\nEDGE_SE3_TRACKXYZ 0 1 0 0 1 0 0 0 0 0 0\n");
  Expected<Graph> bad = ReadGraph(zero, "zero.g2o", options);
  ASSERT_FALSE(bad.ok());
  EXPECT_EQ(bad.error().line, 3);
}

TEST(GraphIoBadInputTest, ZeroQuaternionInAnEdgeMeasurement) {
  ExpectError(kPose0 + "EDGE_SE3_PRIOR 0 0 0 0 0 0 0 0" + kI21 + "\n", 2, "quaternion");
}

TEST(GraphIoBadInputTest, PriorParameterIdMustBeZero) {
  ExpectError(kPose0 + "EDGE_SE3_PRIOR 0 1 0 0 0 0 0 0 1" + kI21 + "\n", 2,
              "offset-parameter id must be 0, not 1");
}

TEST(GraphIoBadInputTest, IsDynamicMustBeZeroOrOne) {
  ExpectError(kPose0 + "VERTEX_TRACKXYZ 1 0 0 1\nEDGE_SE3_TRACKXYZ 0 1 0 0 1" + kI6 + " 2\n", 3,
              "is_dynamic '2' must be 0 or 1");
  ExpectError(kPose0 + "VERTEX_TRACKXYZ 1 0 0 1\nEDGE_SE3_TRACKXYZ 0 1 0 0 1" + kI6 + " 1.0\n", 3,
              "is_dynamic");
}

TEST(GraphIoBadInputTest, NumberWithTrailingGarbage) {
  ExpectError("VERTEX_TRACKXYZ 1 0 2x 0\n", 1, "'2x' is not a number");
  ExpectError("VERTEX_TRACKXYZ 1x 0 0 0\n", 1, "vertex id '1x'");
}

// Without labels a pose gets its role from the edges; one that two edges give different roles
// is an error naming both lines.
TEST(GraphIoBadInputTest, UnlabelledPoseWithTwoRoles) {
  std::string text = FrontEnd();
  text.replace(text.find("EDGE_SE3_MOTION 3 4 5"), 21, "EDGE_SE3_MOTION 3 4 0");
  ExpectError(text, 12, "uses vertex 0 as motion, but the EDGE_SE3_TRACKXYZ on line 9 uses it as camera");
}

TEST(GraphIoBadInputTest, OdometryBetweenACameraAndAMotion) {
  const std::string text = FrontEnd() + "EDGE_SE3:QUAT 1 5 0 0 0 0 0 0 1" + kI21 + "\n";
  ExpectError(text, 13, "it must join two cameras (odometry) or two motions (smoothing)");
}

TEST(GraphIoBadInputTest, MotionEdgeWhoseCurrentPointIsNotObserved) {
  const std::string text = FrontEnd() + "VERTEX_TRACKXYZ 6 3 0 5\nEDGE_SE3_MOTION 4 6 5 0 0 0" + kI6 +
                           " 7 2 1\n";
  ExpectError(text, 14, "point 6 ('curr') has no EDGE_SE3_TRACKXYZ");
}

TEST(GraphIoBadInputTest, TrackletThatBranchesAtItsEnd) {
  // Points 3 and 6 both continue into point 4.
  const std::string text = FrontEnd() + "VERTEX_TRACKXYZ 6 2 0 5\nEDGE_SE3_TRACKXYZ 0 6 1 0 5" + kI6 +
                           " 1\nEDGE_SE3_MOTION 6 4 5 0 0 0" + kI6 + " 7 1 1\n";
  ExpectError(text, 15, "point 4 is 'curr' of two motion edges (the other on line 12)");
}

// A labelled front end whose motion edge joins points of the wrong frames or object.
TEST(GraphIoBadInputTest, LabelledMotionEdgeDisagreesWithLabels) {
  const std::string labels =
      "LABEL_CAMERA 0 0\nLABEL_CAMERA 1 1\nLABEL_STATIC_POINT 2 0\nLABEL_MOTION 5 7 1\n";
  const std::string good = FrontEnd() + labels + "LABEL_DYNAMIC_POINT 3 7 0 1\nLABEL_DYNAMIC_POINT 4 7 1 1\n";
  Expected<Graph> graph = ReadText(good);
  ASSERT_TRUE(graph.ok()) << graph.error().ToString();
  EXPECT_TRUE(graph->labelled);
  ExpectError(FrontEnd() + labels + "LABEL_DYNAMIC_POINT 3 7 1 1\nLABEL_DYNAMIC_POINT 4 7 1 1\n",
              12, "expected k-1, k and k");
  ExpectError(FrontEnd() + labels + "LABEL_DYNAMIC_POINT 3 8 0 1\nLABEL_DYNAMIC_POINT 4 7 1 1\n",
              12, "joins vertices labelled with objects 8, 7 and 7");
  // A camera labelled as a motion: its EDGE_SE3_TRACKXYZ (line 11) is the first edge to disagree.
  std::string text = good;
  text.replace(text.find("LABEL_CAMERA 1 1"), 16, "LABEL_MOTION 1 7 2");
  ExpectError(text, 11, "field 'pose' is vertex 1, a motion; expected a camera");
}

// An unlabelled object-centric file (SPEC §1.3 edges): roles from the edges, kinds from the
// roles. Expected values by hand from SPEC §1.5 and §3.1.
TEST(GraphIoTest, InfersObjectCentricRolesAndKinds) {
  const std::string pose = " 0 0 0 0 0 0 1\n";
  Expected<Graph> graph = ReadText(
      "VERTEX_SE3:QUAT 1" + pose + "VERTEX_SE3:QUAT 0" + pose + "VERTEX_SE3:QUAT 10" + pose +
      "VERTEX_SE3:QUAT 11" + pose + "VERTEX_SE3:QUAT 14" + pose + "VERTEX_SE3:QUAT 12" + pose +
      "VERTEX_SE3:QUAT 13" + pose + "VERTEX_TRACKXYZ 20 0 0 1\n"
      "EDGE_SE3_PRIOR 0 0 0 0 0 0 0 1" + kI21 + "\n"
      "EDGE_SE3_PRIOR 10 0 0 0 0 0 0 1" + kI21 + "\n"
      "EDGE_SE3:QUAT 0 1 0 0 0 0 0 0 1" + kI21 + "\n"
      "EDGE_SE3:QUAT 12 13 0 0 0 0 0 0 1" + kI21 + "\n"
      "EDGE_SE3_OBJ_TRACKXYZ 0 10 20 0 0 1" + kI6 + "\n"
      "EDGE_SE3_OBJ_TRACKXYZ 1 11 20 0 0 1" + kI6 + "\n"
      "EDGE_SE3_OBJ_MOTION 10 11 12 20" + kI6 + "\n"
      "EDGE_SE3_OBJ_KINEMATIC 10 11 12" + kI21 + "\n"
      "EDGE_SE3_OBJ_KINEMATIC 11 14 13" + kI21 + "\n");
  ASSERT_TRUE(graph.ok()) << graph.error().ToString();
  const std::map<VertexId, Role> expected = {
      {0, Role::kCamera},     {1, Role::kCamera},     {10, Role::kObjectPose},
      {11, Role::kObjectPose}, {14, Role::kObjectPose}, {12, Role::kMotion},
      {13, Role::kMotion},    {20, Role::kObjectPoint}};
  for (const auto& [id, role] : expected) {
    EXPECT_EQ(graph->Find(id)->label.role, role) << "vertex " << id;
  }
  EXPECT_EQ(graph->Find(0)->label.frame, 0);  // cameras sorted by id: frames 0, 1 (SPEC §3.1)
  EXPECT_EQ(graph->Find(1)->label.frame, 1);
  const std::array<int64_t, kNumEdgeKinds> expected_kinds = {
      /*prior*/ 1, /*odometry*/ 1, /*smoothing*/ 1, /*point*/ 0, /*dynamic_point*/ 0,
      /*motion*/ 0, /*object_point*/ 2, /*object_motion*/ 1, /*kinematic*/ 2, /*object_prior*/ 1};
  EXPECT_EQ(CountEdgesByKind(*graph), expected_kinds);
  EXPECT_EQ(KindOf(*graph, graph->Edges<PriorEdge>()[1]), EdgeKind::kObjectPrior);
  EXPECT_EQ(KindOf(*graph, graph->Edges<BetweenEdge>()[1]), EdgeKind::kSmoothing);
}

// SPEC §1.3: EDGE_SE3_OBJ_MOTION's trailing z is optional (0 when absent) and written only when
// it is not 0, so files without it read and write as before.
TEST(GraphIoTest, ObjectMotionMeasurementIsAnOptionalTrailingField) {
  const std::string pose = " 0 0 0 0 0 0 1\n";
  const std::string vertices = "VERTEX_SE3:QUAT 10" + pose + "VERTEX_SE3:QUAT 11" + pose +
                               "VERTEX_SE3:QUAT 12" + pose + "VERTEX_TRACKXYZ 20 0 0 1\n";
  Expected<Graph> with = ReadText(vertices + "EDGE_SE3_OBJ_MOTION 10 11 12 20" + kI6 +
                                  " 0.25 -0.5 2\n");
  ASSERT_TRUE(with.ok()) << with.error().ToString();
  EXPECT_EQ(with->Edges<ObjectMotionEdge>()[0].measurement, Eigen::Vector3d(0.25, -0.5, 2));
  Expected<Graph> without = ReadText(vertices + "EDGE_SE3_OBJ_MOTION 10 11 12 20" + kI6 + "\n");
  ASSERT_TRUE(without.ok()) << without.error().ToString();
  EXPECT_EQ(without->Edges<ObjectMotionEdge>()[0].measurement, Eigen::Vector3d::Zero());
  auto edge_line = [](const Graph& graph) {
    std::ostringstream out;
    WriteGraph(graph, out);
    const std::string text = out.str();
    const size_t at = text.find("EDGE_SE3_OBJ_MOTION");
    return text.substr(at, text.find('\n', at) - at);
  };
  EXPECT_EQ(edge_line(*without), "EDGE_SE3_OBJ_MOTION 10 11 12 20" + kI6);
  EXPECT_EQ(edge_line(*with), "EDGE_SE3_OBJ_MOTION 10 11 12 20" + kI6 + " 0.25 -0.5 2");
  ExpectError(vertices + "EDGE_SE3_OBJ_MOTION 10 11 12 20" + kI6 + " 0.25 -0.5\n", 5,
              "pose_prev pose_curr motion point I(6) [zx zy zz]");
}

TEST(GraphIoTest, UnusedVerticesCountTheMotionEdgeCameraAsAUse) {
  Graph graph;
  for (const VertexId id : {0, 1, 2, 3, 4, 9}) graph.vertices[id] = Vertex{};
  MotionEdge edge;
  edge.prev = 1;
  edge.curr = 2;
  edge.motion = 3;
  edge.camera = 4;
  graph.Edges<MotionEdge>().push_back(edge);
  EXPECT_EQ(UnusedVertices(graph), (std::vector<VertexId>{0, 9}));
}

// SPEC §3.4 order, checked against a hand-written file: LABEL_FORMULATION first, vertices by id,
// edges by kind (prior, odometry, smoothing, point, dynamic_point, motion) and by vertex ids,
// labels by id; priors without the parameter id; EDGE_SE3_TRACKXYZ always with is_dynamic.
TEST(GraphIoTest, WritesInSpecOrder) {
  const std::string input =
      "EDGE_SE3_MOTION 4 5 6 0 0 0" + kI6 + " 3 1 1\n"
      "EDGE_SE3_TRACKXYZ 1 5 1 0 5" + kI6 + " 1\n"
      "EDGE_SE3_TRACKXYZ 0 4 1 0 5" + kI6 + " 1\n"
      "EDGE_SE3_TRACKXYZ 1 2 -1 0 5" + kI6 + "\n"
      "EDGE_SE3_TRACKXYZ 0 2 0 0 5" + kI6 + " 0\n"
      "EDGE_SE3:QUAT 6 7 0 0 0 0 0 0 1" + kI21 + "\n"
      "EDGE_SE3:QUAT 0 1 1 0 0 0 0 0 1" + kI21 + "\n"
      "EDGE_SE3_PRIOR 1 0 1 0 0 0 0 0 1" + kI21 + "\n"
      "EDGE_SE3_PRIOR 0 0 0 0 0 0 0 1" + kI21 + "\n"
      "VERTEX_SE3:QUAT 7 1 0 0 0 0 0 1\nVERTEX_TRACKXYZ 5 2 0 5\nVERTEX_SE3:QUAT 6 1 0 0 0 0 0 1\n"
      "VERTEX_TRACKXYZ 4 1 0 5\nVERTEX_TRACKXYZ 2 0 0 5\nVERTEX_SE3:QUAT 1 1 0 0 0 0 0 1\n"
      "VERTEX_SE3:QUAT 0 0 0 0 0 0 0 1\n"
      "LABEL_MOTION 7 3 2\nLABEL_MOTION 6 3 1\nLABEL_DYNAMIC_POINT 5 3 1 1\nLABEL_DYNAMIC_POINT 4 3 0 1\n"
      "LABEL_STATIC_POINT 2 0\nLABEL_CAMERA 1 1\nLABEL_CAMERA 0 0\nLABEL_FORMULATION frontend\n";
  const std::string expected =
      "LABEL_FORMULATION frontend\n"
      "VERTEX_SE3:QUAT 0 0 0 0 0 0 0 1\nVERTEX_SE3:QUAT 1 1 0 0 0 0 0 1\nVERTEX_TRACKXYZ 2 0 0 5\n"
      "VERTEX_TRACKXYZ 4 1 0 5\nVERTEX_TRACKXYZ 5 2 0 5\nVERTEX_SE3:QUAT 6 1 0 0 0 0 0 1\n"
      "VERTEX_SE3:QUAT 7 1 0 0 0 0 0 1\n"
      "EDGE_SE3_PRIOR 0 0 0 0 0 0 0 1" + kI21 + "\n"
      "EDGE_SE3_PRIOR 1 1 0 0 0 0 0 1" + kI21 + "\n"
      "EDGE_SE3:QUAT 0 1 1 0 0 0 0 0 1" + kI21 + "\n"
      "EDGE_SE3:QUAT 6 7 0 0 0 0 0 0 1" + kI21 + "\n"
      "EDGE_SE3_TRACKXYZ 0 2 0 0 5" + kI6 + " 0\n"
      "EDGE_SE3_TRACKXYZ 1 2 -1 0 5" + kI6 + " 0\n"
      "EDGE_SE3_TRACKXYZ 0 4 1 0 5" + kI6 + " 1\n"
      "EDGE_SE3_TRACKXYZ 1 5 1 0 5" + kI6 + " 1\n"
      "EDGE_SE3_MOTION 4 5 6 0 0 0" + kI6 + " 3 1 1\n"
      "LABEL_CAMERA 0 0\nLABEL_CAMERA 1 1\nLABEL_STATIC_POINT 2 0\nLABEL_DYNAMIC_POINT 4 3 0 1\n"
      "LABEL_DYNAMIC_POINT 5 3 1 1\nLABEL_MOTION 6 3 1\nLABEL_MOTION 7 3 2\n";
  Expected<Graph> graph = ReadText(input);
  ASSERT_TRUE(graph.ok()) << graph.error().ToString();
  std::ostringstream out;
  WriteGraph(*graph, out);
  EXPECT_EQ(out.str(), expected);
}

// Every field of every edge survives read → write → read bit for bit (SPEC §1: the shortest
// exact form).
TEST(GraphIoTest, RoundTripKeepsEveryEdgeDoubleBitExact) {
  const std::string info6 = " 0.1 1e-5 3e-300 0 0 0.7 2.5 0 0 0 0 3.3333333333333335 0 0 0 4 0 0 5 0 6";
  const std::string text = "VERTEX_SE3:QUAT 0 -0 1e-310 3.141592653589793 0.5 0.5 0.5 0.5\n"
                           "VERTEX_SE3:QUAT 1 1.0000000000000002 2 3 0 0 0.38268343236508978 0.92387953251128674\n"
                           "EDGE_SE3_PRIOR 0 0 0.1 0.2 0.3 0 0 0 1" + info6 + "\n"
                           "EDGE_SE3:QUAT 0 1 0.1 0.2 0.3 0.1 0.2 0.3 0.9" + info6 + "\n";
  Expected<Graph> first = ReadText(text);
  ASSERT_TRUE(first.ok()) << first.error().ToString();
  std::ostringstream out;
  WriteGraph(*first, out);
  Expected<Graph> second = ReadText(out.str());
  ASSERT_TRUE(second.ok()) << second.error().ToString();
  auto same_bits = [](const auto& a, const auto& b) {
    return a.size() == b.size() && std::memcmp(a.data(), b.data(), sizeof(double) * a.size()) == 0;
  };
  for (const auto& [id, vertex] : first->vertices) {
    EXPECT_TRUE(same_bits(vertex.value, second->Find(id)->value)) << "vertex " << id;
  }
  EXPECT_TRUE(std::signbit(second->Find(0)->value[4]));  // -0 stays -0
  EXPECT_EQ(second->Find(0)->value[5], 1e-310);          // subnormal kept
  EXPECT_TRUE(same_bits(first->Edges<PriorEdge>()[0].measurement.data, second->Edges<PriorEdge>()[0].measurement.data));
  EXPECT_TRUE(same_bits(first->Edges<PriorEdge>()[0].information, second->Edges<PriorEdge>()[0].information));
  EXPECT_TRUE(same_bits(first->Edges<BetweenEdge>()[0].measurement.data, second->Edges<BetweenEdge>()[0].measurement.data));
  EXPECT_TRUE(same_bits(first->Edges<BetweenEdge>()[0].information, second->Edges<BetweenEdge>()[0].information));
  EXPECT_FALSE(second->Edges<PriorEdge>()[0].has_parameter_id);
}

TEST(GraphIoTest, FailedWriteKeepsTheExistingFile) {
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("graph_io_test_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const std::string path = (dir / "graph.g2o").string();
  Expected<Graph> graph = ReadText(FrontEnd());
  ASSERT_TRUE(graph.ok()) << graph.error().ToString();
  ASSERT_TRUE(WriteGraph(*graph, path).ok());
  // Block the temporary file beside the target with a directory: the write must fail cleanly.
  std::filesystem::create_directories(path + ".partial");
  Graph empty;
  const Status failed = WriteGraph(empty, path);
  EXPECT_FALSE(failed.ok());
  EXPECT_EQ(failed.error().file, path);
  Expected<Graph> again = ReadGraph(path);
  ASSERT_TRUE(again.ok()) << again.error().ToString();
  EXPECT_EQ(again->vertices.size(), 6u);
  EXPECT_FALSE(WriteGraph(empty, (dir / "missing" / "graph.g2o").string()).ok());
  std::filesystem::remove_all(dir);
}

// --- the reference set ---

class ReferenceGraphIoTest : public ::testing::TestWithParam<testing::ReferenceGraph> {};

// A count in a reference summary.json; summaries written before SPEC §3.6 do not list the
// hybrid's roles and edge kinds, which then count 0.
double SummaryCount(const JsonValue& summary, const char* section, const char* name) {
  const double count = NumberAt(summary, {section, name});
  return std::isnan(count) ? 0 : count;
}

// Roles and kinds as GTSAM's reference summary counts them, and a bit-exact round trip.
TEST_P(ReferenceGraphIoTest, CountsMatchReferenceAndRoundTripIsBitExact) {
  const testing::ReferenceGraph& reference = GetParam();
  Expected<Graph> graph = ReadGraph(reference.graph_path);
  ASSERT_TRUE(graph.ok()) << graph.error().ToString();
  Expected<JsonValue> summary = ReadJsonFile(reference.ProfileDir("tight") + "/summary.json");
  ASSERT_TRUE(summary.ok()) << summary.error().ToString();
  for (const Role role : kAllRoles) {
    int64_t count = 0;
    for (const auto& [id, vertex] : graph->vertices) count += vertex.label.role == role;
    EXPECT_EQ(count, SummaryCount(*summary, "variables", RoleName(role))) << RoleName(role);
  }
  const auto counts = CountEdgesByKind(*graph);
  for (const EdgeKind kind : kAllEdgeKinds) {
    EXPECT_EQ(counts[static_cast<int>(kind)], SummaryCount(*summary, "edges", EdgeKindName(kind)))
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

// Every graph file of the reference set (SPEC §6): front ends, built graphs and the GTSAM
// solutions (VERTEX and LABEL lines only, no edges), relative to ReferenceDir().
// `name` restricts to files of that name ("" for all).
std::vector<std::string> ReferenceFiles(const std::string& name = "") {
  std::vector<std::string> files;
  const std::filesystem::path root(testing::ReferenceDir());
  std::error_code ec;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(root, ec)) {
    const std::filesystem::path& path = entry.path();
    if (path.extension() != ".g2o") continue;
    const std::string relative = std::filesystem::relative(path, root).generic_string();
    const std::string parent = path.parent_path().filename().string();
    if (!name.empty() && path.filename() != name) continue;
    if (path.filename() == "frontend.g2o" || parent == "graphs" ||
        (path.filename() == "solution.g2o" && parent.rfind("tight", 0) == 0)) {
      files.push_back(relative);
    }
  }
  std::sort(files.begin(), files.end());
  return files;
}

class ReferenceFileIoTest : public ::testing::TestWithParam<std::string> {
 protected:
  std::string Path() const {
    return (std::filesystem::path(testing::ReferenceDir()) / GetParam()).string();
  }
};
class ReferenceSolutionIoTest : public ReferenceFileIoTest {};
class ReferenceFrontEndIoTest : public ReferenceFileIoTest {};

// Reads without error; write → read → write gives the same text (so every double of every
// record survives bit for bit: the shortest exact form is one-to-one) and the same vertex bits.
TEST_P(ReferenceFileIoTest, ReadsAndRoundTripsBitExact) {
  Expected<Graph> graph = ReadGraph(Path());
  ASSERT_TRUE(graph.ok()) << graph.error().ToString();
  std::ostringstream first;
  WriteGraph(*graph, first);
  std::istringstream in(first.str());
  Expected<Graph> again = ReadGraph(in, "written");
  ASSERT_TRUE(again.ok()) << again.error().ToString();
  std::ostringstream second;
  WriteGraph(*again, second);
  EXPECT_TRUE(first.str() == second.str()) << "second write differs from the first";
  ASSERT_EQ(graph->vertices.size(), again->vertices.size());
  for (const auto& [id, vertex] : graph->vertices) {
    ASSERT_EQ(0, std::memcmp(vertex.value.data(), again->Find(id)->value.data(),
                             sizeof(vertex.value)))
        << "vertex " << id;
    ASSERT_EQ(vertex.label.role, again->Find(id)->label.role) << "vertex " << id;
  }
  EXPECT_EQ(graph->NumEdges(), again->NumEdges());
  EXPECT_EQ(graph->labelled, again->labelled);
  EXPECT_EQ(graph->formulation, again->formulation);
}

// A solution carries the input's labels: its variables by role are GTSAM's counts.
TEST_P(ReferenceSolutionIoTest, RolesMatchTheSummary) {
  Expected<Graph> graph = ReadGraph(Path());
  ASSERT_TRUE(graph.ok()) << graph.error().ToString();
  EXPECT_EQ(graph->NumEdges(), 0u);
  const std::string summary_path =
      (std::filesystem::path(Path()).parent_path() / "summary.json").string();
  Expected<JsonValue> summary = ReadJsonFile(summary_path);
  ASSERT_TRUE(summary.ok()) << summary.error().ToString();
  for (const Role role : kAllRoles) {
    int64_t count = 0;
    for (const auto& [id, vertex] : graph->vertices) count += vertex.label.role == role;
    EXPECT_EQ(count, SummaryCount(*summary, "variables", RoleName(role))) << RoleName(role);
  }
}

// SPEC §3.1 inference against the labels an independent simulator wrote: with its LABEL lines
// removed, a front end gets the same role for every vertex, the same camera frames, and the same
// object and frame for every motion and every dynamic point that a motion edge uses.
TEST_P(ReferenceFrontEndIoTest, UnlabelledInfersTheLabels) {
  Expected<Graph> labelled = ReadGraph(Path());
  ASSERT_TRUE(labelled.ok()) << labelled.error().ToString();
  ASSERT_TRUE(labelled->labelled);
  std::ifstream file(Path());
  std::string line, text;
  while (std::getline(file, line)) {
    if (line.rfind("LABEL_", 0) != 0) text += line + '\n';
  }
  std::istringstream in(text);
  Expected<Graph> inferred = ReadGraph(in, "unlabelled");
  ASSERT_TRUE(inferred.ok()) << inferred.error().ToString();
  ASSERT_FALSE(inferred->labelled);
  std::set<VertexId> in_motion_edge;
  for (const MotionEdge& e : labelled->Edges<MotionEdge>()) in_motion_edge.insert({e.prev, e.curr});
  for (const auto& [id, vertex] : labelled->vertices) {
    const Label& want = vertex.label;
    const Label& got = inferred->Find(id)->label;
    ASSERT_EQ(got.role, want.role) << "vertex " << id;
    if (want.role == Role::kCamera) EXPECT_EQ(got.frame, want.frame) << "camera " << id;
    if (want.role == Role::kMotion || in_motion_edge.count(id) > 0) {
      EXPECT_EQ(got.object, want.object) << "vertex " << id;
      EXPECT_EQ(got.frame, want.frame) << "vertex " << id;
    }
  }
  EXPECT_EQ(CountEdgesByKind(*inferred), CountEdgesByKind(*labelled));
}

std::string FileTestName(const ::testing::TestParamInfo<std::string>& info) {
  std::string name = info.param;
  std::replace_if(name.begin(), name.end(), [](char c) { return !std::isalnum(c); }, '_');
  return name;
}
INSTANTIATE_TEST_SUITE_P(Reference, ReferenceFileIoTest, ::testing::ValuesIn(ReferenceFiles()),
                         FileTestName);
INSTANTIATE_TEST_SUITE_P(Reference, ReferenceSolutionIoTest,
                         ::testing::ValuesIn(ReferenceFiles("solution.g2o")), FileTestName);
INSTANTIATE_TEST_SUITE_P(Reference, ReferenceFrontEndIoTest,
                         ::testing::ValuesIn(ReferenceFiles("frontend.g2o")), FileTestName);
GTEST_ALLOW_UNINSTANTIATED_PARAMETERIZED_TEST(ReferenceFileIoTest);
GTEST_ALLOW_UNINSTANTIATED_PARAMETERIZED_TEST(ReferenceSolutionIoTest);
GTEST_ALLOW_UNINSTANTIATED_PARAMETERIZED_TEST(ReferenceFrontEndIoTest);

}  // namespace
}  // namespace dynslam
