// libFuzzer target: the KITTI Tracking readers (oxts, label_02, calib). The first byte chooses
// the reader ('o', 'l', anything else: calib), the rest is the file. Reading must never crash;
// what reads must turn into finite poses (the simulator's next step). Build and run: scripts/fuzz.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <sstream>
#include <string>

#include "dynslam/kitti.h"

namespace {

void AbortUnlessFinite(const dynslam::Pose& pose) {
  for (const double v : pose.data) {
    if (!std::isfinite(v)) std::abort();
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size == 0) return 0;
  std::istringstream in(std::string(reinterpret_cast<const char*>(data) + 1, size - 1));
  switch (data[0]) {
    case 'o':
      if (const auto oxts = dynslam::ReadOxts(in, "fuzz"); oxts.ok()) {
        const double scale = dynslam::MercatorScale(oxts->front().lat);
        for (const dynslam::OxtsRecord& record : *oxts) {
          AbortUnlessFinite(dynslam::OxtsToImuPose(record, scale));
        }
      }
      break;
    case 'l':
      if (const auto labels = dynslam::ReadLabels(in, "fuzz"); labels.ok()) {
        for (const dynslam::LabelRecord& label : *labels) {
          AbortUnlessFinite(dynslam::ObjectInCamera(label));
        }
      }
      break;
    default:
      if (const auto calib = dynslam::ReadCalib(in, "fuzz"); calib.ok()) {
        AbortUnlessFinite(dynslam::ImuToCamera(*calib));
      }
      break;
  }
  return 0;
}
