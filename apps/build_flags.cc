#include "build_flags.h"

namespace dynslam::cli {

BuildFlags::BuildFlags(ArgParser* parser)
    : min_object_frames_(defaults_.min_object_frames), kinematic_sigma_(defaults_.kinematic_sigma) {
  parser->AddInt("min-object-frames", &min_object_frames_,
                 "shortest object segment kept, in frames (SPEC §3.1)", 2, 1000000);
  parser->AddChoice("object-init", &object_init_, {"align", "centroid"},
                    "initial object poses: ground truth at a segment's start then rigid alignment, "
                    "or point centroids with identity rotation (SPEC §3.3)");
  parser->AddChoice("motion-init", &motion_init_, {"frontend", "identity"},
                    "initial motions: the front end's values, or identity");
  parser->AddDouble("kinematic-sigma", &kinematic_sigma_,
                    "sigma of the object kinematic edge, all six components (oc_b, oc_c)", 1e-9, 1e9);
}

std::optional<std::string> BuildFlags::Finish(BuildOptions* options) const {
  *options = defaults_;
  options->min_object_frames = static_cast<int>(min_object_frames_);
  options->object_init = object_init_ == "centroid" ? ObjectInit::kCentroid : ObjectInit::kAlign;
  options->motion_init = motion_init_ == "identity" ? MotionInit::kIdentity : MotionInit::kFrontEnd;
  options->kinematic_sigma = kinematic_sigma_;
  return std::nullopt;
}

}  // namespace dynslam::cli
