#include "build_flags.h"

namespace dynslam::cli {

BuildFlags::BuildFlags(ArgParser* parser)
    : min_object_frames_(defaults_.min_object_frames), kinematic_sigma_(defaults_.kinematic_sigma) {
  parser->AddInt("min-object-frames", &min_object_frames_,
                 "shortest object segment kept, in frames (SPEC §3.1)", 2, 1000000);
  parser->AddChoice("object-init", &object_init_, {"motion", "align", "truth", "centroid"},
                    "initial object poses after a segment's first (ground truth where given): "
                    "chained from the initial motions, rigid alignment of the points (the "
                    "reference graphs' rule), the ground truth at every frame, or every pose at "
                    "its points' centroid with identity rotation (SPEC §3.3)");
  parser->AddChoice("motion-init", &motion_init_, {"frontend", "identity"},
                    "initial motions: the front end's values, or identity");
  parser->AddDouble("kinematic-sigma", &kinematic_sigma_,
                    "sigma of the object kinematic edge, all six components (oc_b, oc_c)", 1e-9, 1e9);
}

std::optional<std::string> BuildFlags::Finish(BuildOptions* options) const {
  *options = defaults_;
  options->min_object_frames = static_cast<int>(min_object_frames_);
  ParseObjectInit(object_init_, &options->object_init);  // AddChoice admits only valid names
  options->motion_init = motion_init_ == "identity" ? MotionInit::kIdentity : MotionInit::kFrontEnd;
  options->kinematic_sigma = kinematic_sigma_;
  return std::nullopt;
}

}  // namespace dynslam::cli
