// Ground-truth files (SPEC §2): camera poses X^W_k and object poses L^W_k by frame.
//
//     CAMERA k tx ty tz qx qy qz qw
//     OBJECT k j tx ty tz qx qy qz qw
//
// Graph layer: no Ceres. Errors name the file, the line and the problem.
#ifndef DYNSLAM_GROUND_TRUTH_H_
#define DYNSLAM_GROUND_TRUTH_H_

#include <cstdint>
#include <istream>
#include <map>
#include <string>
#include <utility>

#include "dynslam/pose.h"
#include "dynslam/status.h"

namespace dynslam {

struct GroundTruth {
  std::map<int64_t, Pose> cameras;                       // frame k → X^W_k
  std::map<std::pair<int64_t, int64_t>, Pose> objects;   // (object j, frame k) → L^W_k

  const Pose* Camera(int64_t frame) const;
  const Pose* Object(int64_t object, int64_t frame) const;
};

Expected<GroundTruth> ReadGroundTruth(const std::string& path);
// The same from a stream; `name` is the file name errors give.
Expected<GroundTruth> ReadGroundTruth(std::istream& in, const std::string& name);
// `header` lines are written as `# …` comments first (SPEC §2 frame mapping, provenance).
Status WriteGroundTruth(const GroundTruth& ground_truth, const std::string& path,
                        const std::string& header = "");

}  // namespace dynslam

#endif  // DYNSLAM_GROUND_TRUTH_H_
