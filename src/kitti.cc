#include "dynslam/kitti.h"

#include <cmath>
#include <fstream>
#include <string_view>
#include <vector>

#include <Eigen/Geometry>
#include <Eigen/SVD>

#include "src/text_fields.h"

namespace dynslam {
namespace {

constexpr double kPi = 3.14159265358979323846;

// A finite number, the whole field.
bool ParseDouble(std::string_view text, double* value) {
  return ParseWholeNumber(text, value) && std::isfinite(*value);
}

// Calls `record(fields, line_number)` for each non-blank line; stops at the first error.
template <typename F>
Status ForEachLine(std::istream& in, const std::string& path, F record) {
  std::string line;
  std::vector<std::string_view> fields;
  int64_t number = 0;
  while (std::getline(in, line)) {
    ++number;
    SplitFields(line, &fields);
    if (fields.empty()) continue;
    if (Status status = record(fields, number); !status.ok()) return status;
  }
  if (in.bad()) return Error{path, number, "read error"};
  return Status::Ok();
}

// `read(stream, path)` on the file at `path`.
template <typename T>
Expected<T> ReadFile(const std::string& path,
                     Expected<T> (*read)(std::istream&, const std::string&)) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return Error{path, 0, "cannot open the file"};
  return read(in, path);
}

Eigen::Matrix3d ProjectToRotation(const Eigen::Matrix3d& m) {
  Eigen::JacobiSVD<Eigen::Matrix3d> svd(m, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d d = Eigen::Matrix3d::Identity();
  d(2, 2) = (svd.matrixU() * svd.matrixV().transpose()).determinant() < 0 ? -1.0 : 1.0;
  return svd.matrixU() * d * svd.matrixV().transpose();
}

Eigen::Matrix4d Homogeneous(const Eigen::Matrix<double, 3, 4>& m) {
  Eigen::Matrix4d h = Eigen::Matrix4d::Identity();
  h.topRows<3>() = m;
  return h;
}

Pose FromMatrix(const Eigen::Matrix3d& R, const Eigen::Vector3d& t) {
  Eigen::Quaterniond q(R);
  q.normalize();
  if (q.w() < 0) q.coeffs() = -q.coeffs();  // one sign, so that outputs are stable
  return Pose::FromRotationTranslation(q, t);
}

Pose Multiply(const Pose& a, const Pose& b) {
  const Eigen::Quaterniond q = (a.rotation() * b.rotation()).normalized();
  return Pose::FromRotationTranslation(q, a.rotation() * b.translation() + a.translation());
}

Pose Invert(const Pose& a) {
  const Eigen::Quaterniond qi = a.rotation().conjugate();
  return Pose::FromRotationTranslation(qi, -(qi * a.translation()));
}

}  // namespace

Expected<std::vector<OxtsRecord>> ReadOxts(const std::string& path) {
  return ReadFile<std::vector<OxtsRecord>>(path, ReadOxts);
}

Expected<std::vector<OxtsRecord>> ReadOxts(std::istream& in, const std::string& path) {
  std::vector<OxtsRecord> records;
  const Status status = ForEachLine(in, path, [&](const std::vector<std::string_view>& f,
                                              int64_t line) -> Status {
    if (f.size() != 30) {
      return Error{path, line, "an oxts record has 30 fields (devkit dataformat.txt), found " +
                                   std::to_string(f.size())};
    }
    double v[30];
    for (int i = 0; i < 30; ++i) {
      if (!ParseDouble(f[i], &v[i])) {
        return Error{path, line, "field " + std::to_string(i + 1) + " '" + std::string(f[i]) +
                                     "' is not a finite number"};
      }
    }
    if (std::abs(v[0]) >= 90.0 || std::abs(v[1]) > 180.0) {
      return Error{path, line, "latitude/longitude out of range"};
    }
    OxtsRecord r;
    r.lat = v[0];
    r.lon = v[1];
    r.alt = v[2];
    r.roll = v[3];
    r.pitch = v[4];
    r.yaw = v[5];
    r.line = line;
    records.push_back(r);
    return Status::Ok();
  });
  if (!status.ok()) return status.error();
  if (records.empty()) return Error{path, 0, "no oxts records"};
  return records;
}

Expected<std::vector<LabelRecord>> ReadLabels(const std::string& path) {
  return ReadFile<std::vector<LabelRecord>>(path, ReadLabels);
}

Expected<std::vector<LabelRecord>> ReadLabels(std::istream& in, const std::string& path) {
  std::vector<LabelRecord> labels;
  const Status status = ForEachLine(in, path, [&](const std::vector<std::string_view>& f,
                                              int64_t line) -> Status {
    if (f.size() != 17 && f.size() != 18) {
      return Error{path, line, "a label_02 record has 17 fields (18 with a score), found " +
                                   std::to_string(f.size())};
    }
    LabelRecord r;
    r.line = line;
    int64_t truncated = 0, occluded = 0;
    if (!ParseWholeNumber(f[0], &r.frame) || r.frame < 0) {
      return Error{path, line, "frame '" + std::string(f[0]) + "' is not a non-negative integer"};
    }
    if (!ParseWholeNumber(f[1], &r.track_id) || r.track_id < -1) {
      return Error{path, line, "track id '" + std::string(f[1]) + "' is not an integer ≥ −1"};
    }
    r.type = std::string(f[2]);
    // truncated is an integer 0-2 in tracking labels (a float 0-1 in the object benchmark),
    // occluded 0-3; DontCare rows have −1 for both (devkit readme).
    double truncated_value = 0;
    if (!ParseDouble(f[3], &truncated_value) || !(truncated_value >= -1 && truncated_value <= 2)) {
      return Error{path, line, "truncated '" + std::string(f[3]) + "' is not a number from −1 to 2"};
    }
    truncated = static_cast<int64_t>(truncated_value);
    if (!ParseWholeNumber(f[4], &occluded) || occluded < -1 || occluded > 3) {
      return Error{path, line, "occluded '" + std::string(f[4]) + "' is not an integer from −1 to 3"};
    }
    r.truncated = static_cast<int>(truncated);
    r.occluded = static_cast<int>(occluded);
    double v[12];
    for (int i = 0; i < 12; ++i) {
      if (!ParseDouble(f[5 + i], &v[i])) {
        return Error{path, line, "field " + std::to_string(6 + i) + " '" +
                                     std::string(f[5 + i]) + "' is not a finite number"};
      }
    }
    r.alpha = v[0];
    r.bbox = {v[1], v[2], v[3], v[4]};
    r.height = v[5];
    r.width = v[6];
    r.length = v[7];
    r.location = Eigen::Vector3d(v[8], v[9], v[10]);
    r.rotation_y = v[11];
    if (r.type != "DontCare" && r.track_id >= 0 &&
        !(r.height > 0 && r.width > 0 && r.length > 0)) {
      return Error{path, line, "object " + std::to_string(r.track_id) +
                                   " has a non-positive box size"};
    }
    labels.push_back(std::move(r));
    return Status::Ok();
  });
  if (!status.ok()) return status.error();
  return labels;
}

Expected<KittiCalib> ReadCalib(const std::string& path) {
  return ReadFile<KittiCalib>(path, ReadCalib);
}

Expected<KittiCalib> ReadCalib(std::istream& in, const std::string& path) {
  KittiCalib calib;
  bool seen_p[4] = {false, false, false, false};
  bool seen_rect = false, seen_velo = false, seen_imu = false;
  const Status status = ForEachLine(in, path, [&](const std::vector<std::string_view>& f,
                                              int64_t line) -> Status {
    std::string key(f[0]);
    if (!key.empty() && key.back() == ':') key.pop_back();
    size_t expected = 12;
    int which = -1;  // 0-3: P, 4: R_rect, 5: Tr_velo_cam, 6: Tr_imu_velo
    if (key.size() == 2 && key[0] == 'P' && key[1] >= '0' && key[1] <= '3') {
      which = key[1] - '0';
    } else if (key == "R_rect" || key == "R0_rect") {
      which = 4;
      expected = 9;
    } else if (key == "Tr_velo_cam" || key == "Tr_velo_to_cam") {
      which = 5;
    } else if (key == "Tr_imu_velo" || key == "Tr_imu_to_velo") {
      which = 6;
    } else {
      return Status::Ok();  // other keys (Tr_cam_to_road, …) are not needed
    }
    if (f.size() - 1 != expected) {
      return Error{path, line, key + " has " + std::to_string(expected) + " numbers, found " +
                                   std::to_string(f.size() - 1)};
    }
    double v[12];
    for (size_t i = 0; i < expected; ++i) {
      if (!ParseDouble(f[1 + i], &v[i])) {
        return Error{path, line, key + ": '" + std::string(f[1 + i]) +
                                     "' is not a finite number"};
      }
    }
    Eigen::Matrix<double, 3, 4> m;
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 4; ++c) m(r, c) = expected == 12 ? v[4 * r + c] : 0.0;
    }
    if (which < 4) {
      calib.P[which] = m;
      seen_p[which] = true;
    } else if (which == 4) {
      for (int r = 0; r < 3; ++r) {
        for (int c = 0; c < 3; ++c) calib.R_rect(r, c) = v[3 * r + c];
      }
      seen_rect = true;
    } else if (which == 5) {
      calib.Tr_velo_cam = m;
      seen_velo = true;
    } else {
      calib.Tr_imu_velo = m;
      seen_imu = true;
    }
    return Status::Ok();
  });
  if (!status.ok()) return status.error();
  for (int i = 0; i < 4; ++i) {
    if (!seen_p[i]) return Error{path, 0, "P" + std::to_string(i) + " is missing"};
  }
  if (!seen_rect) return Error{path, 0, "R_rect is missing"};
  if (!seen_velo) return Error{path, 0, "Tr_velo_cam is missing"};
  if (!seen_imu) return Error{path, 0, "Tr_imu_velo is missing"};
  if (!(calib.P[2](0, 0) > 0) || !(calib.P[2](1, 1) > 0)) {
    return Error{path, 0, "P2 has a non-positive focal length"};
  }
  const auto near_rotation = [](const Eigen::Matrix3d& m) {
    return (m * m.transpose() - Eigen::Matrix3d::Identity()).norm() < 1e-3 &&
           m.determinant() > 0;
  };
  if (!near_rotation(calib.R_rect) || !near_rotation(calib.Tr_velo_cam.leftCols<3>()) ||
      !near_rotation(calib.Tr_imu_velo.leftCols<3>())) {
    return Error{path, 0, "R_rect, Tr_velo_cam or Tr_imu_velo is not a rotation (to 1e-3)"};
  }
  return calib;
}

