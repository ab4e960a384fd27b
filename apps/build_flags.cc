#include "build_flags.h"

#include <charconv>
#include <cmath>

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
  parser->AddString("hybrid-smoothing-info", &hybrid_smoothing_info_,
                    "information of hy's smoothing edges (SPEC §3.6): frontend (the front-end "
                    "edge's, as written), world (mapped into the body frame by the embedded "
                    "frame's adjoint: as strong as wc's), or SIGMA_R,SIGMA_T in rad and m "
                    "(DynoSAM: 0.01,0.1)",
                    "frontend|world|SR,ST");
}

std::vector<std::string> FormulationChoices() {
  std::vector<std::string> names;
  for (const FormulationInfo& info : Formulations()) names.push_back(info.name);
  return names;
}

namespace {

// "frontend", "world" or "SIGMA_R,SIGMA_T" (both positive and finite).
std::optional<std::string> ParseHybridSmoothingInfo(const std::string& text,
                                                    BuildOptions* options) {
  if (text == "frontend" || text == "world") {
    options->hybrid_smoothing_info =
        text == "world" ? HybridSmoothingInfo::kWorld : HybridSmoothingInfo::kFrontEnd;
    return std::nullopt;
  }
  const size_t comma = text.find(',');
  double sigmas[2];
  const std::string parts[2] = {text.substr(0, comma),
                                comma == std::string::npos ? "" : text.substr(comma + 1)};
  for (int i = 0; i < 2; ++i) {
    const char* begin = parts[i].data();
    const auto [end, ec] = std::from_chars(begin, begin + parts[i].size(), sigmas[i]);
    if (parts[i].empty() || ec != std::errc() || end != begin + parts[i].size() ||
        !(sigmas[i] > 0) || !std::isfinite(sigmas[i])) {
      return "--hybrid-smoothing-info: '" + text +
             "' is not frontend, world or two positive sigmas SIGMA_R,SIGMA_T";
    }
  }
  options->hybrid_smoothing_info = HybridSmoothingInfo::kSigmas;
  options->hybrid_smoothing_sigma_rotation = sigmas[0];
  options->hybrid_smoothing_sigma_translation = sigmas[1];
  return std::nullopt;
}

}  // namespace

std::optional<std::string> BuildFlags::Finish(BuildOptions* options) const {
  *options = defaults_;
  options->min_object_frames = static_cast<int>(min_object_frames_);
  ParseObjectInit(object_init_, &options->object_init);  // AddChoice admits only valid names
  options->motion_init = motion_init_ == "identity" ? MotionInit::kIdentity : MotionInit::kFrontEnd;
  options->kinematic_sigma = kinematic_sigma_;
  return ParseHybridSmoothingInfo(hybrid_smoothing_info_, options);
}

}  // namespace dynslam::cli
