// KITTI Tracking readers and conversions (include/dynslam/kitti.h) against numbers worked out by
// hand from the devkit's documentation (devkit_tracking: readme.txt, dataformat.txt of the oxts,
// convertOxtsToPose.m, latlonToMercator.m, computeBox3D.m) and against the embedded data.
#include "dynslam/kitti.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

namespace dynslam {
namespace {

constexpr double kPi = 3.14159265358979323846;
const std::string kData = std::string(DYNSLAM_SOURCE_DIR) + "/data/kitti_tracking";

Eigen::Matrix3d R(const Pose& pose) { return pose.rotation().toRotationMatrix(); }

std::string WriteTemp(const std::string& name, const std::string& text) {
  const std::string path = ::testing::TempDir() + "/" + name;
  std::ofstream(path, std::ios::binary) << text;
  return path;
}

std::string OxtsLine(double lat, double lon, double alt, double roll, double pitch, double yaw) {
  char buffer[256];
  std::snprintf(buffer, sizeof(buffer), "%.17g %.17g %.17g %.17g %.17g %.17g", lat, lon, alt, roll,
                pitch, yaw);
  std::string line = buffer;
  for (int i = 6; i < 30; ++i) line += " 0";
  return line + "\n";
}

// latlonToMercator: scale = cos(lat0·π/180); mx = scale·er·lon·π/180;
// my = scale·er·ln(tan((90+lat)·π/360)), er = 6378137.
// lat0 = lat = 60°, lon = 1°: scale = cos 60° = 1/2;
//   mx = ½·6378137·π/180 = 3189068.5 · 0.017453292519943295 = 55659.745396637;
//   my = 3189068.5 · ln(tan 75°) = 3189068.5 · ln(2+√3) = 3189068.5 · 1.3169578969248166
//      = 4199868.944909.
TEST(Kitti, OxtsToImuPoseMercatorByHand) {
  EXPECT_NEAR(MercatorScale(60.0), 0.5, 1e-15);
  OxtsRecord r;
  r.lat = 60.0;
  r.lon = 1.0;
  r.alt = 114.5;
  const Pose pose = OxtsToImuPose(r, MercatorScale(60.0));
  EXPECT_NEAR(pose.translation().x(), 55659.745396637, 1e-6);
  EXPECT_NEAR(pose.translation().y(), 4199868.944909, 1e-5);
  EXPECT_EQ(pose.translation().z(), 114.5);
  EXPECT_NEAR(R(pose).norm(), std::sqrt(3.0), 1e-15);  // identity rotation
  EXPECT_NEAR((R(pose) - Eigen::Matrix3d::Identity()).norm(), 0.0, 1e-15);
  // lat = 0, lon = 0 with scale 1: the origin (tan 45° = 1).
  r.lat = 0;
  r.lon = 0;
  EXPECT_NEAR(OxtsToImuPose(r, 1.0).translation().head<2>().norm(), 0.0, 1e-9);
}

// convertOxtsToPose: R = Rz(yaw)·Ry(pitch)·Rx(roll). With roll = yaw = π/2, pitch = 0:
//   R·x = Rz(Rx·x) = Rz·x = y;  R·y = Rz(Rx·y) = Rz·z = z;  R·z = Rz(Rx·z) = Rz·(−y) = x.
// (The other order, Rx·Rz, would send x to Rx·y = z: the test tells the orders apart.)
TEST(Kitti, OxtsRotationOrderByHand) {
  OxtsRecord r;
  r.roll = kPi / 2;
  r.yaw = kPi / 2;
  const Eigen::Matrix3d rot = R(OxtsToImuPose(r, 1.0));
  EXPECT_NEAR((rot * Eigen::Vector3d::UnitX() - Eigen::Vector3d::UnitY()).norm(), 0, 1e-12);
  EXPECT_NEAR((rot * Eigen::Vector3d::UnitY() - Eigen::Vector3d::UnitZ()).norm(), 0, 1e-12);
  EXPECT_NEAR((rot * Eigen::Vector3d::UnitZ() - Eigen::Vector3d::UnitX()).norm(), 0, 1e-12);
  // pitch alone, positive = front down (dataformat.txt): the IMU's forward axis x gets z < 0.
  OxtsRecord p;
  p.pitch = 0.1;
  EXPECT_NEAR((R(OxtsToImuPose(p, 1.0)) * Eigen::Vector3d::UnitX()).z(), -std::sin(0.1), 1e-15);
}

// The devkit's sensor setup (readme): IMU x forward, y left, z up; camera x right, y down,
// z forward. So p_cam ≈ (−y_imu, −z_imu, x_imu): the rotation of ImuToCamera is close to
// [[0,−1,0],[0,0,−1],[1,0,0]] (calibration tilts are below 0.02 rad).
TEST(Kitti, ImuToCameraAxes) {
  Expected<KittiCalib> calib = ReadCalib(kData + "/calib/0003.txt");
  ASSERT_TRUE(calib.ok()) << calib.error().ToString();
  const Pose T = ImuToCamera(*calib);
  Eigen::Matrix3d expected;
  expected << 0, -1, 0, 0, 0, -1, 1, 0, 0;
  EXPECT_LT((R(T) - expected).cwiseAbs().maxCoeff(), 0.02);
  EXPECT_NEAR((R(T) * R(T).transpose() - Eigen::Matrix3d::Identity()).norm(), 0, 1e-12);
  // The camera is ~0.27 m ahead of the velodyne and the velodyne ~0.81 m ahead of the IMU
  // (Tr_velo_cam, Tr_imu_velo translations): the IMU origin seen from the camera is ~1.08 m
  // behind it, i.e. camera z ≈ −1.08.
  EXPECT_NEAR(T.translation().z(), -1.08, 0.03);
}

// Sequence 0003, frames 0 → 1 (oxts lines 1 and 2):
//   Δlat = 49.013152078605 − 49.013141872681 = 1.0205924e−5°,
//   Δlon = 8.4378095507685 − 8.4378138518088 = −4.3010403e−6°.
//   North: er·Δlat·π/180 (Mercator scale·1/cos(lat) ≈ 1 at lat0) = 1.136122 m;
//   east: cos(49.0131°)·er·Δlon·π/180 = 0.655832 · (−0.478793) = −0.314006 m; up 0.00074 m.
//   IMU displacement = √(1.136122² + 0.314006² + 0.00074²) = 1.178718 m.
// The camera is ~1.1 m from the IMU and the heading changes by 1.6 mrad, so the camera moves
// within a few millimetres of that, forward (camera z). Rotation: Δroll = −0.001108,
// Δpitch = 0.000862, Δyaw = 0.001567 rad → angle ≈ √(Σ Δ²) = 0.0021039 rad (to ~2e−5: the
// Euler rates mix at pitch ≈ 0.01 rad).
TEST(Kitti, CameraPosesOfSequence0003ByHand) {
  Expected<KittiSequence> seq = ReadKittiSequence(kData, "0003");
  ASSERT_TRUE(seq.ok()) << seq.error().ToString();
  const std::vector<Pose> poses = CameraPoses(*seq, 0, 3);
  ASSERT_EQ(poses.size(), 3u);
  EXPECT_EQ(poses[0], Pose::Identity());
  const Eigen::Vector3d t = poses[1].translation();
  EXPECT_NEAR(t.norm(), 1.178718, 0.004);
  EXPECT_GT(t.z(), 0.999 * t.norm());
  const double angle = Eigen::AngleAxisd(poses[1].rotation()).angle();
  EXPECT_NEAR(angle, 0.0021039, 3e-5);
  // Relative to another first frame: X'_k = X_1⁻¹·X_k (the world moves with the range).
  const std::vector<Pose> from1 = CameraPoses(*seq, 1, 3);
  const Eigen::Isometry3d expected = poses[1].ToIsometry().inverse() * poses[2].ToIsometry();
  EXPECT_NEAR((from1[1].ToIsometry().matrix() - expected.matrix()).norm(), 0, 1e-9);
}

// label_02/0003.txt line 5:
//   0 0 Car 1 0 -2.162543 894.77 190.65 1241 374  h=1.381664 w=1.510562 l=4.101504
//   x=3.407977 y=1.536793 z=4.758829 ry=-1.570796
// Centre = (x, y − h/2, z) = (3.407977, 0.845961, 4.758829). computeBox3D: corner
// (l/2, 0, w/2) of the box (y = 0 at the bottom) is R_y(ry)·(l/2, 0, w/2) + (x, y, z) with
// R_y(−π/2) = [[0,0,−1],[0,1,0],[1,0,0]]: (−w/2, 0, l/2) + (x, y, z)
//   = (3.407977 − 0.755281, 1.536793, 4.758829 + 2.050752) = (2.652696, 1.536793, 6.809581).
// In the object frame (origin at the centre, y down) that corner is (l/2, h/2, w/2).
TEST(Kitti, LabelToObjectPoseByHand) {
  Expected<std::vector<LabelRecord>> labels = ReadLabels(kData + "/label_02/0003.txt");
  ASSERT_TRUE(labels.ok()) << labels.error().ToString();
  const LabelRecord& label = (*labels)[4];
  ASSERT_EQ(label.line, 5);
  EXPECT_EQ(label.type, "Car");
  EXPECT_EQ(label.track_id, 0);
  const Pose O = ObjectInCamera(label);
  EXPECT_NEAR((O.translation() - Eigen::Vector3d(3.407977, 0.845961, 4.758829)).norm(), 0, 1e-9);
  const Eigen::Vector3d corner =
      O.ToIsometry() * Eigen::Vector3d(4.101504 / 2, 1.381664 / 2, 1.510562 / 2);
  EXPECT_NEAR((corner - Eigen::Vector3d(2.652696, 1.536793, 6.809581)).norm(), 0, 2e-6);
  // The car's length axis points along camera z (it drives ahead of the camera).
  EXPECT_NEAR((R(O) * Eigen::Vector3d::UnitX() - Eigen::Vector3d::UnitZ()).norm(), 0, 1e-6);
}

TEST(Kitti, EmbeddedSequencesHaveOfficialLengths) {
  // Official sequence lengths (KITTI tracking devkit / the data's SOURCES.md).
  const std::vector<std::pair<std::string, size_t>> lengths = {
      {"0000", 154}, {"0001", 447}, {"0002", 233}, {"0003", 144}, {"0004", 314},
      {"0005", 297}, {"0006", 270}, {"0018", 339}, {"0020", 837}};
  for (const auto& [name, length] : lengths) {
    Expected<KittiSequence> seq = ReadKittiSequence(kData, name);
    ASSERT_TRUE(seq.ok()) << seq.error().ToString();
    EXPECT_EQ(seq->oxts.size(), length) << name;
    EXPECT_FALSE(seq->labels.empty()) << name;
    EXPECT_EQ(CameraPoses(*seq, 0, static_cast<int64_t>(length)).size(), length) << name;
  }
}

TEST(Kitti, BadFilesAreErrorsWithFileAndLine) {
  const std::string good = OxtsLine(49, 8.4, 100, 0, 0, 0);
  std::string path = WriteTemp("short.oxts", good + "49 8.4 100 0 0 0\n");
  Expected<std::vector<OxtsRecord>> oxts = ReadOxts(path);
  ASSERT_FALSE(oxts.ok());
  EXPECT_EQ(oxts.error().line, 2);
  EXPECT_NE(oxts.error().ToString().find(path + ":2:"), std::string::npos);

  path = WriteTemp("nan.oxts", good + good + OxtsLine(49, 8.4, 100, 0, 0, 0).replace(0, 2, "nan"));
  oxts = ReadOxts(path);
  ASSERT_FALSE(oxts.ok());
  EXPECT_EQ(oxts.error().line, 3);
  EXPECT_FALSE(ReadOxts(WriteTemp("empty.oxts", "\n")).ok());
  EXPECT_FALSE(ReadOxts(::testing::TempDir() + "/does_not_exist.txt").ok());

  path = WriteTemp("bad.label",
                   "0 0 Car 0 0 0 1 2 3 4 1.5 1.6 4 1 1.6 10 0\n"
                   "1 0 Car 0 0 0 1 2 3 4 1.5 1.6 x 1 1.6 10 0\n");
  Expected<std::vector<LabelRecord>> labels = ReadLabels(path);
  ASSERT_FALSE(labels.ok());
  EXPECT_EQ(labels.error().line, 2);
  labels = ReadLabels(WriteTemp("few.label", "0 0 Car 0 0 0 1 2 3 4\n"));
  ASSERT_FALSE(labels.ok());
  EXPECT_EQ(labels.error().line, 1);
  labels = ReadLabels(WriteTemp("size.label", "0 0 Car 0 0 0 1 2 3 4 0 1.6 4 1 1.6 10 0\n"));
  ASSERT_FALSE(labels.ok());
  // Found by kitti_reader_fuzzer: a truncated value beyond int64 was cast (undefined behaviour).
  for (const char* field : {"truncated 11111111111111111111111 0", "occluded 0 99999999999",
                            "truncated 3 0", "occluded 0 -2"}) {
    const std::string name = std::string(field).substr(0, std::string(field).find(' '));
    const std::string values = std::string(field).substr(name.size() + 1);
    labels = ReadLabels(WriteTemp("range.label", "0 0 Car " + values + " 0 1 2 3 4 1.5 1.6 4 1 1.6 10 0\n"));
    ASSERT_FALSE(labels.ok()) << field;
    EXPECT_EQ(labels.error().line, 1);
    EXPECT_NE(labels.error().message.find(name), std::string::npos) << labels.error().message;
  }

  Expected<KittiCalib> calib = ReadCalib(WriteTemp("missing.calib", "P0: 1 0 0 0 0 1 0 0 0 0 1 0\n"));
  ASSERT_FALSE(calib.ok());
  EXPECT_NE(calib.error().message.find("missing"), std::string::npos);
  calib = ReadCalib(WriteTemp("short.calib", "P0: 1 0 0\n"));
  ASSERT_FALSE(calib.ok());
  EXPECT_EQ(calib.error().line, 1);

  // A label beyond the oxts frames.
  const std::string dir = ::testing::TempDir() + "/kitti_bad";
  for (const char* sub : {"/oxts", "/label_02", "/calib"}) {
    std::filesystem::create_directories(dir + sub);
  }
  std::ofstream(dir + "/oxts/0000.txt") << good << good;
  std::ofstream(dir + "/label_02/0000.txt") << "5 0 Car 0 0 0 1 2 3 4 1.5 1.6 4 1 1.6 10 0\n";
  std::ifstream calib_in(kData + "/calib/0003.txt");
  std::ofstream(dir + "/calib/0000.txt") << calib_in.rdbuf();
  Expected<KittiSequence> seq = ReadKittiSequence(dir, "0000");
  ASSERT_FALSE(seq.ok());
  EXPECT_EQ(seq.error().line, 1);
  EXPECT_NE(seq.error().message.find("beyond"), std::string::npos);
}

TEST(Kitti, CalibAcceptsObjectBenchmarkKeys) {
  std::ifstream in(kData + "/calib/0003.txt");
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  for (const auto& [from, to] : std::vector<std::pair<std::string, std::string>>{
           {"R_rect", "R0_rect:"}, {"Tr_velo_cam", "Tr_velo_to_cam:"},
           {"Tr_imu_velo", "Tr_imu_to_velo:"}}) {
    text.replace(text.find(from), from.size(), to);
  }
  Expected<KittiCalib> renamed = ReadCalib(WriteTemp("object_style.calib", text));
  Expected<KittiCalib> original = ReadCalib(kData + "/calib/0003.txt");
  ASSERT_TRUE(renamed.ok()) << renamed.error().ToString();
  ASSERT_TRUE(original.ok());
  EXPECT_EQ(renamed->Tr_imu_velo, original->Tr_imu_velo);
  EXPECT_EQ(renamed->R_rect, original->R_rect);
  EXPECT_EQ(renamed->P[2], original->P[2]);
}

}  // namespace
}  // namespace dynslam