Expected<KittiSequence> ReadKittiSequence(const std::string& dir, const std::string& sequence) {
  KittiSequence seq;
  seq.name = sequence;
  auto oxts = ReadOxts(dir + "/oxts/" + sequence + ".txt");
  if (!oxts.ok()) return oxts.error();
  auto labels = ReadLabels(dir + "/label_02/" + sequence + ".txt");
  if (!labels.ok()) return labels.error();
  auto calib = ReadCalib(dir + "/calib/" + sequence + ".txt");
  if (!calib.ok()) return calib.error();
  seq.oxts = std::move(*oxts);
  seq.labels = std::move(*labels);
  seq.calib = *calib;
  const int64_t frames = static_cast<int64_t>(seq.oxts.size());
  for (const LabelRecord& label : seq.labels) {
    if (label.frame >= frames) {
      return Error{dir + "/label_02/" + sequence + ".txt", label.line,
                   "frame " + std::to_string(label.frame) + " is beyond the " +
                       std::to_string(frames) + " frames of the oxts file"};
    }
  }
  return seq;
}

double MercatorScale(double lat0_deg) { return std::cos(lat0_deg * kPi / 180.0); }

Pose OxtsToImuPose(const OxtsRecord& oxts, double scale) {
  const double tx = scale * kEarthRadius * oxts.lon * kPi / 180.0;
  const double ty = scale * kEarthRadius * std::log(std::tan((90.0 + oxts.lat) * kPi / 360.0));
  const Eigen::Matrix3d R =
      (Eigen::AngleAxisd(oxts.yaw, Eigen::Vector3d::UnitZ()) *
       Eigen::AngleAxisd(oxts.pitch, Eigen::Vector3d::UnitY()) *
       Eigen::AngleAxisd(oxts.roll, Eigen::Vector3d::UnitX()))
          .toRotationMatrix();
  return FromMatrix(R, Eigen::Vector3d(tx, ty, oxts.alt));
}

