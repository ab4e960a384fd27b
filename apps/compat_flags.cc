#include "compat_flags.h"

#include <sstream>

namespace dynslam::cli {
namespace {

void Huber(SolverOptions* options, EdgeKind kind, double threshold) {
  options->kernels[static_cast<int>(kind)] = {RobustKernel::Type::kHuber, threshold};
}

}  // namespace

CompatFlags::CompatFlags(ArgParser* parser) {
  parser->AddString("compat", &text_,
                    "the released code's choices (SPEC §7): dsc for all, or item numbers such as "
                    "1,3: 1 information unpermuted, 2 motion edge σ=0.1 Huber 1e-6 as m_prev-H⁻¹m_curr, "
                    "3 wc point edges Huber 1e-5, 4 identity initial motions, 5 object-centric "
                    "noise and first poses, 6 object motion residual without -m_L, 7 GTSAM LM "
                    "with the released stopping rule, 8 later object poses at their points' "
                    "centroid; or DynoSAM's for hy (SPEC §3.6): dynosam for all, or dynosam:LIST: "
                    "1 smoothing σ 0.01 rad 0.1 m at every frame, 2 Huber 1e-4 on hybrid point "
                    "edges, 3 embedded frame at the camera-frame mean of the measurements, 4 "
                    "points from their first measurement",
                    "none|dsc|LIST|dynosam[:LIST]");
}

namespace {

// "1,3" → items[1] = items[3] = true; an error unless every entry is a digit from 1 to size − 1.
std::optional<std::string> ParseItems(const std::string& text, bool* items, size_t size,
                                      const std::string& what) {
  std::stringstream list(text);
  for (std::string item; std::getline(list, item, ',');) {
    if (item.size() != 1 || item[0] < '1' || static_cast<size_t>(item[0] - '0') >= size) {
      return "--compat: '" + item + "' is not " + what;
    }
    items[item[0] - '0'] = true;
  }
  return std::nullopt;
}

}  // namespace

std::optional<std::string> CompatFlags::Finish() {
  item_.fill(false);
  dynosam_.fill(false);
  if (text_ == "none") return std::nullopt;
  if (text_ == "dsc") {
    item_.fill(true);
    return std::nullopt;
  }
  if (text_ == "dynosam") {
    dynosam_.fill(true);
    return std::nullopt;
  }
  if (text_.rfind("dynosam:", 0) == 0) {
    return ParseItems(text_.substr(8), dynosam_.data(), dynosam_.size(),
                      "a DynoSAM item number 1 to 4");
  }
  return ParseItems(text_, item_.data(), item_.size(),
                    "dsc, dynosam, none or an item number 1 to 8");
}

bool CompatFlags::any() const { return Describe() != "none"; }

std::string CompatFlags::Describe() const {
  std::string items;
  for (size_t i = 1; i < item_.size(); ++i) {
    if (item_[i]) items += (items.empty() ? "" : ",") + std::to_string(i);
  }
  std::string dynosam;
  for (size_t i = 1; i < dynosam_.size(); ++i) {
    if (dynosam_[i]) dynosam += (dynosam.empty() ? "dynosam:" : ",") + std::to_string(i);
  }
  if (!dynosam.empty()) items += (items.empty() ? "" : " ") + dynosam;
  return items.empty() ? "none" : items;
}

void CompatFlags::Apply(ReadOptions* options) const {
  options->information_in_tangent_order = item_[1];
}

void CompatFlags::Apply(BuildOptions* options) const {
  if (item_[4]) options->motion_init = MotionInit::kIdentity;
  options->dsc_object_centric_noise = item_[5];
  if (item_[8]) options->object_init = ObjectInit::kCentroid;
  options->dynosam_smoothing = dynosam_[1];
  options->dynosam_embedded_frame = dynosam_[3];
  options->dynosam_points_from_measurements = dynosam_[4];
}

void CompatFlags::Apply(bool world_centric, SolverOptions* options) const {
  if (item_[2]) {
    options->dsc_motion_residual = true;
    Huber(options, EdgeKind::kMotion, 1e-6);
  }
  if (item_[3] && world_centric) {
    Huber(options, EdgeKind::kPoint, 1e-5);
    Huber(options, EdgeKind::kDynamicPoint, 1e-5);
  }
  if (item_[5]) Huber(options, EdgeKind::kObjectMotion, 1e-3);
  options->dsc_object_motion_residual = item_[6];
  options->dsc_released_lm = item_[7];
  if (dynosam_[2]) Huber(options, EdgeKind::kHybridPoint, 1e-4);
}

}  // namespace dynslam::cli
