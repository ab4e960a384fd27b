// SimulateOptionTable (simulate.h): every simulator setting as an option of options.h.
#include <sstream>

#include "dynslam/simulate.h"

namespace dynslam {
namespace {

// "A:B", "A:" or ":B" → [first, last); last −1 means the end.
std::optional<std::string> ParseFrames(const std::string& text, SimulateOptions* options) {
  const std::string form = "'" + text + "' is not A:B with A < B (A: and :B allowed)";
  const size_t colon = text.find(':');
  if (colon == std::string::npos) return form;
  int64_t first = 0, last = -1;
  const std::string a = text.substr(0, colon), b = text.substr(colon + 1);
  if (!a.empty() && ParseInteger(a, 0, INT64_MAX, &first)) return form;
  if (!b.empty() && ParseInteger(b, 1, INT64_MAX, &last)) return form;
  if (last >= 0 && last <= first) return form;
  options->first_frame = first;
  options->last_frame = last;
  return std::nullopt;
}

std::string FramesText(const SimulateOptions& options) {
  return std::to_string(options.first_frame) + ":" +
         (options.last_frame < 0 ? "" : std::to_string(options.last_frame));
}

Option<SimulateOptions> Frames() {
  Option<SimulateOptions> o = Declare<SimulateOptions>(
      "frames", "scene", OptionType::kText,
      "frame range A:B of the sequence, B exclusive (A: and :B allowed); a synthetic scene has "
      "synthetic_frames frames unless B is given",
      "A:B");
  o.get = FramesText;
  o.set = ParseFrames;
  return o;
}

Option<SimulateOptions> ObjectTypes() {
  Option<SimulateOptions> o = Declare<SimulateOptions>(
      "object_types", "density and visibility", OptionType::kText,
      "KITTI label types simulated as rigid objects, comma-separated", "TYPE,...");
  o.get = [](const SimulateOptions& options) {
    std::string text;
    for (const std::string& type : options.object_types) text += (text.empty() ? "" : ",") + type;
    return text;
  };
  o.set = [](const std::string& text, SimulateOptions* options) -> std::optional<std::string> {
    options->object_types.clear();
    std::stringstream in(text);
    for (std::string item; std::getline(in, item, ',');) {
      if (!item.empty()) options->object_types.push_back(item);
    }
    return std::nullopt;
  };
  return o;
}

}  // namespace

const OptionTable<SimulateOptions>& SimulateOptionTable() {
  using O = SimulateOptions;
  static const OptionTable<O> table = {
      Frames(),
      Integer("seed", "scene", &O::seed, "random seed (a seed gives the same files anywhere)", 0,
              INT64_MAX),
      Switch("synthetic", "scene", &O::synthetic, "a small hand-made scene, no KITTI data"),
      Integer("synthetic_frames", "scene", &O::synthetic_frames, "frames of the synthetic scene",
              2, 100000),
      Switch("noise", "noise", &O::noise,
             "draw noise; off: exact measurements and initial values (informations unchanged)"),
      Real("pixel_sigma", "noise", &O::pixel_sigma, "image noise, px", 1e-9, 1e6),
      Real("disparity_sigma", "noise", &O::disparity_sigma, "disparity noise, px", 1e-9, 1e6),
      Real("point_sigma_floor", "noise", &O::point_sigma_floor,
           "m, added in quadrature to each axis of a point's noise", 0, 1e6),
      Real("odometry_rotation_sigma", "noise", &O::odometry_rotation_sigma, "rad per frame",
           1e-12, 10),
      Real("odometry_translation_sigma", "noise", &O::odometry_translation_sigma, "m per frame",
           1e-12, 1e6),
      Real("motion_init_rotation_sigma", "noise", &O::motion_init_rotation_sigma,
           "rad, noise of the initial motions", 1e-12, 10),
      Real("motion_init_translation_sigma", "noise", &O::motion_init_translation_sigma,
           "m, noise of the initial motions", 1e-12, 1e6),
      Real("motion_sigma", "noise", &O::motion_sigma, "m, ternary motion edge (isotropic)", 1e-12,
           1e6),
      Real("smoothing_rotation_sigma", "noise", &O::smoothing_rotation_sigma,
           "rad, smoothing edge", 1e-12, 10),
      Real("smoothing_translation_sigma", "noise", &O::smoothing_translation_sigma,
           "m, smoothing edge", 1e-12, 1e6),
      Real("prior_sigma", "noise", &O::prior_sigma, "rad and m, prior on the first camera",
           1e-12, 1e6),
      Switch("noise_every_edge", "noise", &O::noise_every_edge,
             "also draw the prior, motion and smoothing edges' measurements from their "
             "information, around the truth"),
      Real("outlier_fraction", "noise", &O::outlier_fraction,
           "fraction of point observations with a gross error", 0, 1),
      Real("outlier_min", "noise", &O::outlier_min, "m, smallest gross error", 0, 1e6),
      Real("outlier_max", "noise", &O::outlier_max, "m, largest gross error", 0, 1e6),
      Aliased({"static_points_per_frame"},
              Integer("static_points", "density and visibility", &O::static_points_per_frame,
                      "tracked static points kept per frame", 0, 1000000)),
      Aliased({"dynamic_points_per_object"},
              Integer("dynamic_points", "density and visibility", &O::dynamic_points_per_object,
                      "tracked points kept per visible moving object", 0, 1000000)),
      Aliased({"static_break_probability"},
              Real("static_break", "density and visibility", &O::static_break_probability,
                   "probability per frame that a static track ends", 0, 1)),
      Aliased({"dynamic_break_probability"},
              Real("dynamic_break", "density and visibility", &O::dynamic_break_probability,
                   "probability per frame that a dynamic track ends", 0, 1)),
      Real("min_depth", "density and visibility", &O::min_depth, "m, nearest visible depth", 1e-3,
           1e6),
      Real("max_depth", "density and visibility", &O::max_depth, "m, farthest visible depth",
           1e-3, 1e6),
      Real("moving_min_extent", "density and visibility", &O::moving_min_extent,
           "m, an object is moving when its centre spans at least this ...", 0, 1e6),
      Real("moving_min_speed", "density and visibility", &O::moving_min_speed,
           "m/s, ... and reaches this speed over 1 s somewhere", 0, 1e6),
      ObjectTypes(),
  };
  return table;
}

}  // namespace dynslam
