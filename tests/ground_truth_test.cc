// SPEC §2 ground-truth files: the records, comments and line ends of the format, every bad input
// rejected with file:line (never a crash), bit-exact write → read, and the reference scenes'
// gt.txt read with the record counts of the file itself.
#include "dynslam/ground_truth.h"

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "reference_util.h"

namespace dynslam {
namespace {

namespace fs = std::filesystem;

class GroundTruthTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("dynslam_ground_truth_test_" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) +
            "_" + ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string Write(const std::string& text, const std::string& name = "gt.txt") {
    const std::string path = (dir_ / name).string();
    std::ofstream(path, std::ios::binary) << text;
    return path;
  }

  // Reading `text` fails at `line` with a message containing `words`.
  void ExpectError(const std::string& text, int64_t line, const std::string& words) {
    const std::string path = Write(text);
    Expected<GroundTruth> gt = ReadGroundTruth(path);
    ASSERT_FALSE(gt.ok()) << "accepted: " << text;
    EXPECT_EQ(gt.error().file, path);
    EXPECT_EQ(gt.error().line, line) << gt.error().ToString();
    EXPECT_NE(gt.error().message.find(words), std::string::npos) << gt.error().ToString();
  }

  fs::path dir_;
};

TEST_F(GroundTruthTest, ReadsRecordsCommentsTabsAndCrLf) {
  const std::string path = Write(
      "# header\r\n"
      "\r\n"
      "CAMERA 0 1 2 3 0 0 0 1   # X_0\r\n"
      "OBJECT\t4\t7\t-1 0.5 2e1 0 0 1 0\r\n"  // frame 4, object 7, 180° about z
      "   \t \n");
  Expected<GroundTruth> gt = ReadGroundTruth(path);
  ASSERT_TRUE(gt.ok()) << gt.error().ToString();
  ASSERT_EQ(gt->cameras.size(), 1u);
  ASSERT_EQ(gt->objects.size(), 1u);
  ASSERT_NE(gt->Camera(0), nullptr);
  EXPECT_EQ(gt->Camera(0)->translation(), Eigen::Vector3d(1, 2, 3));
  EXPECT_EQ(gt->Camera(0)->rotation().coeffs(), Eigen::Quaterniond::Identity().coeffs());
  EXPECT_EQ(gt->Camera(1), nullptr);
  // SPEC §2: `OBJECT k j …` — frame first, then object.
  ASSERT_NE(gt->Object(7, 4), nullptr);
  EXPECT_EQ(gt->Object(4, 7), nullptr);
  EXPECT_EQ(gt->Object(7, 4)->translation(), Eigen::Vector3d(-1, 0.5, 20));
  EXPECT_EQ(gt->Object(7, 4)->rotation().coeffs(), Eigen::Vector4d(0, 0, 1, 0));
}

TEST_F(GroundTruthTest, NormalisesQuaternionsThatAreNotUnit) {
  // SPEC §0: a norm off 1 by more than 1e-12 is normalised; (0 0 0 2) → identity.
  Expected<GroundTruth> gt = ReadGroundTruth(Write("CAMERA 3 0 0 0 0 0 0 2\n"));
  ASSERT_TRUE(gt.ok()) << gt.error().ToString();
  EXPECT_EQ(gt->Camera(3)->rotation().coeffs(), Eigen::Quaterniond::Identity().coeffs());
}

TEST_F(GroundTruthTest, RejectsBadRecordsWithFileAndLine) {
  const std::string ok = "# comment\nCAMERA 0 0 0 0 0 0 0 1\n";  // bad record on line 3
  ExpectError(ok + "CAMERA 1 0 0 0 0 0 1\n", 3, "has 7 fields, expected 8");
  ExpectError(ok + "CAMERA 1 0 0 0 0 0 0 1 5\n", 3, "has 9 fields, expected 8");
  ExpectError(ok + "OBJECT 1 0 0 0 0 0 0 1\n", 3, "has 8 fields, expected 9");
  ExpectError(ok + "CAMERA 1 0 x 0 0 0 0 1\n", 3, "'x' is not a finite number");
  ExpectError(ok + "CAMERA 1 0 0 0 0 0 0 1e999\n", 3, "not a finite number");
  ExpectError(ok + "CAMERA 1 nan 0 0 0 0 0 1\n", 3, "not a finite number");
  ExpectError(ok + "CAMERA 1 inf 0 0 0 0 0 1\n", 3, "not a finite number");
  ExpectError(ok + "CAMERA 1 0 0 0 0 0 0 0\n", 3, "zero quaternion");
  ExpectError(ok + "CAMERA 0 1 0 0 0 0 0 1\n", 3, "second CAMERA record for frame 0");
  ExpectError(ok + "OBJECT 2 5 0 0 0 0 0 0 1\nOBJECT 2 5 1 0 0 0 0 0 1\n", 4,
              "second OBJECT record for object 5 at frame 2");
  ExpectError(ok + "CAMERA -1 0 0 0 0 0 0 1\n", 3, "not a non-negative integer");
  ExpectError(ok + "CAMERA 1.5 0 0 0 0 0 0 1\n", 3, "not a non-negative integer");
  ExpectError(ok + "CAMERA 99999999999999999999 0 0 0 0 0 0 1\n", 3, "not a non-negative integer");
  ExpectError(ok + "OBJECT 1 j 0 0 0 0 0 0 1\n", 3, "object 'j'");
  ExpectError(ok + "POINT 1 0 0 0\n", 3, "unknown record 'POINT'");
  ExpectError(ok + "camera 1 0 0 0 0 0 0 1\n", 3, "unknown record");
}

TEST_F(GroundTruthTest, RejectsFilesThatCannotBeRead) {
  Expected<GroundTruth> missing = ReadGroundTruth((dir_ / "missing.txt").string());
  ASSERT_FALSE(missing.ok());
  EXPECT_NE(missing.error().ToString().find("missing.txt"), std::string::npos);
  // A directory opens on Linux but reads nothing: an error, not an empty ground truth.
  Expected<GroundTruth> directory = ReadGroundTruth(dir_.string());
  EXPECT_FALSE(directory.ok());
}

// Every prefix of a valid file, cut anywhere, is either read or rejected (never a crash), and a
// cut inside the last record is rejected at that record's line.
TEST_F(GroundTruthTest, TruncatedFilesNeverCrash) {
  const std::string text = "CAMERA 0 0 0 0 0 0 0 1\nOBJECT 0 3 1 2 3 0 0 0 1\n";
  const size_t second_line = text.find('\n') + 1;
  for (size_t n = 0; n <= text.size(); ++n) {
    Expected<GroundTruth> gt = ReadGroundTruth(Write(text.substr(0, n)));
    if (n > second_line && n < text.size() - 1) {
      ASSERT_FALSE(gt.ok()) << "prefix of " << n << " bytes";
      EXPECT_EQ(gt.error().line, 2) << gt.error().ToString();
    }
  }
}

TEST_F(GroundTruthTest, WriteThenReadIsBitExact) {
  GroundTruth gt;
  const Eigen::Quaterniond q = Eigen::Quaterniond(0.1, -0.7, 0.3, 0.2).normalized();
  gt.cameras[0] = Pose::FromRotationTranslation(Eigen::Quaterniond::Identity(), {0, 0, 0});
  gt.cameras[12] = Pose::FromRotationTranslation(q, {1.0 / 3.0, -2e-17, 1e300});
  gt.objects[{5, 12}] = Pose::FromRotationTranslation(q.conjugate(), {M_PI, M_E, -0.1});
  const std::string path = (dir_ / "out.txt").string();
  ASSERT_TRUE(WriteGroundTruth(gt, path, "simulated range 10:40\nframe k is KITTI frame 10 + k").ok());
  Expected<GroundTruth> back = ReadGroundTruth(path);
  ASSERT_TRUE(back.ok()) << back.error().ToString();
  ASSERT_EQ(back->cameras.size(), 2u);
  ASSERT_EQ(back->objects.size(), 1u);
  EXPECT_EQ(*back->Camera(12), gt.cameras[12]);
  EXPECT_EQ(*back->Object(5, 12), (gt.objects[{5, 12}]));
  std::ifstream in(path);
  std::string first, second, third;
  std::getline(in, first);
  std::getline(in, second);
  std::getline(in, third);
  EXPECT_EQ(first, "# simulated range 10:40");
  EXPECT_EQ(second, "# frame k is KITTI frame 10 + k");
  EXPECT_EQ(third, "CAMERA 0 0 0 0 0 0 0 1");
  EXPECT_FALSE(WriteGroundTruth(gt, (dir_ / "no" / "such" / "dir.txt").string()).ok());
}

// The reference scenes' gt.txt: as many records as the file has CAMERA / OBJECT lines, and the
// first OBJECT record of synthetic as written in the file.
TEST_F(GroundTruthTest, ReadsTheReferenceScenes) {
  int scenes = 0;
  for (const char* scene : {"synthetic", "kitti_0003"}) {
    const fs::path path = fs::path(testing::ReferenceDir()) / scene / "gt.txt";
    if (!fs::exists(path)) continue;
    ++scenes;
    size_t cameras = 0, objects = 0;
    std::ifstream in(path);
    for (std::string line; std::getline(in, line);) {
      cameras += line.rfind("CAMERA ", 0) == 0;
      objects += line.rfind("OBJECT ", 0) == 0;
    }
    Expected<GroundTruth> gt = ReadGroundTruth(path.string());
    ASSERT_TRUE(gt.ok()) << gt.error().ToString();
    EXPECT_EQ(gt->cameras.size(), cameras) << scene;
    EXPECT_EQ(gt->objects.size(), objects) << scene;
    if (std::string(scene) == "synthetic") {
      // OBJECT 0 1 0.29999999999999999 0.89999999999999991 10 0 -0.70710678118654746 0 0.7071…
      const Pose* l = gt->Object(1, 0);
      ASSERT_NE(l, nullptr);
      EXPECT_EQ(l->translation(), Eigen::Vector3d(0.29999999999999999, 0.89999999999999991, 10));
      EXPECT_NEAR(l->rotation().y(), -0.70710678118654746, 1e-16);
      EXPECT_NEAR(l->rotation().w(), 0.70710678118654757, 1e-16);
    }
  }
  ASSERT_GT(scenes, 0) << "no reference scenes under " << testing::ReferenceDir();
}

}  // namespace
}  // namespace dynslam
