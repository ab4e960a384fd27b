#include "dynslam/ground_truth.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string_view>
#include <vector>

#include "dynslam/file_io.h"
#include "src/number_text.h"
#include "src/text_fields.h"

namespace dynslam {

const Pose* GroundTruth::Camera(int64_t frame) const {
  auto it = cameras.find(frame);
  return it == cameras.end() ? nullptr : &it->second;
}

const Pose* GroundTruth::Object(int64_t object, int64_t frame) const {
  auto it = objects.find({object, frame});
  return it == objects.end() ? nullptr : &it->second;
}

Expected<GroundTruth> ReadGroundTruth(const std::string& path) {
  // A directory opens on Linux and then reads nothing: say so instead of returning no records.
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) {
    return Error{path, 0, "is a directory, not a ground-truth file"};
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) return Error{path, 0, "cannot open the ground-truth file"};
  return ReadGroundTruth(in, path);
}

Expected<GroundTruth> ReadGroundTruth(std::istream& in, const std::string& path) {
  GroundTruth gt;
  std::string line;
  std::vector<std::string_view> f;
  int64_t number = 0;
  while (std::getline(in, line)) {
    ++number;
    SplitFields(BeforeComment(line), &f);
    if (f.empty()) continue;
    auto fail = [&](const std::string& message) { return Error{path, number, message}; };
    const bool camera = f[0] == "CAMERA";
    if (!camera && f[0] != "OBJECT") {
      return fail("unknown record '" + std::string(f[0]) + "' (CAMERA or OBJECT, SPEC §2)");
    }
    const size_t expected = camera ? 9 : 10;
    if (f.size() != expected) {
      return fail(std::string(f[0]) + " has " + std::to_string(f.size() - 1) +
                  " fields, expected " + std::to_string(expected - 1) +
                  (camera ? " (k tx ty tz qx qy qz qw)" : " (k j tx ty tz qx qy qz qw)"));
    }
    int64_t frame = 0, object = 0;
    if (!ParseWholeNumber(f[1], &frame) || frame < 0) return fail("frame '" + std::string(f[1]) + "' is not a non-negative integer");
    if (!camera && (!ParseWholeNumber(f[2], &object) || object < 0)) {
      return fail("object '" + std::string(f[2]) + "' is not a non-negative integer");
    }
    const size_t first = camera ? 2 : 3;
    double v[7];
    for (int i = 0; i < 7; ++i) {
      if (!ParseWholeNumber(f[first + i], &v[i]) || !std::isfinite(v[i])) {
        return fail("field '" + std::string(f[first + i]) + "' is not a finite number");
      }
    }
    Eigen::Quaterniond q(v[6], v[3], v[4], v[5]);
    const double norm = q.coeffs().stableNorm();  // no overflow for huge components
    if (norm == 0) return fail("zero quaternion");
    if (std::abs(norm - 1) > 1e-12) q.coeffs() /= norm;
    const Pose pose = Pose::FromRotationTranslation(q, Eigen::Vector3d(v[0], v[1], v[2]));
    const bool inserted = camera ? gt.cameras.emplace(frame, pose).second
                                 : gt.objects.emplace(std::pair{object, frame}, pose).second;
    if (!inserted) {
      return fail(camera ? "second CAMERA record for frame " + std::to_string(frame)
                         : "second OBJECT record for object " + std::to_string(object) +
                               " at frame " + std::to_string(frame));
    }
  }
  if (in.bad()) return Error{path, number + 1, "read error"};
  return gt;
}

Status WriteGroundTruth(const GroundTruth& ground_truth, const std::string& path,
                        const std::string& header) {
  std::string text;
  std::istringstream header_lines(header);
  for (std::string line; std::getline(header_lines, line);) text += "# " + line + "\n";
  auto pose_fields = [&](const Pose& pose) {
    AppendPoseFields(&text, pose, ' ');
    text += "\n";
  };
  for (const auto& [frame, pose] : ground_truth.cameras) {
    text += "CAMERA " + std::to_string(frame);
    pose_fields(pose);
  }
  for (const auto& [key, pose] : ground_truth.objects) {
    text += "OBJECT " + std::to_string(key.second) + " " + std::to_string(key.first);
    pose_fields(pose);
  }
  return WriteFileAtomically(path, text);
}

}  // namespace dynslam