Pose ImuToCamera(const KittiCalib& calib) {
  Eigen::Matrix4d rect = Eigen::Matrix4d::Identity();
  rect.topLeftCorner<3, 3>() = calib.R_rect;
  const Eigen::Matrix4d m = rect * Homogeneous(calib.Tr_velo_cam) * Homogeneous(calib.Tr_imu_velo);
  return FromMatrix(ProjectToRotation(m.topLeftCorner<3, 3>()), m.topRightCorner<3, 1>());
}

std::vector<Pose> CameraPoses(const KittiSequence& sequence, int64_t first, int64_t last) {
  std::vector<Pose> poses;
  if (sequence.oxts.empty() || first < 0 || last <= first ||
      last > static_cast<int64_t>(sequence.oxts.size())) {
    return poses;
  }
  const double scale = MercatorScale(sequence.oxts.front().lat);
  const Pose camera_to_imu = Invert(ImuToCamera(sequence.calib));
  // Subtract the first IMU position before composing: Mercator coordinates are ~10⁶ m, and
  // differences of nearby poses keep their precision this way.
  const Pose imu_first = OxtsToImuPose(sequence.oxts[first], scale);
  Pose origin = imu_first;
  origin.translation().setZero();
  const Pose world_first = Invert(Multiply(origin, camera_to_imu));
  for (int64_t k = first; k < last; ++k) {
    Pose imu = OxtsToImuPose(sequence.oxts[k], scale);
    imu.translation() -= imu_first.translation();
    poses.push_back(Multiply(world_first, Multiply(imu, camera_to_imu)));
  }
  poses.front() = Pose::Identity();  // exactly, not to rounding
  return poses;
}

Pose ObjectInCamera(const LabelRecord& label) {
  const Eigen::Matrix3d R =
      Eigen::AngleAxisd(label.rotation_y, Eigen::Vector3d::UnitY()).toRotationMatrix();
  const Eigen::Vector3d t = label.location - Eigen::Vector3d(0, label.height / 2.0, 0);
  return FromMatrix(R, t);
}

}  // namespace dynslam
