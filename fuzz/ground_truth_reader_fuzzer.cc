// libFuzzer target: arbitrary bytes as a ground-truth file (SPEC §2). Reading must never crash,
// and a file that reads holds only finite poses. Build and run: scripts/fuzz.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <sstream>
#include <string>

#include "dynslam/ground_truth.h"

namespace {

bool Finite(const dynslam::Pose& pose) {
  for (const double v : pose.data) {
    if (!std::isfinite(v)) return false;
  }
  return true;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  std::istringstream in(std::string(reinterpret_cast<const char*>(data), size));
  const dynslam::Expected<dynslam::GroundTruth> gt = dynslam::ReadGroundTruth(in, "fuzz");
  if (!gt.ok()) return 0;
  for (const auto& [frame, pose] : gt->cameras) {
    if (!Finite(pose)) std::abort();
  }
  for (const auto& [key, pose] : gt->objects) {
    if (!Finite(pose)) std::abort();
  }
  return 0;
}
