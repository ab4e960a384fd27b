#include "export_flags.h"

#include <sstream>

namespace dynslam::cli {

ExportFlags::ExportFlags(ArgParser* parser) {
  parser->Group("output");
  parser->AddString("export", &formats_text_,
                    "also write the camera's and each object's trajectory, estimated and (with "
                    "--gt) true, for evo: tum, kitti or tum,kitti (DIR/camera_estimate.tum.txt, "
                    "DIR/object_J_ground_truth.kitti.txt, ...)",
                    "FORMATS");
  parser->AddDouble("export-rate", &rate_hz_,
                    "frames per second of the TUM timestamps (frame / rate)", 1e-6, 1e9);
}

std::optional<std::string> ExportFlags::Finish() {
  std::stringstream list(formats_text_);
  for (std::string item; std::getline(list, item, ',');) {
    TrajectoryFormat format;
    if (!ParseTrajectoryFormat(item, &format)) {
      return "--export: unknown format '" + item + "' (tum, kitti)";
    }
    formats_.push_back(format);
  }
  return std::nullopt;
}

void ExportFlags::Apply(SolveOutputs* outputs) const {
  outputs->export_formats = formats_;
  outputs->export_rate_hz = rate_hz_;
}

}  // namespace dynslam::cli
