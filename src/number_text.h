// Numbers and poses in the text files dynslam writes (graphs, ground truth, CSV outputs,
// trajectories): the shortest decimal that reads back to the same double (std::to_chars), so
// read → write → read is bit-exact (SPEC §1) and the text does not depend on the C locale.
// Writing the parking-garage graph takes 9-14 ms this way, 60 ms with printf's %.17g
// (build/release/benchmarks/graph_io_benchmark).
#ifndef DYNSLAM_SRC_NUMBER_TEXT_H_
#define DYNSLAM_SRC_NUMBER_TEXT_H_

#include <charconv>
#include <string>

#include "dynslam/pose.h"

namespace dynslam {

// Appends `value` to `out`; infinities as inf / -inf, NaN as nan.
inline void AppendNumber(std::string* out, double value) {
  char buffer[32];  // the longest shortest form, -2.2250738585072014e-308, has 24 characters
  const std::to_chars_result result = std::to_chars(buffer, buffer + sizeof buffer, value);
  out->append(buffer, result.ptr);
}

inline std::string NumberText(double value) {
  std::string text;
  AppendNumber(&text, value);
  return text;
}

// Appends a pose's seven numbers in the order the files write them, tx ty tz qx qy qz qw (the
// block stores qx qy qz qw tx ty tz, pose.h), each after `separator`.
inline void AppendPoseFields(std::string* out, const Pose& pose, char separator) {
  for (const int i : {4, 5, 6, 0, 1, 2, 3}) {
    *out += separator;
    AppendNumber(out, pose.data[i]);
  }
}

}  // namespace dynslam

#endif  // DYNSLAM_SRC_NUMBER_TEXT_H_
